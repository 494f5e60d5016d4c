// Geometry files and expression loads from the command line: V2 exported
// with --export-geometry and read back as a file gives the built-in
// scene's figures; expression tractions give the support reactions of
// their hand-integrated resultants; bad geometry files and expressions are
// refused when the scene is read.
#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace
{
  nlohmann::json
  summary(const std::string &folder)
  {
    return nlohmann::json::parse(
      cli::read_file(cli::join(folder, "summary.json")));
  }

  /// Every number below @p a and @p b agrees to @p rtol of the largest
  /// number of that array or object.
  void
  expect_same_numbers(const nlohmann::json &a,
                      const nlohmann::json &b,
                      const double          rtol,
                      const std::string    &path = "")
  {
    ASSERT_EQ(a.type(), b.type()) << path;
    if (a.is_number())
      {
        EXPECT_NEAR(a.get<double>(),
                    b.get<double>(),
                    rtol * std::max(1., std::abs(a.get<double>())))
          << path;
        return;
      }
    if (a.is_array())
      {
        ASSERT_EQ(a.size(), b.size()) << path;
        double scale = 0.;
        for (const auto &x : a)
          if (x.is_number())
            scale = std::max(scale, std::abs(x.get<double>()));
        for (unsigned int i = 0; i < a.size(); ++i)
          if (a[i].is_number())
            EXPECT_NEAR(a[i].get<double>(), b[i].get<double>(), rtol * scale)
              << path << "[" << i << "]";
          else
            expect_same_numbers(a[i], b[i], rtol, path + "[]");
        return;
      }
    if (a.is_object())
      for (const auto &[key, value] : a.items())
        {
          ASSERT_TRUE(b.contains(key)) << path << "/" << key;
          expect_same_numbers(value, b.at(key), rtol, path + "/" + key);
        }
  }

  const std::string v2 =
    cli::join(cli::join(std::string(IGABDE_SOURCE_DIR), "prm"),
              "v2-lame-cylinder.prm");

  /// A 2D unit box held on its bottom face (face 2) and loaded on its top
  /// face (face 3), no contact.
  void
  write_box_scene(const std::string &path)
  {
    std::ofstream(path) << "set Dimension = 2\n"
                           "subsection Body 1\n"
                           "  set Subdivisions = 4\n"
                           "  set Supports     = 2: x y\n"
                           "end\n"
                           "subsection Body 2\n"
                           "  set Type = none\n"
                           "end\n"
                           "subsection Contact\n"
                           "  set Enabled = false\n"
                           "end\n"
                           "subsection Output\n"
                           "  set Write vtu = false\n"
                           "end\n";
  }

  /**
   * Runs the box scene @p scene with discretisation @p type and the
   * further --set @p setting into @p folder/@p out; returns the support
   * reaction of Body 1 at the first load step.
   */
  nlohmann::json
  first_step_reaction(const std::string &scene,
                      const std::string &type,
                      const std::string &setting,
                      const std::string &folder,
                      const std::string &out)
  {
    const auto r =
      cli::run_igabde("'" + scene + "' --quiet --set Discretization/Type=" +
                        type + " --set '" + setting +
                        "' --set Output/Directory=" + out,
                      folder);
    EXPECT_EQ(r.status, 0) << r.output;
    if (r.status != 0)
      return nlohmann::json::array({0., 0.});
    return summary(cli::join(folder, out))
      .at("load_steps")[0]
      .at("bodies")[0]
      .at("support_reaction");
  }

} // namespace



TEST(CliGeometryFile, ExportedV2ReadBackGivesTheSameFigures)
{
  for (const std::string type : {"nurbs", "lagrange"})
    {
      SCOPED_TRACE(type);
      const cli::ScratchFolder folder("geometry-v2-" + type);
      const std::string set_type = " --quiet --set Discretization/Type=" + type;
      const auto        built_in = cli::run_igabde("'" + v2 + "'" + set_type +
                                              " --export-geometry --set "
                                                     "Output/Directory=built-in",
                                            folder);
      ASSERT_EQ(built_in.status, 0) << built_in.output;
      const std::string file =
        cli::join(folder.path, "built-in/body1-geometry.xml");
      ASSERT_TRUE(std::filesystem::exists(file));
      EXPECT_TRUE(std::filesystem::exists(
        cli::join(folder.path, "built-in/body1-control-net.vtu")));
      // The exported patch is already refined: no refinement on top.
      const auto from_file = cli::run_igabde(
        "'" + v2 + "'" + set_type +
          " --set 'Body 1/Geometry=file' --set 'Body 1/Geometry file=" + file +
          "' --set Discretization/Refinements=0 --set "
          "Output/Directory=from-file",
        folder);
      ASSERT_EQ(from_file.status, 0) << from_file.output;
      const nlohmann::json a = summary(cli::join(folder.path, "built-in"));
      const nlohmann::json b = summary(cli::join(folder.path, "from-file"));
      EXPECT_EQ(a.at("n_dofs"), b.at("n_dofs"));
      EXPECT_EQ(b.at("bodies")[0].at("geometry"), file);
      for (const std::string key : {"points", "point_stresses", "checks"})
        if (a.contains(key))
          expect_same_numbers(a.at(key), b.at(key), 1e-12, key);
      // The quarter annulus 1 <= r <= 2: area 3 pi / 4.
      EXPECT_NEAR(b.at("bodies")[0].at("measure").get<double>(),
                  3. * M_PI / 4.,
                  1e-12);
      EXPECT_EQ(b.at("bodies")[0].at("patches"), 1);
    }
}



TEST(CliGeometryFile, PlanarFileStoredIn3dSpaceGivesTheSameFigures)
{
  // V2's exported quarter annulus rewritten as G+Smo stores planar
  // surfaces (geoDim = 3, a zero z on every row): the 2D scene reads it,
  // says so in one info line, and gives the built-in geometry's figures.
  const cli::ScratchFolder folder("geometry-planar-3d");
  const auto               built_in = cli::run_igabde("'" + v2 +
                                          "' --quiet --export-geometry --set "
                                                        "Output/Directory=built-in",
                                        folder);
  ASSERT_EQ(built_in.status, 0) << built_in.output;
  std::istringstream in(
    cli::read_file(cli::join(folder.path, "built-in/body1-geometry.xml")));
  std::string line, planar;
  bool        in_coefs = false;
  while (std::getline(in, line))
    {
      if (line.find("<coefs") != std::string::npos)
        {
          const auto at = line.find("geoDim=\"2\"");
          ASSERT_NE(at, std::string::npos) << line;
          line.replace(at, 10, "geoDim=\"3\"");
          in_coefs = true;
        }
      else if (line.find("</coefs>") != std::string::npos)
        in_coefs = false;
      else if (in_coefs && !line.empty())
        line += " 0";
      planar += line + "\n";
    }
  const std::string file = cli::join(folder.path, "planar.xml");
  std::ofstream(file) << planar;
  const auto from_file = cli::run_igabde(
    "'" + v2 +
      "' --set 'Body 1/Geometry=file' --set 'Body 1/Geometry file=" + file +
      "' --set Discretization/Refinements=0 --set 'Output/Print "
      "timing=false' --set Output/Directory=from-file",
    folder);
  ASSERT_EQ(from_file.status, 0) << from_file.output;
  EXPECT_NE(from_file.output.find("info: " + file +
                                  ": patch id 0: stored in 3D space "
                                  "(geoDim = 3) with every z zero"),
            std::string::npos)
    << from_file.output;
  const nlohmann::json a = summary(cli::join(folder.path, "built-in"));
  const nlohmann::json b = summary(cli::join(folder.path, "from-file"));
  EXPECT_EQ(a.at("n_dofs"), b.at("n_dofs"));
  for (const std::string key : {"points", "point_stresses", "checks"})
    if (a.contains(key))
      expect_same_numbers(a.at(key), b.at(key), 1e-12, key);
}



TEST(CliGeometryFile, RelativePathsAreFoundFromTheSceneFolder)
{
  const cli::ScratchFolder folder("geometry-relative");
  ASSERT_EQ(cli::run_igabde("'" + v2 +
                              "' --quiet --export-geometry --set "
                              "Output/Directory=scenes/parts",
                            folder)
              .status,
            0);
  // The scene in scenes/, the file in scenes/parts/; run from elsewhere.
  std::filesystem::copy_file(v2, cli::join(folder.path, "scenes/v2.prm"));
  const auto result =
    cli::run_igabde("'" + cli::join(folder.path, "scenes/v2.prm") +
                      "' --quiet --set 'Body 1/Geometry=file' --set 'Body "
                      "1/Geometry file=parts/body1-geometry.xml' --set "
                      "Discretization/Refinements=0 --set "
                      "Output/Directory=out",
                    cli::join(folder.path, "elsewhere"));
  EXPECT_EQ(result.status, 0) << result.output;
}



TEST(CliExpressionLoads, ReactionsMatchTheHandIntegratedResultant)
{
  const cli::ScratchFolder folder("expression-loads");
  const std::string        scene = cli::join(folder.path, "box.prm");
  write_box_scene(scene);

  // t = (10 x, -100 x) on the top face 0 <= x <= 1: resultant (5, -50),
  // so the support reaction is (-5, 50). Both discretisations integrate
  // a linear traction exactly.
  for (const std::string type : {"nurbs", "lagrange"})
    {
      const auto reaction =
        first_step_reaction(scene,
                            type,
                            "Body 1/Tractions=3: function 10*x; -100*x",
                            folder,
                            "linear-" + type);
      EXPECT_NEAR(reaction[0].get<double>(), -5., 1e-10);
      EXPECT_NEAR(reaction[1].get<double>(), 50., 1e-10);
    }

  // A t-dependent traction -100 t^2 x over three steps (t = 1/3, 2/3, 1):
  // the reaction 50 t^2 at each step (not 50 t^2 scaled by t again, and
  // not a straight line between steps).
  const auto r = cli::run_igabde(
    "'" + scene +
      "' --quiet --set 'Body 1/Tractions=3: function 0; -100*t^2*x' --set "
      "'Load path/Number of steps=3' --set Output/Directory=quadratic",
    folder);
  ASSERT_EQ(r.status, 0) << r.output;
  const auto steps =
    summary(cli::join(folder.path, "quadratic")).at("load_steps");
  ASSERT_EQ(steps.size(), 3u);
  for (unsigned int s = 0; s < 3; ++s)
    {
      const double t = (s + 1) / 3.;
      EXPECT_NEAR(
        steps[s].at("bodies")[0].at("support_reaction")[1].get<double>(),
        50. * t * t,
        1e-10);
    }
  // The per-step histories stay internal: steps.csv has the user's columns.
  const std::string csv =
    cli::read_file(cli::join(folder.path, "quadratic/steps.csv"));
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "step,load_factor,displacement_factor");
}



TEST(CliGeometryFile, BadGeometryFilesAndExpressionsAreRefusedWhenRead)
{
  const cli::ScratchFolder folder("geometry-bad-input");
  const std::string        scene = cli::join(folder.path, "box.prm");
  write_box_scene(scene);
  const std::string run = "'" + scene + "' --set Output/Directory=out ";

  cli::expect_refused(run + "--set 'Body 1/Geometry=file'",
                      folder,
                      "Body 1/Geometry file is empty");
  cli::expect_refused(run + "--set 'Body 1/Geometry=file' --set 'Body "
                            "1/Geometry file=nowhere.xml'",
                      folder,
                      "no such file");

  // Two patches that no interface joins: not one body.
  std::ofstream(cli::join(folder.path, "two.xml"))
    << "<xml>\n"
       "<Geometry type=\"TensorBSpline2\" id=\"0\"><Basis "
       "type=\"TensorBSplineBasis2\"><Basis type=\"BSplineBasis\" "
       "index=\"0\"><KnotVector degree=\"1\">0 0 1 1</KnotVector></Basis>"
       "<Basis type=\"BSplineBasis\" index=\"1\"><KnotVector degree=\"1\">0 "
       "0 1 1</KnotVector></Basis></Basis><coefs geoDim=\"2\">0 0 1 0 0 1 1 "
       "1</coefs></Geometry>\n"
       "<Geometry type=\"TensorBSpline2\" id=\"1\"><Basis "
       "type=\"TensorBSplineBasis2\"><Basis type=\"BSplineBasis\" "
       "index=\"0\"><KnotVector degree=\"1\">0 0 1 1</KnotVector></Basis>"
       "<Basis type=\"BSplineBasis\" index=\"1\"><KnotVector degree=\"1\">0 "
       "0 1 1</KnotVector></Basis></Basis><coefs geoDim=\"2\">1 0 2 0 1 1 2 "
       "1</coefs></Geometry>\n"
       "</xml>\n";
  cli::expect_refused(run + "--set 'Body 1/Geometry=file' --set 'Body "
                            "1/Geometry file=two.xml'",
                      folder,
                      "no interface joins patch 1 to patch 0");

  cli::expect_refused(run + "--set 'Body 1/Tractions=3: function -100*x'",
                      folder,
                      "has 1 expressions; give 2");
  cli::expect_refused(run + "--set 'Body 1/Tractions=3: function 0; -100*q'",
                      folder,
                      "cannot evaluate");
  EXPECT_FALSE(std::filesystem::exists(cli::join(folder.path, "out")));
}



TEST(CliExpressionLoads, LinearPrescribedFieldIsReproducedInside)
{
  // u = A x with constant A is an exact elasticity solution without body
  // force; prescribed on every face of a graded box, both discretisations
  // (which contain the linear fields) must give it back inside.
  const cli::ScratchFolder folder("expression-supports");
  const std::string        scene = cli::join(folder.path, "box.prm");
  write_box_scene(scene);
  std::string supports;
  for (const std::string face : {"0", "1", "2", "3"})
    supports += face + ": x = function 0.001*x+0.002*y; " + face +
                ": y = function -0.003*x+0.0015*y; ";
  for (const std::string type : {"nurbs", "lagrange"})
    {
      SCOPED_TRACE(type);
      const auto r = cli::run_igabde(
        "'" + scene + "' --quiet --set Discretization/Type=" + type +
          " --set 'Body 1/Subdivisions=3, 4' --set 'Body 1/Grading=0: 5' "
          "--set 'Body 1/Supports=" +
          supports +
          "' --set 'Probe points=p: 0.3, 0.7' --set Output/Directory=" + type,
        folder);
      ASSERT_EQ(r.status, 0) << r.output;
      const auto p = summary(cli::join(folder.path, type)).at("points").at("p");
      EXPECT_NEAR(p[0].get<double>(), 0.001 * 0.3 + 0.002 * 0.7, 1e-12);
      EXPECT_NEAR(p[1].get<double>(), -0.003 * 0.3 + 0.0015 * 0.7, 1e-12);
    }
}



TEST(CliExpressionLoads, BodyForceFieldReactionIsItsIntegral)
{
  // f = (0, -100 x) on the unit box held at its bottom: the support
  // reaction is -int f = (0, 50).
  const cli::ScratchFolder folder("expression-body-force");
  const std::string        scene = cli::join(folder.path, "box.prm");
  write_box_scene(scene);
  for (const std::string type : {"nurbs", "lagrange"})
    {
      const auto reaction =
        first_step_reaction(scene,
                            type,
                            "Body 1/Body force=function 0; -100*x",
                            folder,
                            type);
      EXPECT_NEAR(reaction[0].get<double>(), 0., 1e-10);
      EXPECT_NEAR(reaction[1].get<double>(), 50., 1e-10);
    }
  const std::string run =
    "'" + scene + "' --set Output/Directory=refused --set ";
  cli::expect_refused(run + "'Body 1/Body force=function 0; -100*t'",
                      folder,
                      "Body force uses t");
  cli::expect_refused(run + "'Body 1/Supports=2: x y; 3: y = function 0.1*t'",
                      folder,
                      "uses t");
}
