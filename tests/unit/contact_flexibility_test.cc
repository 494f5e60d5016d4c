// The condensed flexibility F^L of a two-body problem where both bodies are
// fixed against rigid motion is symmetric and positive definite (Maxwell-
// Betti reciprocity and positive strain energy), for both discretisations
// and with and without friction; the Schur-complement condensation equals
// the per-column solves.

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

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



namespace
{
  /// The condensed flexibility W of the two blocks, formed with the given
  /// linear solver and, with @p schur, from the Schur complement on the
  /// contact face; also returns the asymmetry before symmetrisation.
  std::pair<Eigen::MatrixXd, double>
  condensed_flexibility(const discretization::Type         type,
                        const double                       mu,
                        const discretization::LinearSolver linear_solver,
                        const bool                         schur)
  {
    discretization::DiscretizationSettings settings;
    settings.type          = type;
    settings.degree        = 2;
    settings.linear_solver = linear_solver;
    std::vector<std::unique_ptr<discretization::Body<2>>> bodies;
    bodies.push_back(
      discretization::create_body<2>(block("upper", 0., 1.), settings));
    bodies.push_back(
      discretization::create_body<2>(block("lower", -1., 0.), settings));
    for (auto &body : bodies)
      {
        body->setup_system();
        EXPECT_TRUE(body->free_rigid_modes().empty());
      }

    contact::ContactSettings cs;
    cs.interactions[0].friction_coefficient = mu;
    cs.interactions[0].slave_faces          = {2};
    cs.interactions[0].master_faces         = {3};
    cs.schur_condensation                   = schur;
    cs.progress                             = false;
    std::ostringstream log;
    TimerOutput        timer(log, TimerOutput::never, TimerOutput::wall_times);
    contact::ContactStage<2> stage(cs, bodies, {}, log);
    stage.setup(timer);
    for (unsigned int b = 0; b < bodies.size(); ++b)
      EXPECT_EQ(bodies[b]->has_schur_complement(), schur);
    return {stage.condensed_problem().W, stage.flexibility_asymmetry()};
  }
} // namespace



TEST(ContactFlexibility, SymmetricPositiveDefiniteForFixedBodies)
{
  for (const auto type :
       {discretization::Type::nurbs, discretization::Type::lagrange})
    for (const double mu : {0., 0.3})
      {
        SCOPED_TRACE(to_string(type) + " mu=" + std::to_string(mu));
        // Per-column solves on UMFPACK's LU: the columns come from
        // independent solves, so only round-off can make W asymmetric.
        const auto [W, asymmetry] =
          condensed_flexibility(type,
                                mu,
                                discretization::LinearSolver::umfpack,
                                false);
        ASSERT_GT(W.rows(), 0);
        EXPECT_LT(asymmetry, 1e-10);
        // Positive definite: the smallest eigenvalue is positive relative
        // to the largest (well above round-off for these coarse meshes).
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(W);
        EXPECT_GT(eig.eigenvalues().minCoeff(),
                  1e-8 * eig.eigenvalues().maxCoeff());
        EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(W).info(), Eigen::Success);
      }
}



TEST(ContactFlexibility, SchurComplementEqualsColumnSolves)
{
  // F^L = C^T S^{-1} C from MUMPS' Schur complement on the face unknowns
  // against one UMFPACK LU solve per column: two independent factorisations
  // of the same K, so they agree to round-off times the condition number
  // of these small blocks (about 1e4): 1e-10 relative is a safe bound.
  for (const auto type :
       {discretization::Type::nurbs, discretization::Type::lagrange})
    for (const double mu : {0., 0.3})
      {
        SCOPED_TRACE(to_string(type) + " mu=" + std::to_string(mu));
        const auto [W_columns, a1] =
          condensed_flexibility(type,
                                mu,
                                discretization::LinearSolver::umfpack,
                                false);
        const auto [W_schur, a2] =
          condensed_flexibility(type,
                                mu,
                                discretization::LinearSolver::direct,
                                true);
        const auto [W_block, a3] =
          condensed_flexibility(type,
                                mu,
                                discretization::LinearSolver::direct,
                                false);
        ASSERT_EQ(W_columns.rows(), W_schur.rows());
        EXPECT_LT((W_schur - W_columns).norm(), 1e-10 * W_columns.norm());
        EXPECT_LT((W_block - W_columns).norm(), 1e-10 * W_columns.norm());
        EXPECT_EQ(a2, 0.); // C^T S^-1 C is symmetric by construction
      }
}
