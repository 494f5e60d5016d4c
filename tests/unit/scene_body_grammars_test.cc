// The grammars of a body's entries (scene/body_grammars.h), one test each:
// an entry of every form the grammar accepts, read back as the values
// written by hand beside it, and an entry it refuses, with the part of the
// one-line message that names what is accepted. The end-to-end refusals
// (exit status 2, nothing written) are the bad-input suite's
// (cli_bad_input_test.cc).

#include <igabde/base/utilities.h>

#include <igabde/scene/body_grammars.h>

#include <gtest/gtest.h>

#include <functional>
#include <string>

using namespace igabde;
using namespace igabde::scene;

namespace
{
  /// The faces of a 2D box: x = lower, x = upper, y = lower, y = upper.
  PatchFaces
  box_faces_2d()
  {
    return {{"x = lower", "x = upper", "y = lower", "y = upper"}, false, "box"};
  }

  /// The faces of a 3D geometry file (faces may name a patch).
  PatchFaces
  file_faces_3d()
  {
    return {{"u = 0", "u = 1", "v = 0", "v = 1", "w = 0", "w = 1"},
            true,
            "file"};
  }

  /// Expects @p read to throw an input error whose message starts with
  /// @p where and contains @p text.
  void
  expect_refused(const std::function<void()> &read,
                 const std::string           &where,
                 const std::string           &text)
  {
    try
      {
        read();
        ADD_FAILURE() << "accepted; expected a refusal containing '" << text
                      << "'";
      }
    catch (const base::ExcInput &e)
      {
        const std::string message = base::exception_message(e);
        EXPECT_EQ(message.rfind(where, 0), 0u) << message;
        EXPECT_NE(message.find(text), std::string::npos) << message;
      }
  }
} // namespace



TEST(BodyGrammars, HistoryFollowsTheAtSign)
{
  EXPECT_EQ(split_history("0: x @ ramp"),
            std::make_pair(std::string("0: x"), std::string("ramp")));
  EXPECT_EQ(split_history("0: x"),
            std::make_pair(std::string("0: x"), std::string()));
}



TEST(BodyGrammars, VectorsHaveOneComponentPerDimension)
{
  EXPECT_EQ(read_vector("1, -2.5", 2, "f: V"), std::vector<double>({1, -2.5}));
  // A 3D default read in 2D: its zero third component is dropped.
  EXPECT_EQ(read_vector("0, 1, 0", 2, "f: V"), std::vector<double>({0, 1}));
  expect_refused(
    [] {
      read_vector("0, 1, 2", 2, "f: V");
    },
    "f: V",
    "must have 2 comma-separated components");
  expect_refused(
    [] {
      read_vector("1, inf", 2, "f: V");
    },
    "f: V",
    "'inf' is not a number");
}



TEST(BodyGrammars, FacesArePatchFacesJoinedByPlus)
{
  EXPECT_EQ(read_faces("1+3", box_faces_2d(), "f: S", "1+3: x"),
            std::vector<unsigned int>({1, 3}));
  // 'p.f' on a file: face f of patch p, body face p * 6 + f.
  EXPECT_EQ(read_faces("2.5", file_faces_3d(), "f: S", "2.5: x"),
            std::vector<unsigned int>({17}));
  expect_refused(
    [] {
      read_faces("4", box_faces_2d(), "f: S", "4: x");
    },
    "f: S",
    "must be a patch face 0..3 (several joined by '+') of the "
    "box: 0 (x = lower)");
  expect_refused(
    [] {
      read_faces("1.2", box_faces_2d(), "f: S", "1.2");
    },
    "f: S",
    "face '1.2'");
  expect_refused(
    [] {
      read_faces("0+1", box_faces_2d(), "f: H", "0+1", false);
    },
    "f: H",
    "names several faces");
}



TEST(BodyGrammars, SubdivisionsAreOneCountOrOnePerDirection)
{
  EXPECT_EQ(read_subdivisions("4", 3, "f: N"),
            std::vector<unsigned int>({4, 4, 4}));
  EXPECT_EQ(read_subdivisions("8, 2", 2, "f: N"),
            std::vector<unsigned int>({8, 2}));
  expect_refused(
    [] {
      read_subdivisions("2.5", 2, "f: N");
    },
    "f: N = '2.5'",
    "integers from 1 to 9999");
  expect_refused(
    [] {
      read_subdivisions("1, 2, 3", 2, "f: N");
    },
    "f: N",
    "one count or one per direction");
}



TEST(BodyGrammars, GradingIsTowardAFaceOrABand)
{
  const GradingParameters g =
    read_grading("3: 8; band 0: 0.25, 0.5, 4", 2, "f: G");
  EXPECT_EQ(g.ratio, std::vector<double>({4, 8}));
  EXPECT_EQ(g.toward_high, std::vector<bool>({false, true}));
  EXPECT_EQ(g.band[0][0], 0.25);
  EXPECT_EQ(g.band[0][1], 0.5);
  EXPECT_EQ(g.band[1][0], g.band[1][1]);
  expect_refused(
    [] {
      read_grading("2: 4; 3: 2", 2, "f: G");
    },
    "f: G",
    "direction 1 is graded twice");
  expect_refused(
    [] {
      read_grading("0: 0.5", 2, "f: G");
    },
    "f: G",
    "must lie in [1, 1e6]");
  expect_refused(
    [] {
      read_grading("band 2: 0, 1, 2", 2, "f: G");
    },
    "f: G",
    "a band is 'band d: from, to, ratio'");
}



TEST(BodyGrammars, SupportsHoldComponentsValuesAndExpressions)
{
  const auto s = read_supports("0+2: x y=0.1 @ pull; 3: y = function 0.01*x",
                               box_faces_2d(),
                               "f: S");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].face, 0u);
  EXPECT_EQ(s[1].face, 2u);
  for (unsigned int i = 0; i < 2; ++i)
    {
      EXPECT_TRUE(s[i].components[0] && s[i].components[1]);
      EXPECT_EQ(s[i].values[1], 0.1);
      EXPECT_EQ(s[i].history, "pull");
    }
  EXPECT_EQ(s[2].face, 3u);
  EXPECT_FALSE(s[2].components[0]);
  EXPECT_TRUE(s[2].components[1]);
  EXPECT_EQ(s[2].expressions[1], "0.01*x");
  expect_refused(
    [] {
      read_supports("0: z", box_faces_2d(), "f: S");
    },
    "f: S",
    "'z' in '0: z' is not a component; use x, y");
  expect_refused(
    [] {
      read_supports("0: y = function t*x", box_faces_2d(), "f: S");
    },
    "f: S",
    "uses t");
  expect_refused(
    [] {
      read_supports("0 x", box_faces_2d(), "f: S");
    },
    "f: S",
    "must read 'face: components'");
}



TEST(BodyGrammars, TractionsOfEveryKind)
{
  const auto t = read_tractions(
    "3: pressure 2.5; 1: vector 1, 0 @ side; 0: exact; 2: function x; t*y",
    box_faces_2d(),
    "f: T");
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0].kind, TractionParameters::Kind::pressure);
  EXPECT_EQ(t[0].values, std::vector<double>({2.5}));
  EXPECT_EQ(t[1].kind, TractionParameters::Kind::vector);
  EXPECT_EQ(t[1].values, std::vector<double>({1, 0}));
  EXPECT_EQ(t[1].history, "side");
  EXPECT_EQ(t[2].kind, TractionParameters::Kind::exact);
  EXPECT_EQ(t[3].kind, TractionParameters::Kind::function);
  EXPECT_EQ(t[3].expressions, std::vector<std::string>({"x", "t*y"}));
  EXPECT_TRUE(t[3].uses_t);
  EXPECT_EQ(t[3].face, 2u);
  expect_refused(
    [] {
      read_tractions("0: shear 1", box_faces_2d(), "f: T");
    },
    "f: T",
    "'shear 1' is not 'pressure p'");
  expect_refused(
    [] {
      read_tractions("0: function x", box_faces_2d(), "f: T");
    },
    "f: T",
    "has 1 expressions; give 2");
  expect_refused(
    [] {
      read_tractions("0: function x; (y", box_faces_2d(), "f: T");
    },
    "f: T",
    "cannot evaluate");
}



TEST(BodyGrammars, HoldRotationIsOneFaceOrNone)
{
  EXPECT_EQ(read_hold_rotation("", box_faces_2d(), "f: H"), -1);
  EXPECT_EQ(read_hold_rotation(" 1 ", box_faces_2d(), "f: H"), 1);
  expect_refused(
    [] {
      read_hold_rotation("1+2", box_faces_2d(), "f: H");
    },
    "f: H",
    "names several faces");
}



TEST(BodyGrammars, PointLoadsAreALocationAndAForce)
{
  const auto p = read_point_loads("0, 1 : 0, -5 @ push", 2, "f: P");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].location, std::vector<double>({0, 1}));
  EXPECT_EQ(p[0].force, std::vector<double>({0, -5}));
  EXPECT_EQ(p[0].history, "push");
  expect_refused(
    [] {
      read_point_loads("0, 1", 2, "f: P");
    },
    "f: P",
    "must read 'x, y[, z] : fx, fy[, fz]'");
}



TEST(BodyGrammars, PointSupportsHoldComponentsAtAPoint)
{
  const auto p = read_point_supports("0, 0, 1 : x z=0.01", 3, "f: PS");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].location, std::vector<double>({0, 0, 1}));
  EXPECT_TRUE(p[0].components[0]);
  EXPECT_FALSE(p[0].components[1]);
  EXPECT_TRUE(p[0].components[2]);
  EXPECT_EQ(p[0].values[2], 0.01);
  expect_refused(
    [] {
      read_point_supports("0, 0 :", 2, "f: PS");
    },
    "f: PS",
    "names no component");
  expect_refused(
    [] {
      read_point_supports("0, 0 : x=1,2", 2, "f: PS");
    },
    "f: PS",
    "needs one value");
}



TEST(BodyGrammars, MomentsHaveOneValueIn2DAndThreeIn3D)
{
  const auto m2 = read_moments("1: 2.5", box_faces_2d(), "f: M");
  ASSERT_EQ(m2.size(), 1u);
  EXPECT_EQ(m2[0].face, 1u);
  EXPECT_EQ(m2[0].moment, std::vector<double>({2.5}));
  const auto m3 = read_moments("1.4: 1, 2, 3", file_faces_3d(), "f: M");
  ASSERT_EQ(m3.size(), 1u);
  EXPECT_EQ(m3[0].face, 10u);
  EXPECT_EQ(m3[0].moment, std::vector<double>({1, 2, 3}));
  expect_refused(
    [] {
      read_moments("1: 1, 2", box_faces_2d(), "f: M");
    },
    "f: M",
    "must give one value (the moment about z)");
}



TEST(BodyGrammars, FaceMotionsMoveEachFaceOnce)
{
  const auto f = read_face_motions("3: 0, -0.1, 0.01", box_faces_2d(), "f: F");
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].face, 3u);
  EXPECT_EQ(f[0].motion, std::vector<double>({0, -0.1, 0.01}));
  expect_refused(
    [] {
      read_face_motions("3: 0, 0, 0; 3: 1, 0, 0", box_faces_2d(), "f: F");
    },
    "f: F",
    "face 3 is moved twice");
  expect_refused(
    [] {
      read_face_motions("3: 0, 0", box_faces_2d(), "f: F");
    },
    "f: F",
    "must give three values");
}



TEST(BodyGrammars, BodyForceIsAVectorOrExpressionsWithoutT)
{
  EXPECT_EQ(read_body_force("0, -9.81", 2, "f: B").vector,
            std::vector<double>({0, -9.81}));
  const auto b = read_body_force("function 0; -x", 2, "f: B");
  EXPECT_EQ(b.vector, std::vector<double>({0, 0}));
  EXPECT_EQ(b.expressions, std::vector<std::string>({"0", "-x"}));
  expect_refused(
    [] {
      read_body_force("function 0; -t", 2, "f: B");
    },
    "f: B uses t",
    "scaled by the load factor");
}



TEST(BodyGrammars, ProbePointsAreNamedPoints)
{
  const auto p = read_probe_points("A: 0, 0.5, 1.5; C: 6, 0.5, 0.5", 3, "f: P");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].name, "A");
  EXPECT_EQ(p[0].location, std::vector<double>({0, 0.5, 1.5}));
  EXPECT_EQ(p[1].name, "C");
  expect_refused(
    [] {
      read_probe_points("A: 0, 1", 3, "f: P");
    },
    "f: P",
    "needs 3 coordinates");
}



TEST(BodyGrammars, PointsAndDirectionsHaveExactlyTheScenesComponents)
{
  EXPECT_EQ(read_point("0, 0.5, 1", 3, "f: A"),
            std::vector<double>({0, 0.5, 1}));
  EXPECT_EQ(read_direction("0, -2", 2, "f: D"), std::vector<double>({0, -2}));
  expect_refused(
    [] {
      read_point("0, 1, 0", 2, "f: A");
    },
    "f: A = '0, 1, 0'",
    "must be a 2D point");
  expect_refused(
    [] {
      read_direction("0, 0, 0", 3, "f: D");
    },
    "f: D",
    "must be a non-zero 3D vector, e.g. '0, 0, 1'");
  EXPECT_EQ(read_numbers("0.5 1, 2", "f: N"), std::vector<double>({0.5, 1, 2}));
  EXPECT_TRUE(read_numbers("", "f: N").empty());
}



TEST(BodyGrammars, HistoriesAreNamedFactorLists)
{
  const auto h = read_histories("push: 0, 1; pull: 1, 0.5", "f: H");
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].first, "push");
  EXPECT_EQ(h[0].second, std::vector<double>({0, 1}));
  EXPECT_EQ(h[1].first, "pull");
  EXPECT_EQ(h[1].second, std::vector<double>({1, 0.5}));
  expect_refused(
    [] {
      read_histories("load: 1", "f: H");
    },
    "f: H",
    "'load' is not a usable name");
  expect_refused(
    [] {
      read_histories("a: 1; a: 2", "f: H");
    },
    "f: H",
    "'a' is declared twice");
  expect_refused(
    [] {
      read_histories(": 1", "f: H");
    },
    "f: H",
    "has no name");
}



// 'ramp a b n' and 'hold f n' in a history: the factors written out by
// hand, a ramp's last factor b exactly.
TEST(BodyGrammars, HistoriesRampAndHold)
{
  const auto h =
    read_histories("press: ramp 0 1 4, hold 1 2; slide: hold 0 4, ramp 0 0.3 "
                   "2, 0.5",
                   "f: H");
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].second, std::vector<double>({0.25, 0.5, 0.75, 1, 1, 1}));
  ASSERT_EQ(h[1].second.size(), 7u);
  for (unsigned int k = 0; k < 4; ++k)
    EXPECT_EQ(h[1].second[k], 0.);
  EXPECT_DOUBLE_EQ(h[1].second[4], 0.15);
  EXPECT_EQ(h[1].second[5], 0.3);
  EXPECT_EQ(h[1].second[6], 0.5);
  for (const std::string bad : {"a: ramp 0 1",
                                "a: ramp 0 1 0",
                                "a: hold 1 2.5",
                                "a: hold 1 -3",
                                "a: ramp 0 x 3"})
    expect_refused(
      [&] {
        read_histories(bad, "f: H");
      },
      "f: H",
      "must read");
}
