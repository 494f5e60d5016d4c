// Body n/Kinematics = finite: homogeneous deformations, which both discrete
// spaces (NURBS p = 2 and FE_Q(2) on a box) contain exactly, so that the
// run must reproduce the closed forms of the compressible neo-Hookean law
// W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2 to the Newton
// tolerance:
// - uniaxial stretch to lambda = 2 in plane strain (F = diag(2, s), the
//   lateral stretch s the root of mu (s^2 - 1) + lambda ln(2 s) = 0 where
//   S_22 = 0), prescribed as a displacement and, separately, reached under
//   the dead traction P_11 that it takes;
// - simple shear gamma = 1 (F = I + gamma e_x (x) e_y, J = 1: sigma = mu
//   (b - I), sigma_xx = mu gamma^2, sigma_xy = mu gamma, sigma_yy = 0);
// - a rigid rotation by 90 degrees imposed through Face motions (2D about
//   z, 3D about y): the displacement R (X - c) - (X - c) + d and zero
//   stress, with det F = 1.
// And the refusals at read time of what a finite-strain body cannot take.
// Contact at finite strain: cli_finite_contact_test.cc.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include "neo_hookean_closed_forms.h"
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

// A named namespace: the unity build joins this file with others.
namespace cli_finite_strain
{
  constexpr double E = 1000., nu = 0.3;
  const double     mu       = E / (2. * (1. + nu));
  const double     lambda_L = E * nu / ((1. + nu) * (1. - 2. * nu));

  /// The scene's text of a finite-strain neo-Hookean box.
  std::string
  scene(const std::string &type,
        const unsigned int dim,
        const std::string &body,
        const std::string &probes,
        const unsigned int steps)
  {
    return "set Dimension = " + std::to_string(dim) +
           "\nset Probe points = " + probes +
           "\nsubsection Discretization\n  set Type = " + type +
           "\n  set Degree = 2\n  set Refinements = 1\nend\n"
           "subsection Body 1\n  set Geometry = box\n"
           "  set Young's modulus = 1000\n  set Poisson's ratio = 0.3\n"
           "  set Kinematics = finite\n  set Material = neo-hookean\n" +
           body +
           "end\nsubsection Nonlinear solver\n  set Tolerance = 1e-13\nend\n"
           "subsection Load path\n  set Number of steps = " +
           std::to_string(steps) + "\nend\n";
  }

  /// The lateral stretch and P_11 of plane-strain uniaxial stretch to
  /// @p stretch (neo_hookean_closed_forms.h).
  double
  lateral_stretch(const double stretch)
  {
    return neo_hookean_closed_forms::lateral_stretch(stretch, E, nu);
  }

  double
  first_piola(const double stretch)
  {
    return neo_hookean_closed_forms::uniaxial_first_piola(stretch, E, nu);
  }

  std::vector<double>
  values(const nlohmann::json &j)
  {
    return j.get<std::vector<double>>();
  }

  void
  expect_uniaxial_stretch(const std::string &type, const bool by_traction)
  {
    SCOPED_TRACE(type + (by_traction ? " under a dead traction" :
                                       " by a prescribed displacement"));
    const cli::ScratchFolder scratch("finite-uniaxial-" + type +
                                     (by_traction ? "-traction" : ""));
    std::ostringstream       load;
    load.precision(17);
    if (by_traction)
      load << "  set Supports = 0: x; 2: y\n  set Tractions = 1: vector "
           << first_piola(2.) << ", 0\n";
    else
      load << "  set Supports = 0: x; 2: y; 1: x=1\n";
    const nlohmann::json summary = cli::run_scene_text(
      scratch,
      scene(type, 2, load.str(), "A: 1, 1; B: 0.3, 0.6", 4));
    const double s = lateral_stretch(2.);
    // u = (X, (s - 1) Y) everywhere.
    const auto a = values(summary.at("points").at("A"));
    const auto b = values(summary.at("points").at("B"));
    EXPECT_NEAR(a[0], 1., 1e-10);
    EXPECT_NEAR(a[1], s - 1., 1e-10);
    EXPECT_NEAR(b[0], 0.3, 1e-10);
    EXPECT_NEAR(b[1], 0.6 * (s - 1.), 1e-10);
    // sigma_11 = P_11 lambda / J = P_11 / s, the rest zero; sigma_33 =
    // lambda_L ln J / J; det F = 2 s; the largest stretch 2.
    const auto &stress = summary.at("point_stresses").at("B");
    const auto  sigma  = values(stress.at("stress"));
    EXPECT_NEAR(sigma[0], first_piola(2.) / s, 1e-10 * E);
    EXPECT_NEAR(sigma[1], 0., 1e-10 * E);
    EXPECT_NEAR(sigma[2], 0., 1e-10 * E);
    EXPECT_NEAR(stress.at("stress_zz").get<double>(),
                lambda_L * std::log(2. * s) / (2. * s),
                1e-10 * E);
    EXPECT_NEAR(stress.at("det_F").get<double>(), 2. * s, 1e-10);
    EXPECT_NEAR(stress.at("largest_stretch").get<double>(), 2., 1e-10);
    const auto &steps = summary.at("load_steps");
    ASSERT_EQ(steps.size(), 4u);
    for (const auto &step : steps)
      EXPECT_LE(step.at("finite_strain").at("residual").get<double>(), 1e-13);
  }

  void
  expect_simple_shear(const std::string &type)
  {
    SCOPED_TRACE(type);
    const cli::ScratchFolder scratch("finite-shear-" + type);
    const double             gamma = 1.;
    // u = (gamma y, 0) on the whole boundary.
    const std::string body =
      "  set Supports = 0: x = function y; 0: y; 1: x = function y; 1: y; "
      "2: x y; 3: x=1 y\n";
    const nlohmann::json summary =
      cli::run_scene_text(scratch, scene(type, 2, body, "B: 0.3, 0.6", 2));
    const auto b = values(summary.at("points").at("B"));
    EXPECT_NEAR(b[0], gamma * 0.6, 1e-10);
    EXPECT_NEAR(b[1], 0., 1e-10);
    const auto &stress = summary.at("point_stresses").at("B");
    const auto  sigma  = values(stress.at("stress"));
    EXPECT_NEAR(sigma[0], mu * gamma * gamma, 1e-10 * E);
    EXPECT_NEAR(sigma[1], mu * gamma, 1e-10 * E);
    EXPECT_NEAR(sigma[2], 0., 1e-10 * E);
    EXPECT_NEAR(stress.at("stress_zz").get<double>(), 0., 1e-10 * E);
    EXPECT_NEAR(stress.at("det_F").get<double>(), 1., 1e-10);
  }

  void
  expect_rigid_rotation(const std::string &type, const unsigned int dim)
  {
    SCOPED_TRACE(type + " " + std::to_string(dim) + "D");
    const cli::ScratchFolder scratch("finite-rotation-" + type +
                                     std::to_string(dim));
    // Face 0 (X = 0) of [0, 2] x [0, 1] (x [0, 1]) turned by 90 degrees
    // about its centroid c and moved by d; the body follows rigidly.
    const double      quarter = std::acos(0.);
    std::stringstream motion;
    motion.precision(17);
    if (dim == 2)
      motion << "  set Face motions = 0: 0.1, 0.2, " << quarter << "\n";
    else
      motion << "  set Face motions = 0: 0.1, 0.2, 0.3, 0, " << quarter
             << ", 0\n";
    const std::string body = std::string("  set Upper corner = ") +
                             (dim == 2 ? "2, 1" : "2, 1, 1") + "\n" +
                             motion.str();
    const nlohmann::json summary = cli::run_scene_text(
      scratch,
      scene(type, dim, body, dim == 2 ? "A: 2, 1" : "A: 2, 1, 0.25", 4));
    // X - c of A, turned: 2D about z, (2, 0.5) -> (-0.5, 2); 3D about y,
    // (2, 0.5, -0.25) -> (-0.25, 0.5, -2).
    const auto a = values(summary.at("points").at("A"));
    if (dim == 2)
      {
        EXPECT_NEAR(a[0], 0.1 - 0.5 - 2., 1e-10);
        EXPECT_NEAR(a[1], 0.2 + 2. - 0.5, 1e-10);
      }
    else
      {
        EXPECT_NEAR(a[0], 0.1 - 0.25 - 2., 1e-10);
        EXPECT_NEAR(a[1], 0.2 + 0.5 - 0.5, 1e-10);
        EXPECT_NEAR(a[2], 0.3 - 2. + 0.25, 1e-10);
      }
    const auto &stress = summary.at("point_stresses").at("A");
    for (const double sigma : values(stress.at("stress")))
      EXPECT_NEAR(sigma, 0., 1e-10 * E);
    EXPECT_NEAR(stress.at("det_F").get<double>(), 1., 1e-10);
    EXPECT_NEAR(stress.at("largest_stretch").get<double>(), 1., 1e-10);
    // The coupling carries nothing.
    const auto &reaction = summary.at("load_steps")
                             .back()
                             .at("bodies")
                             .at(0)
                             .at("face_motion_reactions")
                             .at(0);
    for (const double f : values(reaction.at("force")))
      EXPECT_NEAR(f, 0., 1e-10 * E);
    for (const double m : values(reaction.at("moment")))
      EXPECT_NEAR(m, 0., 1e-10 * E);
  }

  void
  expect_follower_pressure_compresses(const std::string &type)
  {
    SCOPED_TRACE(type);
    const cli::ScratchFolder scratch("finite-follower-" + type);
    // A pressure p on the faces x = 1 and y = 1 of the quarter [0, 1]^2 of
    // a block (symmetry supports): F = s I with sigma = -p I on the
    // current surface, mu (s^2 - 1) / s^2 + lambda ln(s^2) / s^2 = -p (J =
    // s^2). A dead load -p N on the reference surface would give the
    // Cauchy stress -p / s instead.
    const double         p       = 200.;
    const nlohmann::json summary = cli::run_scene_text(
      scratch,
      scene(type,
            2,
            "  set Supports = 0: x; 2: y\n  set Tractions = 1: "
            "pressure 200; 3: pressure 200\n",
            "A: 1, 1; B: 0.3, 0.6",
            2));
    double low = 0.1, high = 1.;
    for (unsigned int k = 0; k < 200; ++k)
      {
        const double s = 0.5 * (low + high);
        (mu * (s * s - 1.) + lambda_L * std::log(s * s) < -p * s * s ? low :
                                                                       high) =
          s;
      }
    const double s = 0.5 * (low + high);
    const auto   a = values(summary.at("points").at("A"));
    EXPECT_NEAR(a[0], s - 1., 1e-10);
    EXPECT_NEAR(a[1], s - 1., 1e-10);
    const auto sigma =
      values(summary.at("point_stresses").at("B").at("stress"));
    EXPECT_NEAR(sigma[0], -p, 1e-10 * E);
    EXPECT_NEAR(sigma[1], 0., 1e-10 * E);
    EXPECT_NEAR(sigma[2], -p, 1e-10 * E);
    // The supports balance the pressure's resultant on the current faces,
    // -p s per face in x and in y: they push with p s.
    const auto reaction = values(summary.at("load_steps")
                                   .back()
                                   .at("bodies")
                                   .at(0)
                                   .at("support_reaction"));
    EXPECT_NEAR(reaction[0], p * s, 1e-10 * E);
    EXPECT_NEAR(reaction[1], p * s, 1e-10 * E);
  }

  /// The scene is refused at read time with exit status 2 and one line
  /// that contains @p expected.
  void
  expect_refused(const std::string &name,
                 const std::string &body,
                 const std::string &more,
                 const std::string &expected)
  {
    SCOPED_TRACE(name);
    const cli::ScratchFolder scratch("finite-refused-" + name);
    std::ofstream(cli::join(scratch.path, "scene.prm"))
      << "subsection Body 1\n  set Geometry = box\n  set Supports = 0: x "
         "y\n"
      << body << "end\n"
      << more;
    cli::expect_refused("scene.prm --quiet --set 'Output/Directory=out'",
                        scratch,
                        expected);
  }
} // namespace cli_finite_strain

using namespace cli_finite_strain;



TEST(CliFiniteStrain, UniaxialStretchToTwoNurbs)
{
  expect_uniaxial_stretch("nurbs", false);
  expect_uniaxial_stretch("nurbs", true);
}

TEST(CliFiniteStrain, UniaxialStretchToTwoLagrange)
{
  expect_uniaxial_stretch("lagrange", false);
  expect_uniaxial_stretch("lagrange", true);
}

TEST(CliFiniteStrain, FollowerPressureCompressesHomogeneously)
{
  expect_follower_pressure_compresses("nurbs");
  expect_follower_pressure_compresses("lagrange");
}

TEST(CliFiniteStrain, SimpleShearOfOne)
{
  expect_simple_shear("nurbs");
  expect_simple_shear("lagrange");
}

TEST(CliFiniteStrain, RigidRotationByNinetyDegrees2D)
{
  expect_rigid_rotation("nurbs", 2);
  expect_rigid_rotation("lagrange", 2);
}

TEST(CliFiniteStrain, RigidRotationByNinetyDegrees3D)
{
  expect_rigid_rotation("nurbs", 3);
  expect_rigid_rotation("lagrange", 3);
}

TEST(CliFiniteStrain, RefusedAtReadTime)
{
  const std::string finite = "  set Kinematics = finite\n";
  expect_refused("linear-law",
                 finite,
                 "",
                 "Body 1/Kinematics = finite needs a finite-strain law");
  expect_refused("finite-law-small",
                 "  set Material = neo-hookean\n",
                 "",
                 "Body 1/Material = neo-hookean is a finite-strain law");
  const std::string neo_hookean = finite + "  set Material = neo-hookean\n";
  expect_refused("plane-stress",
                 neo_hookean,
                 "set Plane model = plane stress\n",
                 "has no plane-stress form");
  expect_refused("hold-rotation",
                 neo_hookean + "  set Hold rotation = 0\n",
                 "",
                 "Hold rotation holds the mean small rotation");
  expect_refused("contact-condensed",
                 neo_hookean,
                 "subsection Body 2\n  set Type = rigid plane\nend\n"
                 "subsection Contact\n  set Enabled = true\n"
                 "  set Path = condensed\nend\n",
                 "set Contact/Path = full");
  expect_refused("contact-gmres-amg",
                 neo_hookean,
                 "subsection Body 2\n  set Type = rigid plane\nend\n"
                 "subsection Contact\n  set Enabled = true\n"
                 "  set Full system solver = gmres-amg\nend\n",
                 "Full system solver = gmres-amg");
  expect_refused("unknown-law",
                 finite + "  set Material = mooney-rivlin\n",
                 "",
                 "Material");
}
