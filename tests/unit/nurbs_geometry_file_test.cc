// Reading and writing G+Smo XML geometry files: files written by hand in
// the layout G+Smo writes (the references: a circle's radius, a known
// area, the declared topology), the exact round trip of the writer, the
// measures of exact geometries against their closed forms, and every bad
// input refused with a message that names the file.
#include <igabde/base/utilities.h>

#include <igabde/nurbs/geometry_builders.h>
#include <igabde/nurbs/geometry_file.h>
#include <igabde/nurbs/multi_patch.h>

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

using namespace dealii;
using namespace igabde;
using namespace igabde::nurbs;

namespace
{
  /// Writes @p text to @p name in @p folder and returns the path.
  std::string
  write(const cli::ScratchFolder &folder,
        const std::string        &name,
        const std::string        &text)
  {
    const std::string path = cli::join(folder.path, name);
    std::ofstream(path) << text;
    return path;
  }

  /// A TensorBSpline2 or TensorNurbs2 element (id @p id) in G+Smo's
  /// layout.
  std::string
  patch_2d(const std::string &id,
           const std::string &knots0,
           const std::string &knots1,
           const std::string &coefs,
           const std::string &weights = "",
           const std::string &degree0 = "1",
           const std::string &degree1 = "1",
           const std::string &geo_dim = "2")
  {
    const std::string tensor = "<Basis type=\"TensorBSplineBasis2\">\n"
                               " <Basis type=\"BSplineBasis\" index=\"0\">\n"
                               "  <KnotVector degree=\"" +
                               degree0 + "\">" + knots0 +
                               "</KnotVector>\n"
                               " </Basis>\n"
                               " <Basis type=\"BSplineBasis\" index=\"1\">\n"
                               "  <KnotVector degree=\"" +
                               degree1 + "\">" + knots1 +
                               "</KnotVector>\n"
                               " </Basis>\n"
                               "</Basis>\n";
    const std::string basis =
      weights.empty() ? tensor :
                        "<Basis type=\"TensorNurbsBasis2\">\n" + tensor +
                          "<weights>" + weights + "</weights>\n</Basis>\n";
    return "<Geometry type=\"" +
           std::string(weights.empty() ? "TensorBSpline2" : "TensorNurbs2") +
           "\" id=\"" + id + "\">\n" + basis + "<coefs geoDim=\"" + geo_dim +
           "\">\n" + coefs + "</coefs>\n</Geometry>\n";
  }

  std::string
  xml(const std::string &body)
  {
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xml>\n" + body +
           "</xml>\n";
  }

  /// The unit square [x0, x0 + 1] x [y0, y0 + 1], bilinear, id @p id.
  std::string
  square(const std::string &id, const double x0, const double y0)
  {
    std::ostringstream c;
    c << x0 << ' ' << y0 << '\n'
      << x0 + 1 << ' ' << y0 << '\n'
      << x0 << ' ' << y0 + 1 << '\n'
      << x0 + 1 << ' ' << y0 + 1 << '\n';
    return patch_2d(id, "0 0 1 1", "0 0 1 1", c.str());
  }

  /// The message of the input error that reading @p path ends with.
  template <int dim>
  std::string
  refusal(const std::string &path)
  {
    try
      {
        read_geometry_file<dim>(path);
      }
    catch (const base::ExcInput &e)
      {
        return base::exception_message(e);
      }
    catch (...)
      {
        return "(another exception than an input error)";
      }
    return "(no error)";
  }

  void
  expect_refused(const cli::ScratchFolder &folder,
                 const std::string        &name,
                 const std::string        &text,
                 const std::string        &says)
  {
    SCOPED_TRACE(name);
    const std::string path    = write(folder, name, text);
    const std::string message = refusal<2>(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(says), std::string::npos) << message;
  }
} // namespace



TEST(GeometryFile, ReadsAQuarterAnnulusWrittenInGismosLayout)
{
  // The quarter annulus 1 <= r <= 2 written as G+Smo writes a NURBS
  // surface: direction 0 the arc (degree 2, middle weight cos 45 deg),
  // direction 1 radial; control points direction 0 fastest.
  const cli::ScratchFolder folder("geometry-annulus", "unit");
  const double             w = std::sqrt(0.5);
  std::ostringstream       weights;
  weights.precision(17);
  weights << "1 " << w << " 1 1 " << w << " 1";
  const std::string           path = write(folder,
                                 "annulus.xml",
                                 xml(patch_2d("7",
                                              "0 0 0 1 1 1",
                                              "0 0 1 1",
                                              "1 0\n1 1\n0 1\n2 0\n2 2\n0 2\n",
                                              weights.str(),
                                              "2",
                                              "1")));
  const MultiPatchGeometry<2> g    = read_geometry_file<2>(path);
  ASSERT_EQ(g.patches.size(), 1u);
  EXPECT_TRUE(g.interfaces.empty());
  const NurbsPatch<2> &p = g.patches[0];
  EXPECT_EQ(p.degree(0), 2u);
  EXPECT_EQ(p.degree(1), 1u);
  // Every point of the inner and outer arcs lies on its circle.
  for (const double u : {0., 0.1, 0.37, 0.5, 0.81, 1.})
    {
      EXPECT_NEAR(p.value(Point<2>(u, 0.)).norm(), 1., 1e-14);
      EXPECT_NEAR(p.value(Point<2>(u, 1.)).norm(), 2., 1e-14);
    }
  // Area pi (2^2 - 1^2) / 4.
  EXPECT_NEAR(patch_measure(p), M_PI * 3. / 4., 1e-12);
}



TEST(GeometryFile, ReadsTheTopologyOfAThreePatchLShape)
{
  // Three unit squares forming an L, declared as G+Smo does: patches by
  // id range, interfaces "patch side patch side" followed by the
  // direction map and orientation, boundary as (patch, side) pairs; G+Smo
  // sides are 1..4 = west, east, south, north.
  const cli::ScratchFolder folder("geometry-lshape", "unit");
  const std::string        path =
    write(folder,
          "lshape.xml",
          xml(square("0", 0., -1.) + square("1", -1., -1.) +
              square("2", -1., 0.) +
              "<MultiPatch parDim=\"2\" id=\"9\">\n"
              " <patches type=\"id_range\">0 2</patches>\n"
              " <interfaces>\n2 3 1 4 0 1 1 1\n1 2 0 1 0 1 1 1\n"
              " </interfaces>\n"
              " <boundary>\n2 1\n2 2\n2 4\n1 1\n1 3\n0 2\n0 3\n0 4\n"
              " </boundary>\n"
              "</MultiPatch>\n"));
  const MultiPatchGeometry<2> g = read_geometry_file<2>(path);
  ASSERT_EQ(g.patches.size(), 3u);
  ASSERT_EQ(g.interfaces.size(), 2u);
  // Patch 2's south face (face 2) meets patch 1's north face (face 3).
  EXPECT_EQ(g.interfaces[0].patch[0], 2u);
  EXPECT_EQ(g.interfaces[0].face[0], 2u);
  EXPECT_EQ(g.interfaces[0].patch[1], 1u);
  EXPECT_EQ(g.interfaces[0].face[1], 3u);
  EXPECT_EQ(g.interfaces[0].flags, (std::vector<int>{0, 1, 1, 1}));
  ASSERT_EQ(g.boundary.size(), 8u);
  EXPECT_EQ(g.boundary[2], std::make_pair(2u, 3u));
  double area = 0.;
  for (const auto &p : g.patches)
    area += patch_measure(p);
  EXPECT_NEAR(area, 3., 1e-14);

  // Written and read back: the same patches, interfaces and boundary.
  std::ostringstream out;
  write_geometry_file(g, out);
  const MultiPatchGeometry<2> h =
    read_geometry_file<2>(write(folder, "again.xml", out.str()));
  ASSERT_EQ(h.patches.size(), 3u);
  ASSERT_EQ(h.interfaces.size(), 2u);
  EXPECT_EQ(h.interfaces[1].patch, g.interfaces[1].patch);
  EXPECT_EQ(h.interfaces[1].face, g.interfaces[1].face);
  EXPECT_EQ(h.interfaces[1].flags, g.interfaces[1].flags);
  EXPECT_EQ(h.boundary, g.boundary);
}



TEST(GeometryFile, WriteThenReadIsExact)
{
  // Refined, elevated patches with irrational weights and coordinates: the
  // 17 significant digits written give back the same doubles.
  const cli::ScratchFolder folder("geometry-round-trip", "unit");
  NurbsPatch<3>            beam = make_curved_beam(1., 1.5, 0.4);
  elevate_to_degree(beam, 3);
  subdivide(beam, {{3, 5, 2}}, {{1., 4., 1.}});
  MultiPatchGeometry<3> g;
  g.patches.push_back(beam);
  std::ostringstream out;
  write_geometry_file(g, out);
  const NurbsPatch<3> back =
    read_geometry_file<3>(write(folder, "beam.xml", out.str())).patches[0];
  ASSERT_EQ(back.n_control_points(), beam.n_control_points());
  for (unsigned int d = 0; d < 3; ++d)
    EXPECT_EQ(back.knot_vector(d).knots(), beam.knot_vector(d).knots());
  for (unsigned int a = 0; a < beam.n_control_points(); ++a)
    {
      EXPECT_EQ(back.weight(a), beam.weight(a));
      EXPECT_EQ(back.control_point(a), beam.control_point(a));
    }
  // The left-handed beam is accepted; its volume is the quarter annulus
  // times the width.
  EXPECT_NEAR(patch_measure(back),
              M_PI * (1.5 * 1.5 - 1.) / 4. * 0.4,
              1e-12 * 0.4);

  // The control net as VTU: one cell per cell of the net.
  std::ostringstream vtu;
  write_control_net_vtu(g, vtu);
  const unsigned int cells = (beam.n_control_points(0) - 1) *
                             (beam.n_control_points(1) - 1) *
                             (beam.n_control_points(2) - 1);
  EXPECT_NE(vtu.str().find("NumberOfCells=\"" + std::to_string(cells) + "\""),
            std::string::npos);
}



TEST(GeometryFile, MeasuresOfExactGeometries)
{
  EXPECT_NEAR(patch_measure(make_thick_cylinder_quarter<3>(1., 2., 3.)),
              M_PI * 3. / 4. * 3.,
              1e-12 * 7.);
  EXPECT_NEAR(patch_measure(make_full_disc(Point<2>(1., 2.), 8.)),
              M_PI * 64.,
              1e-12 * 200.);
  NurbsPatch<2> hole = make_plate_with_hole(1., 4.);
  EXPECT_NEAR(patch_measure(hole), 16. - M_PI / 4., 1e-12 * 16.);
  // Refined patches get fewer points per span (the default rule); the
  // closed forms still hold to round-off.
  NurbsPatch<2> annulus = make_quarter_annulus(1., 2.);
  subdivide(annulus, {{4, 16}});
  EXPECT_NEAR(patch_measure(annulus), M_PI * 3. / 4., 1e-12);
  NurbsPatch<3> beam = make_curved_beam(1., 1.5, 0.4);
  elevate_to_degree(beam, 2);
  subdivide(beam, {{8, 32, 8}});
  EXPECT_NEAR(patch_measure(beam), M_PI * (1.5 * 1.5 - 1.) / 4. * 0.4, 1e-13);
}



TEST(GeometryFile, PlanarPatchStoredIn3dSpaceIsReadIn2d)
{
  // G+Smo's planar/ files store surfaces with geoDim = 3 and z = 0: a 2D
  // scene reads them as the same patch as with geoDim = 2, and says so.
  const cli::ScratchFolder folder("geometry-planar", "unit");
  const std::string        in_3d =
    write(folder,
          "in-3d.xml",
          xml(patch_2d("0",
                       "0 0 0.5 1 1",
                       "0 0 1 1",
                       "0 0 0\n0.5 -0.1 0\n1 0 0\n0 1 0\n0.5 1.2 0\n1 1 0\n",
                       "",
                       "1",
                       "1",
                       "3")));
  const std::string in_2d =
    write(folder,
          "in-2d.xml",
          xml(patch_2d("0",
                       "0 0 0.5 1 1",
                       "0 0 1 1",
                       "0 0\n0.5 -0.1\n1 0\n0 1\n0.5 1.2\n1 1\n")));
  const MultiPatchGeometry<2> a = read_geometry_file<2>(in_3d);
  const MultiPatchGeometry<2> b = read_geometry_file<2>(in_2d);
  ASSERT_EQ(a.patches.size(), 1u);
  ASSERT_EQ(a.patches[0].n_control_points(), 6u);
  for (unsigned int i = 0; i < 6; ++i)
    EXPECT_EQ(a.patches[0].control_point(i), b.patches[0].control_point(i));
  ASSERT_EQ(a.notes.size(), 1u);
  EXPECT_NE(a.notes[0].find("geoDim = 3"), std::string::npos) << a.notes[0];
  EXPECT_TRUE(b.notes.empty());
}



TEST(GeometryFile, RationalLiteralsAreReadAsTheirQuotients)
{
  // G+Smo writes exact coordinates as fractions ("1/9", "5/18" in its
  // planar/multiPatches files): read as p / q, the same patch as the
  // decimals; a fraction with a zero or missing part is refused.
  const cli::ScratchFolder folder("geometry-rational", "unit");
  const std::string        fractions =
    write(folder,
          "fractions.xml",
          xml(patch_2d("0",
                       "0 0 1/2 1 1",
                       "0 0 1 1",
                       "0 0\n1/2 -1/10\n1 0\n0 1\n1/2 6/5\n1 1\n",
                       "1 5/18 1 1 2/3 1")));
  const std::string decimals =
    write(folder,
          "decimals.xml",
          xml(patch_2d("0",
                       "0 0 0.5 1 1",
                       "0 0 1 1",
                       "0 0\n0.5 -0.1\n1 0\n0 1\n0.5 1.2\n1 1\n",
                       "1 0.2777777777777778 1 1 0.6666666666666666 1")));
  const MultiPatchGeometry<2> a = read_geometry_file<2>(fractions);
  const MultiPatchGeometry<2> b = read_geometry_file<2>(decimals);
  ASSERT_EQ(a.patches.size(), 1u);
  ASSERT_EQ(a.patches[0].n_control_points(), 6u);
  for (unsigned int i = 0; i < 6; ++i)
    {
      EXPECT_LE(a.patches[0].control_point(i).distance(
                  b.patches[0].control_point(i)),
                1e-15);
      EXPECT_NEAR(a.patches[0].weight(i), b.patches[0].weight(i), 1e-15);
    }
  for (const std::string bad : {"1/0", "1/", "/3", "1/2/3"})
    {
      const std::string path =
        write(folder,
              "bad.xml",
              xml(patch_2d("0",
                           "0 0 1 1",
                           "0 0 1 1",
                           "0 0\n1 0\n0 1\n1 " + bad + "\n")));
      EXPECT_NE(refusal<2>(path).find("'" + bad + "'"), std::string::npos)
        << bad << ": " << refusal<2>(path);
    }
}



TEST(GeometryFile, BadFilesAreRefusedNamingTheFile)
{
  const cli::ScratchFolder folder("geometry-bad", "unit");
  const std::string        unit_square =
    patch_2d("0", "0 0 1 1", "0 0 1 1", "0 0\n1 0\n0 1\n1 1\n");

  const std::string missing = cli::join(folder.path, "missing.xml");
  EXPECT_NE(refusal<2>(missing).find("no such file"), std::string::npos);

  // Truncated: the closing tags are missing.
  const std::string whole = xml(unit_square);
  expect_refused(folder,
                 "truncated.xml",
                 whole.substr(0, whole.size() / 2),
                 "not well-formed XML");
  expect_refused(folder, "no-patch.xml", xml(""), "no <Geometry> element");
  expect_refused(folder,
                 "coefs.xml",
                 xml(patch_2d("0", "0 0 1 1", "0 0 1 1", "0 0\n1 0\n0 1\n")),
                 "4 control points");
  expect_refused(
    folder,
    "weights-count.xml",
    xml(patch_2d("0", "0 0 1 1", "0 0 1 1", "0 0\n1 0\n0 1\n1 1\n", "1 1 1")),
    "weights");
  expect_refused(
    folder,
    "weight-zero.xml",
    xml(patch_2d("0", "0 0 1 1", "0 0 1 1", "0 0\n1 0\n0 1\n1 1\n", "1 1 0 1")),
    "must be positive");
  expect_refused(
    folder,
    "decreasing.xml",
    xml(patch_2d("0", "0 0 0.7 0.3 1 1", "0 0 1 1", "0 0\n1 0\n0 1\n1 1\n")),
    "non-decreasing");
  expect_refused(folder,
                 "short.xml",
                 xml(patch_2d("0", "0 0 1", "0 0 1 1", "0 0\n1 0\n0 1\n1 1\n")),
                 "too few knots");
  expect_refused(folder,
                 "geodim.xml",
                 xml(patch_2d("0",
                              "0 0 1 1",
                              "0 0 1 1",
                              "0 0 0\n1 0 0\n0 1 0.5\n1 1 0\n",
                              "",
                              "1",
                              "1",
                              "3")),
                 "geoDim = 3 and control point 2 has z = 0.5");
  expect_refused(folder,
                 "not-a-number.xml",
                 xml(
                   patch_2d("0", "0 0 1 1", "0 0 1 1", "0 0\n1 0\n0 x\n1 1\n")),
                 "'x' is not a number");
  // Degree 11 along direction 0 (12 knots at each end, 12 control points
  // in that direction): above the largest degree the bases evaluate.
  {
    std::string knots, coefs;
    for (unsigned int k = 0; k < 24; ++k)
      knots += (k < 12 ? "0 " : "1 ");
    for (unsigned int j = 0; j < 2; ++j)
      for (unsigned int i = 0; i < 12; ++i)
        coefs += std::to_string(i / 11.) + " " + std::to_string(j) + "\n";
    expect_refused(folder,
                   "degree.xml",
                   xml(patch_2d("0", knots, "0 0 1 1", coefs, "", "11", "1")),
                   "degree 11 is above the largest supported, 10");
  }
  // A bilinear patch whose upper corners are crossed: the map folds.
  expect_refused(folder,
                 "folded.xml",
                 xml(
                   patch_2d("0", "0 0 1 1", "0 0 1 1", "0 0\n1 0\n1 1\n0 1\n")),
                 "changes sign");
  // All control points on one line: the patch has no area.
  expect_refused(folder,
                 "flat.xml",
                 xml(
                   patch_2d("0", "0 0 1 1", "0 0 1 1", "0 0\n1 0\n2 0\n3 0\n")),
                 "vanishes");
  // Patches that do not touch, declared glued.
  expect_refused(folder,
                 "interface.xml",
                 xml(square("0", 0., 0.) + square("1", 3., 0.) +
                     "<MultiPatch parDim=\"2\" id=\"5\">\n"
                     " <patches type=\"id_range\">0 1</patches>\n"
                     " <interfaces>0 2 1 1 0 1 1 1</interfaces>\n"
                     "</MultiPatch>\n"),
                 "must coincide");
  expect_refused(folder,
                 "side.xml",
                 xml(square("0", 0., 0.) + square("1", 1., 0.) +
                     "<MultiPatch parDim=\"2\" id=\"5\">\n"
                     " <patches type=\"id_range\">0 1</patches>\n"
                     " <interfaces>0 2 1 7 0 1 1 1</interfaces>\n"
                     "</MultiPatch>\n"),
                 "sides are 1 to 4");
  // A 3D patch in a 2D scene.
  NurbsPatch<3>         box = make_box<3>(Point<3>(), Point<3>(1., 1., 1.));
  MultiPatchGeometry<3> g;
  g.patches.push_back(box);
  std::ostringstream out;
  write_geometry_file(g, out);
  expect_refused(folder, "box3d.xml", out.str(), "another dimension");
}



TEST(NurbsFaceInterpolation, CollocatesAtTheGrevillePointsOfCurvedFaces)
{
  // The interpolant sum_A R_A v_A of a function that is not in the space
  // must still match it at the face's Greville points (the defining
  // property), checked with the patch's own rational basis; the face
  // solve goes direction by direction, this check does not.
  const auto check = [](const auto &patch, const unsigned int face) {
    constexpr int dim = std::decay_t<decltype(patch)>::dimension;
    const auto    g   = [](const Point<dim> &x) {
      return x[0] * x[0] + 2. * x[1] + std::sin(x[dim - 1]);
    };
    const std::vector<double> v = interpolate_on_face<dim>(patch, face, g);
    const std::vector<unsigned int> points = patch.face_control_points(face);
    ASSERT_EQ(v.size(), points.size());
    std::array<std::vector<double>, dim> coords;
    for (unsigned int d = 0; d < dim; ++d)
      coords[d] =
        (d == face / 2) ?
          std::vector<double>{face % 2 == 0 ? patch.parametric_lower()[d] :
                                              patch.parametric_upper()[d]} :
          patch.knot_vector(d).greville_abscissae();
    std::vector<unsigned int> indices;
    std::vector<double>       values;
    for (const Point<dim> &xi : tensor_product_points<dim>(coords))
      {
        patch.basis(xi, indices, values);
        double sum = 0.;
        for (unsigned int k = 0; k < indices.size(); ++k)
          {
            const auto it = std::find(points.begin(), points.end(), indices[k]);
            if (it != points.end())
              sum += values[k] * v[it - points.begin()];
          }
        EXPECT_NEAR(sum, g(patch.value(xi)), 1e-12 * 10.);
      }
  };
  NurbsPatch<2> annulus = make_quarter_annulus(1., 2.);
  elevate_to_degree(annulus, 3);
  subdivide(annulus, {{4, 7}}, {{1., 3.}});
  for (unsigned int face = 0; face < 4; ++face)
    check(annulus, face);
  NurbsPatch<3> beam = make_curved_beam(1., 1.5, 0.4);
  elevate_to_degree(beam, 2);
  subdivide(beam, {{2, 6, 3}});
  for (unsigned int face = 0; face < 6; ++face)
    check(beam, face);
}



// A patch that meets itself would be a slit or a puncture in a body of one
// patch: a full ring (its two angular ends coincide) and a quarter disc
// whose radial direction starts at the centre (the face r = 0 is one
// point) are refused with what to model instead; the quarter annulus, whose
// faces are all distinct and of positive length, is read.
TEST(GeometryFile, PatchesThatMeetThemselvesAreRefused)
{
  const cli::ScratchFolder folder("geometry-closure", "unit");
  const double             h = std::sqrt(0.5);
  std::ostringstream       ring, ring_weights;
  ring << std::setprecision(17);
  ring_weights << std::setprecision(17);
  const double circle[9][3] = {{1, 0, 1},
                               {1, 1, h},
                               {0, 1, 1},
                               {-1, 1, h},
                               {-1, 0, 1},
                               {-1, -1, h},
                               {0, -1, 1},
                               {1, -1, h},
                               {1, 0, 1}};
  for (const double r : {1., 2.})
    for (const auto &c : circle)
      {
        ring << r * c[0] << ' ' << r * c[1] << '\n';
        ring_weights << c[2] << '\n';
      }
  expect_refused(folder,
                 "ring.xml",
                 xml(patch_2d("0",
                              "0 0 0 0.25 0.25 0.5 0.5 0.75 0.75 1 1 1",
                              "0 0 1 1",
                              ring.str(),
                              ring_weights.str(),
                              "2",
                              "1")),
                 "faces 0 and 1 (G+Smo sides 1 and 2) coincide");

  std::ostringstream pole;
  pole << std::setprecision(17) << "0 0\n0 0\n0 0\n1 0\n1 1\n0 1\n";
  expect_refused(folder,
                 "pole.xml",
                 xml(patch_2d("0",
                              "0 0 0 1 1 1",
                              "0 0 1 1",
                              pole.str(),
                              "1\n" + std::to_string(h) + "\n1\n1\n" +
                                std::to_string(h) + "\n1\n",
                              "2",
                              "1")),
                 "face 2 (G+Smo side 3) collapses");

  std::ostringstream annulus;
  annulus << std::setprecision(17) << "1 0\n1 1\n0 1\n2 0\n2 2\n0 2\n";
  const std::string path =
    write(folder,
          "annulus.xml",
          xml(patch_2d("0",
                       "0 0 0 1 1 1",
                       "0 0 1 1",
                       annulus.str(),
                       "1\n0.70710678118654757\n1\n1\n0.70710678118654757\n1\n",
                       "2",
                       "1")));
  EXPECT_EQ(read_geometry_file<2>(path).patches.size(), 1u);
}



namespace glue_test
{
  /// The L of three unit squares of ReadsTheTopologyOfAThreePatchLShape,
  /// its middle square (patch 1) written with its directions swapped (a
  /// left-handed patch whose faces are numbered differently), each patch
  /// split into @p spans[p] spans per direction.
  MultiPatchGeometry<2>
  l_shape(const cli::ScratchFolder                         &folder,
          const std::array<std::array<unsigned int, 2>, 3> &spans)
  {
    // Patch 1 = [-1, 0]^2, direction 0 along y: faces 0 y = -1, 1 y = 0,
    // 2 x = -1, 3 x = 0; so patch 2's south meets its face 1 (side 2),
    // and its face 3 (side 4) meets patch 0's west.
    const std::string swapped =
      patch_2d("1", "0 0 1 1", "0 0 1 1", "-1 -1\n-1 0\n0 -1\n0 0\n");
    MultiPatchGeometry<2> g = read_geometry_file<2>(
      write(folder,
            "lshape-swapped.xml",
            xml(square("0", 0., -1.) + swapped + square("2", -1., 0.) +
                "<MultiPatch parDim=\"2\" id=\"9\">\n"
                " <patches type=\"id_range\">0 2</patches>\n"
                " <interfaces>\n2 3 1 2\n1 4 0 1\n </interfaces>\n"
                "</MultiPatch>\n")));
    for (unsigned int p = 0; p < 3; ++p)
      subdivide(g.patches[p], spans[p]);
    return g;
  }
} // namespace glue_test



TEST(GeometryFile, GluesConformingPatchesWhateverTheirOrientation)
{
  const cli::ScratchFolder folder("geometry-glue", "unit");
  // Patch 1's direction 0 runs along y, so its spans are given swapped.
  const MultiPatchGeometry<2> g =
    glue_test::l_shape(folder, {{{{2, 3}}, {{3, 3}}, {{3, 2}}}});
  const auto [numbers, n] =
    glue_control_points(g.patches, g.interfaces, "lshape: ");
  // 3 x 4 + 4 x 4 + 4 x 3 control points, 4 + 4 shared (the point (0, 0)
  // of all three patches is one).
  EXPECT_EQ(n, 40u - 8u);
  // Independent of the matching: control points with one number coincide,
  // control points with different numbers do not.
  std::vector<std::vector<Point<2>>> at(n);
  for (unsigned int p = 0; p < 3; ++p)
    for (unsigned int a = 0; a < g.patches[p].n_control_points(); ++a)
      at[numbers[p][a]].push_back(g.patches[p].control_point(a));
  for (unsigned int i = 0; i < n; ++i)
    {
      ASSERT_FALSE(at[i].empty());
      for (const Point<2> &x : at[i])
        EXPECT_LT(x.distance(at[i][0]), 1e-14);
      for (unsigned int j = 0; j < i; ++j)
        EXPECT_GT(at[j][0].distance(at[i][0]), 0.1);
    }
  // Patch 0 keeps its own numbering.
  for (unsigned int a = 0; a < g.patches[0].n_control_points(); ++a)
    EXPECT_EQ(numbers[0][a], a);
}



TEST(GeometryFile, NonConformingInterfacesAreRefusedNamingThem)
{
  const cli::ScratchFolder folder("geometry-glue-bad", "unit");
  // Patch 0 has 3 spans along its west face, patch 1 2 along the face it
  // meets there.
  const MultiPatchGeometry<2> g =
    glue_test::l_shape(folder, {{{{2, 3}}, {{2, 3}}, {{3, 2}}}});
  try
    {
      glue_control_points(g.patches, g.interfaces, "lshape: ");
      FAIL() << "a non-conforming interface was glued";
    }
  catch (const base::ExcInput &e)
    {
      const std::string message = base::exception_message(e);
      EXPECT_NE(message.find("lshape: interface (patch 1 face 3, patch 0 "
                             "face 0) is not conforming"),
                std::string::npos)
        << message;
    }
}
