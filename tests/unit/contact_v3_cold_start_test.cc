// V3 (scenes.md) solved by the B-Newton from p = 0. The contact stage
// starts a first step from the bilateral solve over the pairs that touch,
// which is exact on V3 (the scene test converges after 0 iterations), so
// the scene alone never exercises the Newton iteration on this problem.
// Here the condensed V3 problem of the stage is solved again from zero
// contact forces (and the solver's own rigid-mode start): the B-Newton has
// to find the contact state itself.

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <igabde/contact/bnewton.h>
#include <igabde/contact/contact_solver.h>
#include <igabde/contact/contact_stage.h>

#include <deal.II/base/timer.h>

#include <gtest/gtest.h>

#include <sstream>

namespace
{
  using namespace igabde;
  using namespace dealii;

  /// A V3 block [0, 1] x [y0, y0 + 1], degree 2, 4 x 4 spans (the scene's
  /// base mesh after its 2 refinements), E = 1000, nu = 0.3, held in x on
  /// x = 0.
  discretization::BodyDescription<2>
  v3_block(const std::string &name, const double y0)
  {
    discretization::BodyDescription<2> d;
    d.name                    = name;
    d.material.youngs_modulus = 1000.;
    d.material.poisson_ratio  = 0.3;
    d.geometry = nurbs::make_box<2>(Point<2>(0., y0), Point<2>(1., y0 + 1.));
    nurbs::elevate_to_degree(d.geometry, 2);
    nurbs::subdivide(d.geometry, std::array<unsigned int, 2>{{4, 4}});
    discretization::DirichletCondition<2> roller;
    roller.boundary_id   = 0;
    roller.components[0] = true;
    d.dirichlet.push_back(roller);
    return d;
  }
} // namespace



TEST(ContactV3, BNewtonFromZeroForcesGivesTheUniformPressure)
{
  for (const auto type :
       {discretization::Type::nurbs, discretization::Type::lagrange})
    for (const double mu : {0., 0.3})
      {
        SCOPED_TRACE(to_string(type) + " mu=" + std::to_string(mu));
        // Upper block: pressure 1 on its top, held vertically only by the
        // contact. Lower block: also held in y at its bottom.
        auto                                upper = v3_block("upper", 0.);
        discretization::NeumannCondition<2> pressure;
        pressure.boundary_id = 3;
        pressure.traction    = [](const Point<2> &, const Tensor<1, 2> &n) {
          return -1. * n;
        };
        upper.tractions.push_back(pressure);
        auto                                  lower = v3_block("lower", -1.);
        discretization::DirichletCondition<2> bottom;
        bottom.boundary_id   = 2;
        bottom.components[1] = true;
        lower.dirichlet.push_back(bottom);

        discretization::DiscretizationSettings settings;
        settings.type   = type;
        settings.degree = 2;
        std::vector<std::unique_ptr<discretization::Body<2>>> bodies;
        bodies.push_back(discretization::create_body<2>(upper, settings));
        bodies.push_back(discretization::create_body<2>(lower, settings));
        for (auto &body : bodies)
          body->setup_system();
        ASSERT_EQ(bodies[0]->free_rigid_modes().size(), 1u);

        contact::ContactSettings cs;
        cs.interactions[0].friction_coefficient = mu;
        cs.interactions[0].slave_faces          = {2};
        cs.interactions[0].master_faces         = {3};
        cs.progress                             = false;
        std::ostringstream log;
        TimerOutput timer(log, TimerOutput::never, TimerOutput::wall_times);
        contact::ContactStage<2> stage(cs, bodies, {}, log);
        stage.setup(timer);

        // One load step through the stage sets q and b of the condensed
        // problem for load factor 1.
        std::vector<Vector<double>> u;
        for (const auto &body : bodies)
          u.push_back(body->load_solution());
        const auto step = stage.solve_step(1., u, timer);
        ASSERT_TRUE(step.converged) << step.diagnosis;
        const contact::ContactProblem &problem = stage.condensed_problem();
        const unsigned int             m       = stage.n_components();

        // The same problem from p = 0.
        const contact::BNewtonSolver solver(cs.solver.bnewton);
        const auto                   result =
          solver.solve(problem,
                       Eigen::VectorXd::Zero(problem.n_rows()),
                       Eigen::VectorXd());
        ASSERT_TRUE(result.converged) << result.diagnosis;
        // Not converged by construction: the start is not the answer.
        EXPECT_GT(result.iterations, 1u);

        // Exact (scenes.md V3): every pair carries the applied pressure 1
        // and no tangential force. The stopping test bounds the natural-map
        // residual by 1e-10 |q|; with the flexibility's condition number of
        // these small blocks (below 1e2) the forces are accurate to far
        // better than the scene criterion 1e-8.
        const auto &pairs = stage.pairs();
        ASSERT_EQ(static_cast<unsigned int>(result.p.size()), m * pairs.size());
        for (unsigned int i = 0; i < pairs.size(); ++i)
          {
            EXPECT_NEAR(result.p(m * i) / pairs[i].area, 1., 1e-8)
              << "pair " << i;
            for (unsigned int k = 1; k < m; ++k)
              EXPECT_NEAR(result.p(m * i + k) / pairs[i].area, 0., 1e-8)
                << "pair " << i;
          }
      }
}
