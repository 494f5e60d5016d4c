// The condensed flexibility F^L of a two-body problem where both bodies are
// fixed against rigid motion is symmetric and positive definite (Maxwell-
// Betti reciprocity and positive strain energy), for both discretisations
// and with and without friction.

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>

#include <igabde/contact/contact_stage.h>

#include <deal.II/base/timer.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <sstream>

namespace
{
  using namespace igabde;
  using namespace dealii;

  discretization::BodyDescription<2>
  block(const std::string &name, const double y0, const double y1)
  {
    discretization::BodyDescription<2> d;
    d.name                    = name;
    d.material.youngs_modulus = 1000.;
    d.material.poisson_ratio  = 0.3;
    d.geometry = nurbs::make_box<2>(Point<2>(0., y0), Point<2>(1., y1));
    nurbs::elevate_to_degree(d.geometry, 2);
    nurbs::subdivide(d.geometry, std::array<unsigned int, 2>{{4, 2}});
    // Fixed: the far face clamped, so no rigid mode is left free.
    discretization::DirichletCondition<2> clamp;
    clamp.boundary_id   = (y0 < 0. ? 2 : 3);
    clamp.components[0] = clamp.components[1] = true;
    d.dirichlet.push_back(clamp);
    return d;
  }
} // namespace



TEST(ContactFlexibility, SymmetricPositiveDefiniteForFixedBodies)
{
  for (const std::string type : {"nurbs", "lagrange"})
    for (const double mu : {0., 0.3})
      {
        SCOPED_TRACE(type + " mu=" + std::to_string(mu));
        discretization::DiscretizationSettings settings;
        settings.type   = type;
        settings.degree = 2;
        std::vector<std::unique_ptr<discretization::Body<2>>> bodies;
        bodies.push_back(
          discretization::create_body<2>(block("upper", 0., 1.), settings));
        bodies.push_back(
          discretization::create_body<2>(block("lower", -1., 0.), settings));
        for (auto &body : bodies)
          {
            body->setup();
            ASSERT_TRUE(body->free_rigid_modes().empty());
          }

        contact::ContactSettings<2> cs;
        cs.friction_coefficient = mu;
        cs.slave_face           = 2;
        cs.master_face          = 3;
        std::ostringstream log;
        TimerOutput timer(log, TimerOutput::never, TimerOutput::wall_times);
        contact::ContactStage<2> stage(cs, bodies, log);
        stage.setup(timer);

        const Eigen::MatrixXd &W = stage.condensed_problem().W;
        ASSERT_GT(W.rows(), 0);
        EXPECT_EQ(W.rows(),
                  (mu > 0 ? 2 : 1) * stage.condensed_problem().n_contacts);
        // Symmetric before symmetrisation, to round-off (the columns come
        // from independent solves, so only round-off can differ).
        EXPECT_LT(stage.flexibility_asymmetry(), 1e-10);
        // Positive definite: the smallest eigenvalue is positive relative
        // to the largest (well above round-off for these coarse meshes).
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(W);
        EXPECT_GT(eig.eigenvalues().minCoeff(),
                  1e-8 * eig.eigenvalues().maxCoeff());
        EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(W).info(), Eigen::Success);
      }
}
