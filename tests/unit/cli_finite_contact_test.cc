// Contact at finite strain on the full path (Body n/Kinematics = finite
// with Contact/Enabled): homogeneous compressions that both discrete
// spaces (NURBS p = 2 and FE_Q(2) on boxes) contain exactly, so that the
// run must reproduce the closed forms of the compressible neo-Hookean law
// (neo_hookean_closed_forms.h) to the solver's tolerance:
// - a block pressed onto a frictionless rigid plane by moving its top face
//   down by 0.4: uniaxial stress, the stretch 0.6 along y and s across it
//   (zero lateral stress), the contact force the nominal stress times the
//   width;
// - two blocks of different stiffness, one on the other, frictionless,
//   pressed by 0.5 together: both in uniaxial stress with one nominal
//   stress, their stretches l1 + l2 = 1.5 with P(l1; E1) = P(l2; E2) (a
//   root found here by bisection). Their lateral stretches differ, so the
//   upper block's points slide over the lower one: pairs formed once hold
//   on the flat interface whatever the slide.
// A linearised body (a tangent that stays the small-strain one) or a gap
// of the reference configuration would miss these by far more than the
// tolerance. And the refusals of what the full path at finite strain
// cannot take.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include "neo_hookean_closed_forms.h"
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

// A named namespace: the unity build joins this file with others.
namespace cli_finite_contact
{
  using namespace neo_hookean_closed_forms;

  constexpr double nu = 0.3;

  std::string
  discretization(const std::string &type)
  {
    return "set Dimension = 2\nsubsection Discretization\n  set Type = " +
           type + "\n  set Degree = 2\n  set Refinements = 1\nend\n";
  }

  std::string
  block(const std::string &corners, const double E, const std::string &supports)
  {
    return "  set Geometry = box\n" + corners +
           "  set Young's modulus = " + std::to_string(E) +
           "\n  set Poisson's ratio = 0.3\n"
           "  set Kinematics = finite\n  set Material = neo-hookean\n"
           "  set Supports = " +
           supports + "\n";
  }

  const std::string solver = "  set Tolerance = 1e-12\n"
                             "  set Path = full\nend\n"
                             "subsection Load path\n"
                             "  set Number of steps = 4\nend\n";

  std::vector<double>
  values(const nlohmann::json &j)
  {
    return j.get<std::vector<double>>();
  }

  void
  expect_block_on_plane(const std::string &type)
  {
    SCOPED_TRACE(type);
    const double             E = 1000., stretch = 0.6;
    const cli::ScratchFolder scratch("finite-contact-plane-" + type);
    const nlohmann::json     summary = cli::run_scene_text(
      scratch,
      discretization(type) + "set Probe points = A: 0.8, 0.5\n" +
        "subsection Body 1\n" +
        block("  set Lower corner = 0, 0\n  set Upper corner = 1, 1\n",
              E,
              "0: x; 3: y=-0.4") +
        "end\nsubsection Body 2\n  set Type = rigid plane\n"
            "  set Plane point = 0, 0\n  set Plane normal = 0, 1\nend\n"
            "subsection Contact\n  set Enabled = true\n"
            "  set Friction coefficient = 0\n  set Slave face = 2\n" +
        solver);
    ASSERT_EQ(summary.at("status"), "ok");
    const double s = lateral_stretch(stretch, E, nu);
    // u = ((s - 1) X, (stretch - 1) Y).
    const auto a = values(summary.at("points").at("A"));
    EXPECT_NEAR(a[0], 0.8 * (s - 1.), 1e-9);
    EXPECT_NEAR(a[1], 0.5 * (stretch - 1.), 1e-9);
    // The plane pushes up with -P_22 over the reference width 1.
    const auto  &last  = summary.at("load_steps").back();
    const auto   force = values(last.at("total_contact_force"));
    const double P     = uniaxial_first_piola(stretch, E, nu);
    EXPECT_NEAR(force[0], 0., 1e-9 * E);
    EXPECT_NEAR(force[1], -P, 1e-9 * E);
    EXPECT_NEAR(last.at("finite_strain").at("min_det_F").get<double>(),
                stretch * s,
                1e-9);
  }

  void
  expect_block_on_block(const std::string &type)
  {
    SCOPED_TRACE(type);
    const double E1 = 1000., E2 = 3000., squeeze = 0.5;
    // l1 + l2 = 2 - squeeze and one nominal stress: P(l1; E1) - P(2 -
    // squeeze - l1; E2) grows with l1.
    double low = 1. - squeeze + 1e-9, high = 1.;
    for (unsigned int k = 0; k < 200; ++k)
      {
        const double l1 = 0.5 * (low + high);
        (uniaxial_first_piola(l1, E1, nu) <
             uniaxial_first_piola(2. - squeeze - l1, E2, nu) ?
           low :
           high)        = l1;
      }
    const double l1 = 0.5 * (low + high), l2 = 2. - squeeze - l1;
    const double s1 = lateral_stretch(l1, E1, nu),
                 s2 = lateral_stretch(l2, E2, nu);
    const double P  = uniaxial_first_piola(l1, E1, nu);

    const cli::ScratchFolder scratch("finite-contact-blocks-" + type);
    const nlohmann::json     summary = cli::run_scene_text(
      scratch,
      discretization(type) +
        "set Probe points = A: 0.8, 1.5; B: 0.8, 0.5\n"
            "subsection Body 1\n" +
        block("  set Lower corner = 0, 1\n  set Upper corner = 1, 2\n",
              E1,
              "0: x; 3: y=-0.5") +
        "end\nsubsection Body 2\n  set Type = deformable\n" +
        block("  set Lower corner = 0, 0\n  set Upper corner = 1, 1\n",
              E2,
              "0: x; 2: y") +
        "end\nsubsection Contact\n  set Enabled = true\n"
            "  set Friction coefficient = 0\n  set Slave face = 2\n"
            "  set Master face = 3\n" +
        solver);
    ASSERT_EQ(summary.at("status"), "ok");
    // Body 2: u = ((s2 - 1) X, (l2 - 1) Y); Body 1 on top of it: u_y =
    // (l2 - 1) + (l1 - 1) (Y - 1).
    const auto a = values(summary.at("points").at("A"));
    const auto b = values(summary.at("points").at("B"));
    EXPECT_NEAR(a[0], 0.8 * (s1 - 1.), 1e-9);
    EXPECT_NEAR(a[1], (l2 - 1.) + 0.5 * (l1 - 1.), 1e-9);
    EXPECT_NEAR(b[0], 0.8 * (s2 - 1.), 1e-9);
    EXPECT_NEAR(b[1], 0.5 * (l2 - 1.), 1e-9);
    const auto &last  = summary.at("load_steps").back();
    const auto  force = values(last.at("total_contact_force"));
    EXPECT_NEAR(force[1], -P, 1e-9 * E1);
    // The lower block's support carries the same force.
    const auto reaction =
      values(last.at("bodies").at(1).at("support_reaction"));
    EXPECT_NEAR(reaction[1], -P, 1e-9 * E1);
  }

  /// Refused with exit status 2 and one line containing @p expected.
  void
  expect_refused(const std::string &name,
                 const std::string &body,
                 const std::string &contact,
                 const std::string &expected)
  {
    SCOPED_TRACE(name);
    const cli::ScratchFolder scratch("finite-contact-refused-" + name);
    std::ofstream(cli::join(scratch.path, "scene.prm"))
      << "subsection Body 1\n"
      << block("", 1000., body) << "end\n"
      << "subsection Body 2\n  set Type = rigid plane\n"
         "  set Plane point = 0, -0.1\nend\n"
         "subsection Contact\n  set Enabled = true\n  set Slave face = 2\n"
      << contact << "end\n";
    cli::expect_refused("scene.prm --quiet --set 'Output/Directory=out'",
                        scratch,
                        expected);
  }
} // namespace cli_finite_contact

// (Qualified: the unity build joins the other command-line tests' names.)
TEST(CliFiniteContact, BlockOnRigidPlaneNurbs)
{
  cli_finite_contact::expect_block_on_plane("nurbs");
}

TEST(CliFiniteContact, BlockOnRigidPlaneLagrange)
{
  cli_finite_contact::expect_block_on_plane("lagrange");
}

TEST(CliFiniteContact, BlockOnBlockNurbs)
{
  cli_finite_contact::expect_block_on_block("nurbs");
}

TEST(CliFiniteContact, BlockOnBlockLagrange)
{
  cli_finite_contact::expect_block_on_block("lagrange");
}

TEST(CliFiniteContact, Refusals)
{
  cli_finite_contact::expect_refused("condensed",
                                     "3: y=-0.2",
                                     "  set Path = condensed\n",
                                     "set Contact/Path = full");
  // Held against its rigid motions by contact alone: small strain only,
  // refused when the supports have been analysed (the set-up's lines come
  // first), with exit status 2.
  const cli::ScratchFolder scratch("finite-contact-refused-floating");
  std::ofstream(cli::join(scratch.path, "scene.prm"))
    << "subsection Body 1\n"
    << cli_finite_contact::block("", 1000., "3: y") << "end\n"
    << "subsection Body 2\n  set Type = rigid plane\n"
       "  set Plane point = 0, -0.1\nend\n"
       "subsection Contact\n  set Enabled = true\n  set Slave face = 2\n"
       "  set Friction coefficient = 0\n  set Path = full\nend\n";
  const auto result =
    cli::run_igabde("scene.prm --quiet --set 'Output/Directory=out'", scratch);
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("held by contact alone against translation x"),
            std::string::npos)
    << result.output;
}
