// Body n/Face motions: a face moved rigidly, as a kinematic coupling moves
// it. With nu = 0 a beam clamped at x = 0 whose end face x = L is turned by
// theta about z (and lifted by theta L / 2) is in pure bending with
// curvature kappa = theta / L: u_x = -kappa x y, u_y = kappa x^2 / 2, the
// end face stays plane and turns rigidly, and the clamped face does not
// move. The quadratic field lies in both discrete spaces (NURBS p = 2 and
// FE_Q(2) on a box), so the interior displacement and the coupling's
// reaction (no force, the moment E I theta / L about the face's centroid)
// must equal the closed form to round-off. A body held by one face motion
// alone moves rigidly and carries nothing.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace
{
  constexpr double E = 1000., theta = 0.01, L = 4., h = 1., w = 0.5;

  /// "a, b[, c]" of the first @p dim values.
  std::string
  point(const unsigned int dim, const double a, const double b, const double c)
  {
    std::ostringstream s;
    s.precision(17);
    s << a << ", " << b;
    if (dim == 3)
      s << ", " << c;
    return s.str();
  }

  void
  expect_turned_end_bends_purely(const unsigned int dim,
                                 const std::string &type)
  {
    SCOPED_TRACE(std::to_string(dim) + "D " + type);
    const cli::ScratchFolder scratch("face-motion-" + std::to_string(dim) +
                                     type);
    // The end face's motion at displacement factor 1: lifted by theta L / 2,
    // turned by theta about z. Two steps: factors 0.5 and 1.
    std::ostringstream motion;
    motion.precision(17);
    motion << "1: 0, " << theta * L / 2 << (dim == 3 ? ", 0, 0, 0, " : ", ")
           << theta;
    const nlohmann::json summary = cli::run_scene_text(
      scratch,
      "set Dimension = " + std::to_string(dim) +
        "\nset Probe points = mid: " + point(dim, L / 2, h / 2, w / 2) +
        "\nsubsection Discretization\n  set Type = " + type +
        "\n  set Degree = 2\nend\nsubsection Body 1\n  set Geometry = box\n"
        "  set Lower corner = " +
        point(dim, 0, -h / 2, -w / 2) +
        "\n  set Upper corner = " + point(dim, L, h / 2, w / 2) +
        "\n  set Subdivisions = 4, 2" + (dim == 3 ? ", 1" : "") +
        "\n  set Young's modulus = " + std::to_string(E) +
        "\n  set Poisson's ratio = 0\n  set Supports = 0: x y" +
        (dim == 3 ? " z" : "") + "\n  set Face motions = " + motion.str() +
        "\nend\nsubsection Load path\n  set Load factors = 1, 1\n"
        "  set Displacement factors = 0.5, 1\nend\n");

    const double              kappa = theta / L, x = L / 2, y = h / 2;
    const std::vector<double> u = summary.at("points").at("mid");
    ASSERT_EQ(u.size(), dim);
    EXPECT_NEAR(u[0], -kappa * x * y, 1e-9 * theta * h);
    EXPECT_NEAR(u[1], kappa * x * x / 2, 1e-9 * theta * h);
    if (dim == 3)
      {
        EXPECT_NEAR(u[2], 0., 1e-9 * theta * h);
      }

    // Second moment of the section about z (per unit thickness in 2D).
    const double I      = (dim == 3 ? w : 1.) * h * h * h / 12.;
    const double moment = E * I * theta / L;
    const auto  &steps  = summary.at("load_steps");
    ASSERT_EQ(steps.size(), 2u);
    for (unsigned int s = 0; s < 2; ++s)
      {
        const double factor = (s == 0 ? 0.5 : 1.);
        const auto  &body   = steps[s].at("bodies").at(0);
        ASSERT_TRUE(body.contains("face_motion_reactions")) << body.dump();
        const auto &reaction = body.at("face_motion_reactions").at(0);
        EXPECT_EQ(reaction.at("face"), 1);
        const std::vector<double> force  = reaction.at("force");
        const std::vector<double> torque = reaction.at("moment");
        ASSERT_EQ(force.size(), dim);
        ASSERT_EQ(torque.size(), dim == 2 ? 1u : 3u);
        // Force scale: the bending stress's resultant over half the face.
        for (const double f : force)
          EXPECT_NEAR(f, 0., 1e-9 * moment / h);
        EXPECT_NEAR(torque.back(), factor * moment, 1e-9 * moment);
        for (unsigned int a = 0; a + 1 < torque.size(); ++a)
          EXPECT_NEAR(torque[a], 0., 1e-9 * moment);
      }

    // steps.csv carries the same reaction.
    std::ifstream csv(cli::join(scratch.path, "out/steps.csv"));
    std::string   header, row;
    std::getline(csv, header);
    std::getline(csv, row);
    std::getline(csv, row);
    const std::string column = "reaction_body1_face1_moment_z";
    const auto        at     = header.find(column);
    ASSERT_NE(at, std::string::npos) << header;
    const auto field = std::count(header.begin(), header.begin() + at, ',');
    std::stringstream cells(row);
    std::string       cell;
    for (long k = 0; k <= field; ++k)
      std::getline(cells, cell, ',');
    EXPECT_NEAR(std::stod(cell), moment, 1e-9 * moment) << header << "\n"
                                                        << row;
  }
} // namespace



TEST(CliFaceMotion, TurnedEndBendsANurbsBeamPurely2D)
{
  expect_turned_end_bends_purely(2, "nurbs");
}



TEST(CliFaceMotion, TurnedEndBendsAnFeQBeamPurely2D)
{
  expect_turned_end_bends_purely(2, "lagrange");
}



TEST(CliFaceMotion, TurnedEndBendsANurbsBeamPurely3D)
{
  expect_turned_end_bends_purely(3, "nurbs");
}



TEST(CliFaceMotion, TurnedEndBendsAnFeQBeamPurely3D)
{
  expect_turned_end_bends_purely(3, "lagrange");
}



namespace
{
  /**
   * A 3D box [0, 1] x [0, 2] x [0, 0.5] held only by the motion of its face
   * 4 (z = 0, centroid c = (0.5, 1, 0)) with every component non-zero:
   * the whole body follows u = d + r x (x - c) without strain, so the far
   * corner (1, 2, 0.5) moves by it and the coupling carries nothing.
   */
  void
  expect_rigid_motion(const std::string &type)
  {
    SCOPED_TRACE(type);
    const cli::ScratchFolder scratch("face-motion-rigid-" + type);
    const double d[3] = {0.01, -0.02, 0.03}, r[3] = {0.004, -0.003, 0.002};
    std::ostringstream motion;
    motion.precision(17);
    motion << "4: " << d[0] << ", " << d[1] << ", " << d[2] << ", " << r[0]
           << ", " << r[1] << ", " << r[2];
    const nlohmann::json summary = cli::run_scene_text(
      scratch,
      "set Dimension = 3\nset Probe points = far: 1, 2, 0.5\n"
      "subsection Discretization\n  set Type = " +
        type +
        "\n  set Degree = 2\nend\nsubsection Body 1\n  set Geometry = box\n"
        "  set Lower corner = 0, 0, 0\n  set Upper corner = 1, 2, 0.5\n"
        "  set Subdivisions = 2, 3, 1\n  set Young's modulus = 1000\n"
        "  set Poisson's ratio = 0.3\n  set Face motions = " +
        motion.str() + "\nend\n");
    const double              y[3] = {1. - 0.5, 2. - 1., 0.5 - 0.};
    const std::vector<double> u    = summary.at("points").at("far");
    ASSERT_EQ(u.size(), 3u);
    for (unsigned int a = 0; a < 3; ++a)
      {
        const double exact = d[a] + r[(a + 1) % 3] * y[(a + 2) % 3] -
                             r[(a + 2) % 3] * y[(a + 1) % 3];
        EXPECT_NEAR(u[a], exact, 1e-12) << "component " << a;
      }
    const auto &reaction = summary.at("load_steps")
                             .at(0)
                             .at("bodies")
                             .at(0)
                             .at("face_motion_reactions")
                             .at(0);
    // Scale: E times the largest rotation times the face's area.
    for (const char *key : {"force", "moment"})
      for (const double v : reaction.at(key).get<std::vector<double>>())
        EXPECT_NEAR(v, 0., 1e-9 * 1000. * 0.004 * 2.) << key;
  }
} // namespace



TEST(CliFaceMotion, OneMovedFaceCarriesANurbsBodyRigidly)
{
  expect_rigid_motion("nurbs");
}



TEST(CliFaceMotion, OneMovedFaceCarriesAnFeQBodyRigidly)
{
  expect_rigid_motion("lagrange");
}



TEST(CliFaceMotion, IncompleteOrConflictingMotionIsRefusedWhenRead)
{
  const cli::ScratchFolder scratch("face-motion-bad");
  const struct
  {
    std::string set, expected;
  } cases[] = {
    {"--set 'Body 1/Face motions=3: 0, 0'", "must give three values"},
    {"--set 'Body 1/Face motions=3: 0, 0, 0.01; 3: 0, 0, 0'", "moved twice"},
    {"--set 'Body 1/Face motions=3: 0, 0, 0.01' "
     "--set 'Body 1/Supports=3: y'",
     "is also in Supports"},
    {"--set 'Body 1/Face motions=7: 0, 0, 0.01'", "Face motions"},
  };
  for (const auto &c : cases)
    {
      const auto run =
        cli::run_prm_scene(scratch.path, "v3-contact-patch-2d.prm", c.set);
      EXPECT_EQ(run.status, 2) << c.set << "\n" << run.output;
      EXPECT_NE(run.output.find(c.expected), std::string::npos) << c.set << "\n"
                                                                << run.output;
      EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1)
        << c.set << "\n"
        << run.output;
    }
}
