// Contact/Pairing = weighted-gap: the contact patch test (V3 of scenes.md)
// on non-matching meshes. Two blocks stacked with zero gap, rollers only,
// the upper block pressed by a uniform pressure 1 and held vertically only
// by the contact. The exact solution is a uniaxial stress state in both
// blocks: it lies in both discrete spaces (linear displacements), its
// relative displacement across the interface vanishes everywhere, and its
// contact pressure is 1 at every point. Weighted-gap pairs (one per basis
// function of the slave face, integrated against the master basis with the
// slave elements cut at the master element edges) transmit it exactly, so
// every pair's pressure (force / tributary area int N_j dGamma) is 1 and
// its tangential force 0, to the solver's accuracy: the tolerance 1e-6 of
// the issue is far above it (B-Newton residual 1e-10 |q|, flexibility
// condition numbers below 1e3 on these blocks).
//
// Cases: slave (upper) 2x2 on master 3x3 and 3x3 on 2x2, 2D and 3D, NURBS
// p = 2 and FE_Q(2), mu = 0 and 0.3, the gap weighted by the dual basis
// psi_j (Pairing = weighted-gap) and by N_j (weighted-gap-standard). The
// node-to-surface pairs of the same meshes are solved beside them and their
// error printed (doc/verification.md quotes it); they are not exact, which the
// test checks too, so that the weighted-gap result cannot come from a
// configuration where any pairing passes (except NURBS slave 3 on master 2,
// where a symmetry makes them exact: derived below and checked as well).

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <igabde/contact/contact_stage.h>

#include <deal.II/base/timer.h>

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace
{
  using namespace igabde;
  using namespace dealii;

  /// A V3 block of n spans per direction, degree 2, E = 1000, nu = 0.3:
  /// [0, 1]^dim shifted by @p shift in the last direction, held normal to
  /// its faces x = 0 (and y = 0 in 3D).
  template <int dim>
  discretization::BodyDescription<dim>
  v3_block(const std::string &name, const double shift, const unsigned int n)
  {
    discretization::BodyDescription<dim> d;
    d.name                    = name;
    d.material.youngs_modulus = 1000.;
    d.material.poisson_ratio  = 0.3;
    Point<dim> lo, hi;
    for (unsigned int c = 0; c < dim; ++c)
      hi[c] = 1.;
    lo[dim - 1] += shift;
    hi[dim - 1] += shift;
    d.geometry = nurbs::make_box<dim>(lo, hi);
    nurbs::elevate_to_degree(d.geometry, 2);
    std::array<unsigned int, dim> spans;
    spans.fill(n);
    nurbs::subdivide(d.geometry, spans);
    for (unsigned int c = 0; c + 1 < dim; ++c)
      {
        discretization::DirichletCondition<dim> roller;
        roller.boundary_id   = 2 * c;
        roller.components[c] = true;
        d.dirichlet.push_back(roller);
      }
    return d;
  }

  /// Largest |p_n / A - 1| and |p_t| / A over the pairs.
  struct PatchResult
  {
    double       normal_error     = 0.;
    double       tangential_error = 0.;
    unsigned int n_pairs          = 0;
  };

  template <int dim>
  PatchResult
  patch_test(const discretization::Type type,
             const contact::Pairing     pairing,
             const unsigned int         n_slave,
             const unsigned int         n_master,
             const double               mu)
  {
    auto upper = v3_block<dim>("upper", 0., n_slave);
    discretization::NeumannCondition<dim> pressure;
    pressure.boundary_id = 2 * dim - 1;
    pressure.traction    = [](const Point<dim> &, const Tensor<1, dim> &n) {
      return -1. * n;
    };
    upper.tractions.push_back(pressure);
    auto lower = v3_block<dim>("lower", -1., n_master);
    discretization::DirichletCondition<dim> bottom;
    bottom.boundary_id         = 2 * (dim - 1);
    bottom.components[dim - 1] = true;
    lower.dirichlet.push_back(bottom);

    discretization::DiscretizationSettings settings;
    settings.type   = type;
    settings.degree = 2;
    std::vector<std::unique_ptr<discretization::Body<dim>>> bodies;
    bodies.push_back(discretization::create_body<dim>(upper, settings));
    bodies.push_back(discretization::create_body<dim>(lower, settings));
    for (auto &body : bodies)
      body->setup_system();

    contact::ContactSettings cs;
    cs.interactions[0].friction_coefficient = mu;
    cs.interactions[0].slave_faces          = {2 * (dim - 1)};
    cs.interactions[0].master_faces         = {2 * (dim - 1) + 1};
    cs.interactions[0].pairing              = pairing;
    cs.progress                             = false;
    std::ostringstream log;
    TimerOutput        timer(log, TimerOutput::never, TimerOutput::wall_times);
    contact::ContactStage<dim> stage(cs, bodies, {}, log);
    stage.setup(timer);
    std::vector<Vector<double>> u;
    for (const auto &body : bodies)
      u.push_back(body->load_solution());
    const auto step = stage.solve_step(1., u, timer);
    EXPECT_TRUE(step.converged) << step.diagnosis;

    const auto        &pairs = stage.pairs();
    const auto        &p     = stage.forces();
    const unsigned int m     = stage.n_components();
    PatchResult        result;
    result.n_pairs = pairs.size();
    for (unsigned int i = 0; i < pairs.size(); ++i)
      {
        result.normal_error = std::max(result.normal_error,
                                       std::abs(p(m * i) / pairs[i].area - 1.));
        double t            = 0.;
        for (unsigned int k = 1; k < m; ++k)
          t += p(m * i + k) * p(m * i + k);
        result.tangential_error =
          std::max(result.tangential_error, std::sqrt(t) / pairs[i].area);
      }
    return result;
  }

  template <int dim>
  void
  run_cases()
  {
    for (const auto type :
         {discretization::Type::nurbs, discretization::Type::lagrange})
      for (const auto &[n_slave, n_master] :
           {std::pair<unsigned int, unsigned int>{2, 3}, {3, 2}})
        for (const double mu : {0., 0.3})
          {
            std::ostringstream name;
            name << dim << "D " << to_string(type) << " slave " << n_slave
                 << " on master " << n_master << " mu=" << mu;
            SCOPED_TRACE(name.str());
            const auto closest =
              patch_test<dim>(type,
                              contact::Pairing::node_to_surface,
                              n_slave,
                              n_master,
                              mu);
            // Both weightings of the gap (the dual basis psi_j, the
            // default, and N_j itself) sum to one over the face.
            for (const contact::Pairing pairing :
                 {contact::Pairing::weighted_gap,
                  contact::Pairing::weighted_gap_standard})
              {
                SCOPED_TRACE(contact::to_string(pairing));
                const auto weighted =
                  patch_test<dim>(type, pairing, n_slave, n_master, mu);
                std::cout << "[ patch    ] " << name.str() << ": "
                          << contact::to_string(pairing) << " "
                          << weighted.n_pairs << " pairs, max |p/A - 1| "
                          << std::scientific << std::setprecision(2)
                          << weighted.normal_error << ", max |p_t|/A "
                          << weighted.tangential_error << std::defaultfloat
                          << std::endl;
                EXPECT_LE(weighted.normal_error, 1e-6);
                EXPECT_LE(weighted.tangential_error, 1e-6);
                // The slave face's trace space: (n (p = 2) + 2)^(dim-1)
                // functions for NURBS, (2 n + 1)^(dim-1) nodes for FE_Q(2).
                const unsigned int per_direction =
                  (type == discretization::Type::nurbs ? n_slave + 2 :
                                                         2 * n_slave + 1);
                EXPECT_EQ(weighted.n_pairs,
                          static_cast<unsigned int>(
                            std::pow(per_direction, dim - 1)));
              }
            std::cout << "[ patch    ] " << name.str() << ": node-to-surface "
                      << closest.n_pairs << " pairs, max |p/A - 1| "
                      << std::scientific << std::setprecision(2)
                      << closest.normal_error << ", max |p_t|/A "
                      << closest.tangential_error << std::defaultfloat
                      << std::endl;
            // Point pairs miss the patch test where the master's space is
            // not integrated exactly by the slave's pair rule (points x_i,
            // weights A_i): the master then receives sum_i R_B(x_i) A_i
            // instead of int R_B. The exception, derived by hand: NURBS
            // slave 3 on master 2. The rule on the Greville abscissae 0,
            // 1/6, 1/2, 5/6, 1 integrates the slave's splines, hence all
            // quadratics; the master's space is the quadratics plus
            // (x - 1/2)_+^2, and the rule and the integral are both
            // symmetric about 1/2 while (x - 1/2)_+^2 + (1/2 - x)_+^2 is a
            // quadratic, so that function is integrated exactly too (in 3D
            // the rule is the tensor product). There node-to-surface passes.
            // FE_Q(2) slave 3 on master 2 fails: Simpson's rule on the
            // middle third misses the master's kink at 1/2.
            if (type == discretization::Type::nurbs && n_slave == 3 &&
                n_master == 2)
              EXPECT_LE(closest.normal_error, 1e-6);
            else
              EXPECT_GT(closest.normal_error, 1e-3);
          }
  }
} // namespace



TEST(ContactWeightedGap, PatchTestOnNonMatchingMeshes2D)
{
  run_cases<2>();
}



TEST(ContactWeightedGap, PatchTestOnNonMatchingMeshes3D)
{
  run_cases<3>();
}



// The same patch test through the scene file and the command line, as a user
// selects it: prm/v3-contact-patch-2d.prm (2D NURBS, degree 2) with
// Contact/Pairing = weighted-gap and 2 spans on 3, mu = 0.3, and the 3D scene
// with FE_Q(2), 2 spans on 3 (node-to-surface misses both by 15-52 %). The
// scene's own check, summary.json's checks.pressure_uniformity = max_i |p_i / p
// - 1| against the applied pressure 1, must be at most 1e-6.
TEST(ContactWeightedGap, PatchTestFromTheSceneFile)
{
  struct Case
  {
    std::string scene, type, slave, master;
  };
  for (const Case &c : {Case{"v3-contact-patch-2d.prm", "nurbs", "2", "3"},
                        Case{"v3-contact-patch-3d.prm", "lagrange", "2", "3"}})
    {
      SCOPED_TRACE(c.scene);
      const cli::ScratchFolder scratch("weighted-gap", "wg");
      const std::string        scene =
        cli::join(std::string(IGABDE_SOURCE_DIR), "prm/" + c.scene);
      const auto run = cli::run_igabde(
        "'" + scene +
          "' --quiet --set 'Contact/Pairing=weighted-gap'"
          " --set 'Contact/Friction coefficient=0.3'"
          " --set 'Discretization/Type=" +
          c.type +
          "' --set 'Discretization/Refinements=0'"
          " --set 'Body 1/Subdivisions=" +
          c.slave + "' --set 'Body 2/Subdivisions=" + c.master +
          "' --set 'Output/Directory=out' --set 'Output/Write vtu=false'",
        scratch.path);
      ASSERT_EQ(run.status, 0) << run.output;
      const auto summary = nlohmann::json::parse(
        cli::read_file(cli::join(scratch.path, "out/summary.json")));
      EXPECT_LE(summary.at("checks").at("pressure_uniformity").get<double>(),
                1e-6);
      // One pair per basis function of the slave face: NURBS p = 2 on 2
      // spans has 4, FE_Q(2) on 2 x 2 cells 5 x 5.
      EXPECT_EQ(summary.at("n_contact_pairs").get<unsigned int>(),
                c.type == "nurbs" ? 4u : 25u);
    }
}

// The dual-weighted gap int psi_j g / int N_j of a curved face touching the
// other in the middle of a knot span is negative though the bodies do not
// overlap (psi_j has negative lobes; V6's half disc on 29 spans: -0.0033).
// Overlap is judged on the pointwise gap: that run goes on, and its contact
// force balances the load (60 on the disc's diameter); a disc moved 0.01
// into the block is refused with its pointwise gap.
TEST(ContactWeightedGap, CurvedFaceTouchingMidSpanIsNotAnOverlap)
{
  const std::string scene =
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/v6-cylinder-on-block.prm");
  const std::string coarse = "' --quiet --set 'Body 1/Subdivisions=29, 4'"
                             " --set 'Body 2/Subdivisions=35, 8'"
                             " --set 'Output/Directory=out'";
  {
    const cli::ScratchFolder scratch("weighted-gap", "midspan");
    const auto run = cli::run_igabde("'" + scene + coarse, scratch.path);
    ASSERT_EQ(run.status, 0) << run.output;
    const auto summary = nlohmann::json::parse(
      cli::read_file(cli::join(scratch.path, "out/summary.json")));
    EXPECT_EQ(summary.at("status").get<std::string>(), "ok");
    const auto force = summary.at("total_contact_force");
    EXPECT_NEAR(force.at(1).get<double>(), 60., 60. * 1e-8);
    EXPECT_NEAR(force.at(0).get<double>(), 0., 60. * 1e-8);
  }
  {
    const cli::ScratchFolder scratch("weighted-gap", "overlap");
    const auto               run =
      cli::run_igabde("'" + scene + coarse + " --set 'Body 1/Centre=0, 7.99'",
                      scratch.path);
    EXPECT_EQ(run.status, 2) << run.output;
    // The pointwise gap at the quadrature points: negative, and no deeper
    // than the 0.01 the disc was moved (its lowest point, x = 0, need not
    // be a quadrature point).
    const std::string message = "initially penetrates body2's face 3 (gap ";
    const auto        at      = run.output.find(message);
    ASSERT_NE(at, std::string::npos) << run.output;
    const double gap = std::stod(run.output.substr(at + message.size()));
    EXPECT_LT(gap, 0.);
    EXPECT_GE(gap, -0.01 * (1. + 1e-9));
  }
}
