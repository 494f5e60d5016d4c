// Values no body can have are refused when the scene is read (ctest label
// bad-input): exit status 2, one line naming the file and the parameter,
// nothing set up and nothing written. Before the body grammar moved into
// the parameters, E = 0, nu = 0.5, nu = -1 and a face the geometry does not
// have were found during set-up (exit status 1, a failed summary.json and
// the scene banner on screen).

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <filesystem>
#include <fstream>
#include <string>

namespace
{
  /**
   * Runs the V3 2D scene (a contact scene: both bodies, both contact faces)
   * with one override and checks the parse-time refusal: status 2, one
   * line starting "igabde: error: <scene file>: " and naming @p parameter,
   * no scene banner, no output folder, hence no summary.json and no VTU.
   */
  void
  expect_refused_at_parse_time(
    const std::string &name,
    const std::string &setting,
    const std::string &parameter,
    const std::string &scene_name      = "v3-contact-patch-2d.prm",
    const std::string &extra_arguments = "")
  {
    SCOPED_TRACE(setting);
    const cli::ScratchFolder folder("bad-input-" + name);
    const std::string        scene =
      cli::join(cli::join(std::string(IGABDE_SOURCE_DIR), "prm"), scene_name);
    const auto result =
      cli::run_igabde("'" + scene + "' --set \"" + setting +
                        "\" --set 'Output/Directory=out' " + extra_arguments,
                      folder);
    EXPECT_EQ(result.status, 2) << result.output;
    // One line, the error itself.
    EXPECT_EQ(result.output.find('\n'), result.output.size() - 1)
      << result.output;
    EXPECT_EQ(result.output.rfind("igabde: error: " + scene + ": ", 0), 0u)
      << result.output;
    EXPECT_NE(result.output.find(parameter), std::string::npos)
      << result.output;
    // Nothing was set up: no banner, no output folder.
    EXPECT_EQ(result.output.find("Scene "), std::string::npos) << result.output;
    EXPECT_FALSE(
      std::filesystem::exists(cli::join(folder.path, "out/summary.json")));
    EXPECT_FALSE(std::filesystem::exists(
      cli::join(folder.path, "out/solution-body1-0001.vtu")));
    EXPECT_FALSE(std::filesystem::exists(cli::join(folder.path, "out")));
  }
} // namespace



TEST(CliBadInput, ZeroYoungsModulus)
{
  expect_refused_at_parse_time("e0",
                               "Body 1/Young's modulus=0",
                               "Body 1/Young's modulus = 0 must be > 0");
}



TEST(CliBadInput, PoissonRatioAtOneHalf)
{
  expect_refused_at_parse_time("nu05",
                               "Body 2/Poisson's ratio=0.5",
                               "Body 2/Poisson's ratio = 0.5 must lie in "
                               "-1 < nu < 0.5");
}



TEST(CliBadInput, PoissonRatioAtMinusOne)
{
  expect_refused_at_parse_time("nu-1",
                               "Body 1/Poisson's ratio=-1",
                               "Body 1/Poisson's ratio = -1 must lie in "
                               "-1 < nu < 0.5");
}



TEST(CliBadInput, NegativeFrictionCoefficient)
{
  expect_refused_at_parse_time("mu",
                               "Contact/Friction coefficient=-0.1",
                               "Contact/Friction coefficient");
}



TEST(CliBadInput, SupportOnAFaceTheGeometryDoesNotHave)
{
  // A 2D box has faces 0..3; face 4 exists only in 3D.
  expect_refused_at_parse_time("support-face",
                               "Body 2/Supports=0: x; 4: y",
                               "Body 2/Supports: face '4' in '4: y' must be "
                               "a patch face 0..3");
}



TEST(CliBadInput, TractionOnAFaceTheGeometryDoesNotHave)
{
  expect_refused_at_parse_time("traction-face",
                               "Body 1/Tractions=5: pressure 1",
                               "Body 1/Tractions: face '5' in '5: pressure "
                               "1' must be a patch face 0..3");
}



TEST(CliBadInput, ContactFaceTheGeometryDoesNotHave)
{
  expect_refused_at_parse_time("contact-face",
                               "Contact/Master face=4",
                               "Contact/Master face (Body 2): face '4' must "
                               "be a patch face 0..3");
}



TEST(CliBadInput, SupportComponentOutsideTheDimension)
{
  expect_refused_at_parse_time("component",
                               "Body 1/Supports=0: z",
                               "Body 1/Supports: 'z' in '0: z' is not a "
                               "component");
}



TEST(CliBadInput, SceneBeyondTheMachinesMemory)
{
  // V3 at 12 refinements: about 5e8 unknowns and terabytes of factor. The
  // size guard stops it before anything is built, with the estimate, the
  // largest refinement that fits and the way past the guard.
  expect_refused_at_parse_time("too-large",
                               "Discretization/Refinements=12",
                               "needs more memory than the machine has free");
  expect_refused_at_parse_time("too-large-2",
                               "Discretization/Refinements=12",
                               "igabde --force runs it anyway");
}



TEST(CliBadInput, MisspelledParameterInSetWithDidYouMean)
{
  expect_refused_at_parse_time("misspelled",
                               "Body 1/Youngs modulus=5",
                               "Did you mean 'Body 1/Young's modulus'?");
  expect_refused_at_parse_time("misspelled-section",
                               "Bdy 1/Poisson's ratio=0.2",
                               "Did you mean 'Body 1/Poisson's ratio'?");
}



TEST(CliBadInput, WrongTypeNamesTheExpectedPattern)
{
  expect_refused_at_parse_time("type",
                               "Body 1/Young's modulus=abc",
                               "does not match the given pattern");
}



TEST(CliBadInput, DegreeOutsideOneToSix)
{
  expect_refused_at_parse_time("degree0",
                               "Discretization/Degree=0",
                               "Integer range 1...6");
  expect_refused_at_parse_time("degree30",
                               "Discretization/Degree=30",
                               "Integer range 1...6");
}



TEST(CliBadInput, NotANumberOrInfinite)
{
  expect_refused_at_parse_time("nan",
                               "Body 1/Young's modulus=nan",
                               "Body 1/Young's modulus=nan");
  expect_refused_at_parse_time("inf",
                               "Body 1/Upper corner=1, inf",
                               "Body 1/Upper corner: 'inf' is not a number");
  expect_refused_at_parse_time("inf-mu",
                               "Contact/Friction coefficient=inf",
                               "Contact/Friction coefficient=inf");
}



TEST(CliBadInput, InnerRadiusNotBelowOuter)
{
  expect_refused_at_parse_time("radii",
                               "Body 1/Inner radius=3",
                               "Body 1/Inner radius (3.000000) must be smaller "
                               "than Outer radius",
                               "v2-lame-cylinder.prm");
}



TEST(CliBadInput, PointLoadOutsideTheBody)
{
  // Found during set-up before (exit status 1, a failed summary.json).
  expect_refused_at_parse_time("point-load",
                               "Body 1/Point loads=100, 100 : 0, -1",
                               "Body 1/Point loads: the point (100 100) is not "
                               "in the body");
}



TEST(CliBadInput, SubdivisionsOutOfRange)
{
  expect_refused_at_parse_time("subdivisions",
                               "Body 1/Subdivisions=0, 2",
                               "counts must be integers from 1 to 9999");
}



TEST(CliBadInput, OutputSubdivisionsNeitherAutoNorOneToSixteen)
{
  for (const char *value : {"0", "17", "four", "2.5"})
    expect_refused_at_parse_time(
      "output-subdivisions",
      std::string("Discretization/Output subdivisions=") + value,
      "Output subdivisions = '" + std::string(value) +
        "': write 'auto' or a whole number");
}



TEST(CliBadInput, MomentWithTheWrongNumberOfComponentsOrFace)
{
  expect_refused_at_parse_time("moment-components",
                               "Body 1/Moments=1: 1, 2",
                               "Moments: '1: 1, 2' must give one value");
  expect_refused_at_parse_time("moment-face",
                               "Body 1/Moments=7: 1",
                               "Moments: face '7' in '7: 1' must be a patch "
                               "face");
}



TEST(CliBadInput, UnwritableOutputDirectory)
{
  // A folder below a regular file cannot be created.
  const cli::ScratchFolder folder("bad-input-output");
  std::ofstream(cli::join(folder.path, "file")) << "x";
  const std::string scene =
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/v3-contact-patch-2d.prm");
  const auto result =
    cli::run_igabde("'" + scene + "' --set 'Output/Directory=file/out'",
                    folder);
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_EQ(result.output.find('\n'), result.output.size() - 1)
    << result.output;
  EXPECT_NE(result.output.find("Output/Directory = 'file/out' cannot be "
                               "created"),
            std::string::npos)
    << result.output;
}



TEST(CliBadInput, ContactToleranceAndRScaleNotPositive)
{
  // Refused by the contact solver's constructor before (exit status 1, a
  // failed summary.json naming no parameter).
  expect_refused_at_parse_time("tolerance0",
                               "Contact/Tolerance=0",
                               "Contact/Tolerance = 0 must be > 0");
  expect_refused_at_parse_time("rscale0",
                               "Contact/r scale=0",
                               "Contact/r scale = 0 must be > 0");
}



TEST(CliBadInput, ZeroPlaneNormal)
{
  expect_refused_at_parse_time("plane-normal",
                               "Body 2/Plane normal=0, 0",
                               "Body 2/Plane normal = '0, 0' must not be "
                               "zero",
                               "v5-hertz-2d.prm");
  expect_refused_at_parse_time("plane-normal-components",
                               "Body 2/Plane normal=1",
                               "Body 2/Plane normal: '1' must have 2 "
                               "comma-separated components",
                               "v5-hertz-2d.prm");
}



TEST(CliBadInput, BodyWithoutAnySupport)
{
  // Found after assembly before ("body1 is not held against translation x
  // and the scene has no contact").
  expect_refused_at_parse_time("no-support",
                               "Body 1/Supports=",
                               "Body 1/Supports is empty and the scene has "
                               "no contact",
                               "v1-plate-with-hole.prm");
  // Two bodies in contact with each other and nothing else: the contact
  // solver failed to converge, with a long diagnosis, before.
  expect_refused_at_parse_time("no-support-pair",
                               "Body 1/Supports=",
                               "Body 1/Supports and Body 2/Supports are both "
                               "empty",
                               "v3-contact-patch-2d.prm",
                               "--set 'Body 2/Supports='");
}



TEST(CliBadInput, LoadHistoryWithoutAName)
{
  expect_refused_at_parse_time("history-name",
                               "Load path/Histories=: 1, 1, 1, 1, 1",
                               "Load path/Histories: ': 1, 1, 1, 1, 1' has "
                               "no name",
                               "load-histories-block.prm");
}



TEST(CliBadInput, UnreadableSceneMarksItsOutputFolderFailed)
{
  // A finished run leaves status "ok"; a scene that cannot be read into the
  // same folder (named by --set or by the scene's Output section) must not
  // leave it there.
  const cli::ScratchFolder folder("bad-input-stale-ok");
  const std::string        scene =
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/v3-contact-patch-2d.prm");
  const std::string summary = cli::join(folder.path, "out/summary.json");
  const auto        ok      = cli::run_igabde(
    "'" + scene +
      "' --quiet --set 'Output/Directory=out' --set 'Output/Write vtu=false'",
    folder);
  ASSERT_EQ(ok.status, 0) << ok.output;
  ASSERT_NE(cli::read_file(summary).find("\"status\": \"ok\""),
            std::string::npos);

  const auto bad = cli::run_igabde("'" + scene +
                                     "' --set 'Output/Directory=out' "
                                     "--set 'Contact/r scale=0'",
                                   folder);
  EXPECT_EQ(bad.status, 2) << bad.output;
  std::string text = cli::read_file(summary);
  EXPECT_NE(text.find("\"status\": \"failed\""), std::string::npos) << text;
  EXPECT_EQ(text.find("\"ok\""), std::string::npos) << text;
  EXPECT_NE(text.find("Contact/r scale = 0 must be > 0"), std::string::npos)
    << text;

  // The folder named by the scene itself, and a malformed value.
  std::ofstream(cli::join(folder.path, "own.prm"))
    << "include " << scene << "\n"
    << "subsection Output\n  set Directory = out\nend\n"
    << "subsection Body 1\n  set Young's modulus = abc\nend\n";
  std::ofstream(summary) << "{\n  \"status\": \"ok\"\n}\n";
  const auto own = cli::run_igabde("own.prm", folder);
  EXPECT_EQ(own.status, 2) << own.output;
  text = cli::read_file(summary);
  EXPECT_NE(text.find("\"status\": \"failed\""), std::string::npos) << text;
  EXPECT_NE(text.find("Young's modulus"), std::string::npos) << text;

  // A folder that does not exist is not created.
  const auto elsewhere = cli::run_igabde("'" + scene +
                                           "' --set 'Output/Directory=new' "
                                           "--set 'Contact/r scale=0'",
                                         folder);
  EXPECT_EQ(elsewhere.status, 2) << elsewhere.output;
  EXPECT_FALSE(std::filesystem::exists(cli::join(folder.path, "new")));
}



TEST(CliBadInput, ProbeWithTheWrongNumberOfCoordinates)
{
  expect_refused_at_parse_time("probe-syntax",
                               "Probe points=a: 1",
                               "Probe points: 'a: 1' needs 2 coordinates");
}



TEST(CliBadInput, ProbeOutsideEveryBodyRefusedBeforeTheSolve)
{
  // Found when the bodies are built, before anything is factorised or
  // solved (after the solve, before): exit status 2, one error line, no
  // load step.
  const cli::ScratchFolder folder("bad-input-probe-outside");
  const std::string        scene =
    cli::join(std::string(IGABDE_SOURCE_DIR), "prm/v3-contact-patch-2d.prm");
  const auto result = cli::run_igabde("'" + scene +
                                        "' --set 'Probe points=far: 5, 5' "
                                        "--set 'Output/Directory=out'",
                                      folder);
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("Probe points: 'far: 5, 5' lies in no body"),
            std::string::npos)
    << result.output;
  EXPECT_EQ(result.output.find("Load step"), std::string::npos)
    << result.output;
}



TEST(CliBadInput, NinthBodySaysHowManyBodiesThereAre)
{
  // deal.II's own text was "Line <n> of file <f>: There is no such
  // subsection to be entered: Body 9".
  const cli::ScratchFolder folder("bad-input-body-9");
  const std::string        scene = cli::join(folder.path, "nine.prm");
  {
    std::ofstream out(scene);
    out << "set Dimension = 2\nsubsection Body 9\n  set Radius = 1\nend\n";
  }
  const auto result = cli::run_igabde("'" + scene + "'", folder);
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("there is no section 'Body 9' (line 2): "
                               "igabde models up to 8 bodies"),
            std::string::npos)
    << result.output;
  EXPECT_EQ(result.output.find("There is no such subsection"),
            std::string::npos)
    << result.output;
}



TEST(CliBadInput, HoldRotationOnAMissingFaceOrOnTheFullPath)
{
  expect_refused_at_parse_time("hold-face",
                               "Body 1/Hold rotation=7",
                               "Body 1/Hold rotation: face '7' must be a "
                               "patch face 0..3");
  expect_refused_at_parse_time("hold-full",
                               "Body 1/Hold rotation=3",
                               "Body 1/Hold rotation is modelled on the "
                               "condensed path only, but Contact/Path = full",
                               "v3-contact-patch-2d.prm",
                               "--set 'Contact/Path=full'");
}



TEST(CliBadInput, GradingBandOutsideItsDirection)
{
  expect_refused_at_parse_time("band",
                               "Body 1/Grading=band 0: 0.6, 0.4, 8",
                               "Body 1/Grading: 'band 0: 0.6, 0.4, 8': a band "
                               "is 'band d: from, to, ratio'");
}



TEST(CliBadInput, HertzChecksOfTheOtherDimension)
{
  expect_refused_at_parse_time("hertz-point-2d",
                               "Checks/Hertz point load=1",
                               "Checks/Hertz point load is the 3D point "
                               "contact of a sphere");
  expect_refused_at_parse_time("hertz-line-3d",
                               "Checks/Hertz line load=1",
                               "Checks/Hertz line load is the 2D line contact",
                               "v7-sphere-on-block.prm");
  expect_refused_at_parse_time("hertz-axis-2d",
                               "Checks/Hertz axis direction=0, 1",
                               "Checks/Hertz axis direction = '0, 1' must be "
                               "a non-zero 3D vector",
                               "v7-sphere-on-block.prm");
  // A geometry file has no Body 1/Radius to fall back on.
  expect_refused_at_parse_time("hertz-radius-file",
                               "Checks/Hertz radius=0",
                               "Checks/Hertz radius = 0 takes Body 1/Radius",
                               "v7-sphere-on-block.prm");
}



TEST(CliBadInput, HertzRadiiThatDescribeNoEllipticalContact)
{
  // Checks/Hertz radii on the elliptical scene: each case one line naming
  // the parameter, when the scene is read.
  const std::string scene = "hertz-elliptical-contact.prm";
  expect_refused_at_parse_time("radii-one",
                               "Checks/Hertz radii=2",
                               "give two radii per body",
                               scene);
  expect_refused_at_parse_time("radii-negative",
                               "Checks/Hertz radii=-2, 1",
                               "must be positive",
                               scene);
  expect_refused_at_parse_time("radii-line",
                               "Checks/Hertz radii=flat, 1; flat, 2",
                               "a line contact",
                               scene);
  expect_refused_at_parse_time("radii-three",
                               "Checks/Hertz radii=2, 1; 1, 1; 1, 1",
                               "more than two bodies",
                               scene);
  expect_refused_at_parse_time("radii-direction",
                               "Checks/Hertz principal direction=0, 0, 1",
                               "at right angles",
                               scene);
  expect_refused_at_parse_time("radii-no-load",
                               "Checks/Hertz point load=0",
                               "set Checks/Hertz point load too",
                               scene);
}



TEST(CliBadInput, RigidSphereInTwoDimensions)
{
  expect_refused_at_parse_time("sphere-2d",
                               "Body 2/Type=rigid sphere",
                               "Body 2/Type = rigid sphere is a 3D obstacle",
                               "rigid-cylinder-on-block.prm");
}



TEST(CliBadInput, RigidCylinderWithoutRadius)
{
  expect_refused_at_parse_time("cylinder-radius",
                               "Body 2/Radius=0",
                               "Body 2/Radius = 0 must be > 0",
                               "rigid-cylinder-on-block.prm");
}



TEST(CliBadInput, RigidCylinderWithZeroAxis)
{
  expect_refused_at_parse_time("cylinder-axis",
                               "Body 2/Axis=0, 0, 0",
                               "Body 2/Axis = '0, 0, 0' must not be zero",
                               "rigid-sphere-on-block.prm",
                               "--set 'Body 2/Type=rigid cylinder'");
}



TEST(CliBadInput, ObstacleMotionWithTheWrongNumberOfValues)
{
  // 2D: two translations, or two and one rotation; four is neither.
  expect_refused_at_parse_time("motion-count",
                               "Body 2/Motion=0, -0.1, 0, 1",
                               "Body 2/Motion: '0, -0.1, 0, 1' gives 4 values",
                               "rigid-cylinder-on-block.prm");
}



TEST(CliBadInput, ObstacleMotionOnADeformableBody)
{
  expect_refused_at_parse_time("motion-deformable",
                               "Body 2/Motion=0, -0.1",
                               "Body 2/Motion is for rigid obstacles");
}



TEST(CliBadInput, ObstacleMotionWithAnUndeclaredHistory)
{
  expect_refused_at_parse_time("motion-history",
                               "Body 2/Motion=0, -0.1 @ press",
                               "Body 2: load history 'press' is not declared",
                               "rigid-cylinder-on-block.prm");
}



TEST(CliBadInput, RigidSurfaceFaceThatDoesNotExist)
{
  expect_refused_at_parse_time("surface-face",
                               "Contact/Master face=7",
                               "Contact/Master face (Body 2): face '7' must "
                               "be a patch face 0..3",
                               "rigid-punch-on-block.prm");
}



TEST(CliBadInput, RigidSurfaceGeometryFileMissing)
{
  expect_refused_at_parse_time("surface-file",
                               "Body 2/Geometry file=nope.xml",
                               "Body 2/Geometry file = nope.xml: ",
                               "rigid-punch-on-block.prm");
}



TEST(CliBadInput, RoundedPunchCheckWithoutCornerRadius)
{
  expect_refused_at_parse_time("punch-radius",
                               "Checks/Rounded punch corner radius=0",
                               "Checks/Rounded punch corner radius must be > "
                               "0 (m)",
                               "rigid-punch-on-block.prm");
}



// Scenes of more than two bodies (prm/three-block-stack.prm).
TEST(CliBadInput, InteractionNamesABodyTheSceneDoesNotHave)
{
  expect_refused_at_parse_time("interaction-missing-body",
                               "Contact/Interaction 2/Master body=4",
                               "Contact/Interaction 2/Master body = 4 names no "
                               "body",
                               "three-block-stack.prm");
}

TEST(CliBadInput, InteractionPairsABodyWithItself)
{
  expect_refused_at_parse_time("interaction-with-itself",
                               "Contact/Interaction 2/Master body=2",
                               "Master body = Slave body = 2",
                               "three-block-stack.prm");
}

TEST(CliBadInput, InteractionWithARigidSlave)
{
  expect_refused_at_parse_time("interaction-rigid-slave",
                               "Body 3/Type=rigid plane",
                               "Contact/Interaction 3/Slave body = 3",
                               "three-block-stack.prm",
                               "--set 'Contact/Interaction 3/Slave body=3' "
                               "--set 'Contact/Interaction 3/Slave face=3' "
                               "--set 'Contact/Interaction 3/Master body=1' "
                               "--set 'Contact/Interaction 3/Master face=3'");
}

TEST(CliBadInput, InteractionFaceThatDoesNotExist)
{
  expect_refused_at_parse_time("interaction-missing-face",
                               "Contact/Interaction 2/Master face=7",
                               "Contact/Interaction 2/Master face",
                               "three-block-stack.prm");
}

TEST(CliBadInput, InteractionRepeated)
{
  expect_refused_at_parse_time("interaction-repeated",
                               "Contact/Interaction 2/Slave body=1",
                               "Contact/Interaction 2 repeats Contact",
                               "three-block-stack.prm",
                               "--set 'Contact/Interaction 2/Master body=2' "
                               "--set 'Contact/Interaction 2/Slave face=2' "
                               "--set 'Contact/Interaction 2/Master face=3'");
}

TEST(CliBadInput, InteractionNegativeFrictionCoefficient)
{
  expect_refused_at_parse_time(
    "interaction-negative-friction",
    "Contact/Interaction 2/Friction coefficient=-0.1",
    "Contact/Interaction 2/Friction coefficient",
    "three-block-stack.prm");
}

TEST(CliBadInput, BodyInNoInteractionAndHeldByNothing)
{
  expect_refused_at_parse_time("body-in-no-interaction",
                               "Body 3/Supports=",
                               "no contact interaction names Body 3",
                               "three-block-stack.prm",
                               "--set 'Contact/Interaction 2/Slave body=0' "
                               "--set 'Contact/Interaction 2/Master body=0'");
}

TEST(CliBadInput, BodiesJoinedByContactThatNothingHolds)
{
  expect_refused_at_parse_time("bodies-nothing-holds",
                               "Body 1/Supports=",
                               "none of which touches a rigid obstacle",
                               "three-block-stack.prm",
                               "--set 'Body 2/Supports=' "
                               "--set 'Body 3/Supports='");
}

TEST(CliBadInput, GapInTheBodyNumbering)
{
  expect_refused_at_parse_time("bodies-gap",
                               "Body 4/Type=rigid plane",
                               "number the bodies from Body 1 without gaps",
                               "v3-contact-patch-2d.prm");
}

TEST(CliBadInput, FiniteSlidingOnTheCondensedPath)
{
  expect_refused_at_parse_time("sliding-condensed",
                               "Contact/Path=condensed",
                               "only the full path follows",
                               "hertz-cylinder-sliding.prm");
}

TEST(CliBadInput, FiniteSlidingWithPointPairs)
{
  expect_refused_at_parse_time("sliding-point-pairs",
                               "Contact/Pairing=node-to-surface",
                               "Contact/Pairing = node-to-surface",
                               "hertz-cylinder-sliding.prm");
}

TEST(CliBadInput, FiniteSlidingWithGmres)
{
  expect_refused_at_parse_time("sliding-gmres",
                               "Contact/Full system solver=gmres-amg",
                               "Full system solver = mumps or klu",
                               "hertz-cylinder-sliding.prm");
}

TEST(CliBadInput, FiniteSlidingWithABodyHeldByContactAlone)
{
  // The upper block of V3 is held vertically by the contact only: its
  // rigid-mode columns would follow the pairs too. Refused when the
  // contact problem is formed, before any step.
  const cli::ScratchFolder folder("bad-input-sliding-free-mode");
  const std::string        scene =
    cli::join(cli::join(std::string(IGABDE_SOURCE_DIR), "prm"),
              "v3-contact-patch-2d.prm");
  const auto result = cli::run_igabde(
    "'" + scene +
      "' --quiet --set 'Contact/Sliding=finite' --set "
      "'Contact/Pairing=weighted-gap' --set 'Contact/Friction coefficient=0' "
      "--set 'Output/Directory=out'",
    folder);
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("only its contacts hold"), std::string::npos)
    << result.output;
  EXPECT_FALSE(
    std::filesystem::exists(cli::join(folder.path, "out/contact-0001.csv")));
}

TEST(CliBadInput, FaceMotionAboutTooFewCoordinates)
{
  expect_refused_at_parse_time("face-motion-about",
                               "Body 1/Face motions=1: 0, 0, 0.01 about 1",
                               "after 'about'",
                               "v3-contact-patch-2d.prm");
}
