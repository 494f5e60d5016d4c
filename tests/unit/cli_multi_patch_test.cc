// Multi-patch bodies from the command line, NURBS and FE_Q(2): V2 on a
// ring of four glued patches and on a 3D slab of four patches gives the
// single-patch quarter's errors (the discrete ring is the quarter four
// times; NURBS is moreover exact in the angle on these arcs) and converges
// at the rate p + 1; a quarter of three patches gives the same errors
// whatever its middle patch's orientation; the exported analysis geometry
// reads back to the same figures; the V3 contact patch test holds with
// both contact surfaces over three glued patches; bad multi-patch input is
// refused when the scene is read.
#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

namespace multi_patch_test
{
  const std::string source(IGABDE_SOURCE_DIR);

  /// Writes a ring sector by contrib/geometry/annulus-patches with
  /// @p arguments into @p folder/@p name.
  void
  write_ring(const std::string &folder,
             const std::string &name,
             const std::string &arguments)
  {
    const auto r =
      cli::run_in(folder,
                  "python3 '" +
                    cli::join(source, "contrib/geometry/annulus-patches") +
                    "' --inner-radius 1 --radius 2 " + arguments + " > " +
                    name);
    ASSERT_EQ(r.status, 0) << r.output;
  }

  /// Runs @p scene (a path) with @p sets in @p folder/@p out and returns
  /// its summary (null if it failed).
  nlohmann::json
  run(const std::string &folder,
      const std::string &scene,
      const std::string &sets,
      const std::string &out)
  {
    const auto r = cli::run_igabde("'" + scene + "' --quiet " + sets +
                                     " --set 'Output/Directory=" + out +
                                     "' --set 'Output/Write vtu=false' "
                                     "--set 'Output/Print timing=false'",
                                   folder);
    EXPECT_EQ(r.status, 0) << r.output;
    if (r.status != 0)
      return nullptr;
    return nlohmann::json::parse(
      cli::read_file(cli::join(cli::join(folder, out), "summary.json")));
  }

  double
  l2(const nlohmann::json &summary)
  {
    return summary.is_null() ?
             1. :
             summary.at("checks").at("l2_error").get<double>();
  }

  double
  energy(const nlohmann::json &summary)
  {
    return summary.is_null() ?
             1. :
             summary.at("checks").at("energy_error").get<double>();
  }

} // namespace multi_patch_test



namespace multi_patch_test
{
  /// A G+Smo Geometry element: the multilinear box [lo, hi] (2D or 3D),
  /// its parametric directions taken in the order @p axes (axes[d] is the
  /// coordinate that direction d runs along).
  std::string
  box_patch(const unsigned int         id,
            const std::vector<double> &lo,
            const std::vector<double> &hi,
            const std::vector<int>    &axes)
  {
    const unsigned int dim = lo.size();
    const std::string  n   = std::to_string(dim);
    std::string        xml = "<Geometry type=\"TensorBSpline" + n + "\" id=\"" +
                      std::to_string(id) +
                      "\"><Basis type=\"TensorBSplineBasis" + n + "\">";
    for (unsigned int d = 0; d < dim; ++d)
      xml += "<Basis type=\"BSplineBasis\" index=\"" + std::to_string(d) +
             "\"><KnotVector degree=\"1\">0 0 1 1</KnotVector></Basis>";
    xml += "</Basis><coefs geoDim=\"" + n + "\">";
    // Control point a: bit d of a is the end of direction d.
    for (unsigned int a = 0; a < (1u << dim); ++a)
      {
        std::vector<double> x = lo;
        for (unsigned int d = 0; d < dim; ++d)
          if ((a >> d) & 1u)
            x[axes[d]] = hi[axes[d]];
        for (const double v : x)
          xml += std::to_string(v) + " ";
        xml += "\n";
      }
    return xml + "</coefs></Geometry>\n";
  }

  /// The V3 contact patch test with both blocks split along x into three
  /// glued patches of equal width, the middle patch of each turned (its
  /// directions in another order); the slave and master surfaces each span
  /// the three patches, and the meshes match (as the node-to-surface
  /// pairing needs for the patch test). Returns the scene's path.
  std::string
  write_split_patch_test(const std::string &folder, const unsigned int dim)
  {
    const bool                three = (dim == 3);
    const std::vector<double> z0 =
      three ? std::vector<double>{0.} : std::vector<double>{};
    const std::vector<double> z1 =
      three ? std::vector<double>{1.} : std::vector<double>{};
    auto with_z = [](std::vector<double> v, const std::vector<double> &z) {
      v.insert(v.end(), z.begin(), z.end());
      return v;
    };
    // A plain patch's faces: 0 x = lo, 1 x = hi, 2 y = lo, 3 y = hi
    // (4 z = lo, 5 z = hi); the turned one's directions are (y, x[, z]):
    // 0 y = lo, 1 y = hi, 2 x = lo, 3 x = hi.
    const std::vector<int> plain =
      three ? std::vector<int>{0, 1, 2} : std::vector<int>{0, 1};
    const std::vector<int> turned =
      three ? std::vector<int>{1, 0, 2} : std::vector<int>{1, 0};
    // Interfaces (G+Smo sides = face + 1): plain east (1) to turned west
    // (2), turned east (3) to plain west (0).
    const std::string multipatch =
      "<MultiPatch parDim=\"" + std::to_string(dim) +
      "\" id=\"9\"><patches type=\"id_range\">0 2</patches>"
      "<interfaces>0 2 1 3\n1 4 2 1</interfaces></MultiPatch>\n";
    // lower-shifted.xml: the lower block split elsewhere (x = 0.3, 0.7),
    // so that slave elements straddle its patch boundaries.
    const std::vector<double> thirds = {0., 1. / 3., 2. / 3., 1.};
    for (const auto &[name, y0, y1, x] :
         {std::make_tuple("upper.xml", 0., 1., thirds),
          std::make_tuple("lower.xml", -1., 0., thirds),
          std::make_tuple("lower-shifted.xml",
                          -1.,
                          0.,
                          std::vector<double>{0., 0.3, 0.7, 1.})})
      {
        std::ofstream out(cli::join(folder, name));
        out << "<xml>\n";
        for (unsigned int p = 0; p < 3; ++p)
          out << box_patch(p,
                           with_z({x[p], y0}, z0),
                           with_z({x[p + 1], y1}, z1),
                           p == 1 ? turned : plain);
        out << multipatch << "</xml>\n";
      }
    const std::string scene = cli::join(folder, "split.prm");
    // In 3D the z faces are held in z on both bodies.
    const std::string z_supports =
      three ? "; 0.4+1.4+2.4: z; 0.5+1.5+2.5: z" : std::string();
    std::ofstream(scene)
      << "set Dimension = " << dim << "\n"
      << "subsection Discretization\n  set Type = nurbs\n  set Degree = 2\n"
         "  set Refinements = 1\nend\n"
      << "subsection Body 1\n  set Geometry = file\n"
         "  set Geometry file = upper.xml\n  set Subdivisions = 2\n"
         "  set Young's modulus = 1000\n  set Poisson's ratio = 0.3\n"
         "  set Supports = 0.0: x"
      << z_supports << "\n  set Tractions = 0.3+1.1+2.3: pressure 1\nend\n"
      << "subsection Body 2\n  set Type = deformable\n"
         "  set Geometry = file\n  set Geometry file = lower.xml\n"
         "  set Subdivisions = 2\n"
         "  set Young's modulus = 1000\n  set Poisson's ratio = 0.3\n"
         "  set Supports = 0.0: x; 0.2+1.0+2.2: y"
      << z_supports << "\nend\n"
      << "subsection Contact\n  set Enabled = true\n"
         "  set Slave face = 0.2+1.0+2.2\n"
         "  set Master face = 0.3+1.1+2.3\nend\n"
      << "subsection Checks\n  set Uniform pressure = 1\nend\n";
    return scene;
  }
} // namespace multi_patch_test



TEST(CliMultiPatch, RingOfFourPatchesConvergesLikeOnePatch)
{
  using namespace multi_patch_test;
  const cli::ScratchFolder folder("multi-patch-ring");
  const std::string        ring = cli::join(source, "prm/v2-lame-ring.prm");
  const std::string quarter     = cli::join(source, "prm/v2-lame-cylinder.prm");
  for (const std::string type : {"nurbs", "lagrange"})
    {
      SCOPED_TRACE(type);
      std::vector<double> errors;
      for (const unsigned int r : {2u, 3u, 4u})
        {
          SCOPED_TRACE("Refinements = " + std::to_string(r));
          const std::string set =
            "--set Discretization/Type=" + type +
            " --set Discretization/Refinements=" + std::to_string(r);
          const std::string tag   = type + std::to_string(r);
          const auto        whole = run(folder, ring, set, "ring" + tag);
          const auto        one   = run(folder, quarter, set, "one" + tag);
          // Each of the ring's patches is the quarter's patch turned, and
          // the discrete ring is symmetric: the same errors (NURBS: the
          // same radial space, exact in the angle; FE_Q(2): the same
          // interpolated quarter, four times).
          EXPECT_NEAR(l2(whole), l2(one), 1e-8 * l2(one));
          EXPECT_NEAR(energy(whole), energy(one), 1e-8 * energy(one));
          errors.push_back(l2(whole));
          ASSERT_FALSE(whole.is_null());
          EXPECT_EQ(whole.at("bodies")[0].at("patches"), 4);
          // The exact ring's area 3 pi (rational arcs integrate exactly).
          EXPECT_NEAR(whole.at("bodies")[0].at("measure").get<double>(),
                      3. * M_PI,
                      1e-12);
          EXPECT_TRUE(whole.at("bodies")[0].at("free_rigid_modes").empty());
        }
      // L2 error of order h^(p+1) = h^3 for both (the asymptotic rate, to
      // 0.15).
      for (unsigned int k = 0; k + 1 < errors.size(); ++k)
        EXPECT_NEAR(std::log2(errors[k] / errors[k + 1]), 3., 0.15);
    }
}



TEST(CliMultiPatch, PatchesOfEitherOrientationAndFaceSumsGiveTheQuarter)
{
  using namespace multi_patch_test;
  const cli::ScratchFolder folder("multi-patch-flipped");
  // A quarter ring of three patches; in the second file the middle one
  // runs backwards in the angle (left-handed): its faces 2 and 3 swap.
  write_ring(folder.path, "quarter-3.xml", "--angle 90 --patches 3");
  write_ring(folder.path, "flipped-3.xml", "--angle 90 --patches 3 --flip-odd");
  const std::string quarter = cli::join(source, "prm/v2-lame-cylinder.prm");
  const auto set = [&](const std::string &file, const std::string &type) {
    return "--set Discretization/Type=" + type +
           " --set 'Body 1/Geometry=file' --set 'Body 1/Geometry file=" +
           cli::join(folder.path, file) +
           "' --set 'Body 1/Supports=0.2: y; 2.3: x' --set 'Body "
           "1/Tractions=0.0+1.0+2.0: pressure 1' --set "
           "Discretization/Refinements=3";
  };
  for (const std::string type : {"nurbs", "lagrange"})
    {
      SCOPED_TRACE(type);
      const auto three =
        run(folder, quarter, set("quarter-3.xml", type), "three-" + type);
      const auto flipped =
        run(folder, quarter, set("flipped-3.xml", type), "flipped-" + type);
      // The same mesh and map, numbered otherwise.
      EXPECT_NEAR(l2(flipped), l2(three), 1e-8 * l2(three));
      EXPECT_NEAR(energy(flipped), energy(three), 1e-8 * energy(three));
      ASSERT_FALSE(flipped.is_null());
      EXPECT_NEAR(flipped.at("bodies")[0].at("measure").get<double>(),
                  0.75 * M_PI,
                  1e-12);
      if (type == "nurbs")
        {
          // Exact in the angle: the single patch's errors.
          const auto one =
            run(folder, quarter, "--set Discretization/Refinements=3", "one");
          EXPECT_NEAR(l2(flipped), l2(one), 1e-8 * l2(one));
          EXPECT_NEAR(energy(flipped), energy(one), 1e-8 * energy(one));
        }
    }
}



TEST(CliMultiPatch, SlabOfFourPatchesIsThePlaneStrainRing)
{
  using namespace multi_patch_test;
  const cli::ScratchFolder folder("multi-patch-slab");
  write_ring(folder.path, "slab.xml", "--patches 4 --width 1 --flip-odd");
  const std::string quarter = cli::join(source, "prm/v2-lame-cylinder-3d.prm");
  for (const std::string type : {"nurbs", "lagrange"})
    {
      SCOPED_TRACE(type);
      const std::string common = "--set Discretization/Type=" + type +
                                 " --set Discretization/Refinements=1";
      const std::string set =
        common + " --set 'Body 1/Geometry=file' --set 'Body 1/Geometry file=" +
        cli::join(folder.path, "slab.xml") +
        "' --set 'Body 1/Supports=0.4+1.4+2.4+3.4: z; 0.5+1.5+2.5+3.5: z' "
        "--set 'Body 1/Point supports=1, 0, 0: y; -1, 0, 0: y; 0, 1, 0: x' "
        "--set 'Body 1/Tractions=0.0+1.0+2.0+3.0: pressure 1'";
      const auto slab = run(folder, quarter, set, "slab-" + type);
      const auto one  = run(folder, quarter, common, "one-" + type);
      EXPECT_NEAR(l2(slab), l2(one), 1e-8 * l2(one));
      EXPECT_NEAR(energy(slab), energy(one), 1e-8 * energy(one));
      ASSERT_FALSE(slab.is_null());
      EXPECT_NEAR(slab.at("bodies")[0].at("measure").get<double>(),
                  3. * M_PI,
                  1e-12);
    }
}



TEST(CliMultiPatch, PatchesThatOnlyTouchStayApart)
{
  using namespace multi_patch_test;
  const cli::ScratchFolder folder("multi-patch-slit");
  // The ring without its last interface (patch 3 to patch 0 at theta = 0):
  // the faces there touch but are not glued, a slit.
  std::ifstream in(cli::join(source, "prm/geometry/annulus-4.xml"));
  std::ofstream out(cli::join(folder.path, "slit.xml"));
  std::string   line;
  while (std::getline(in, line))
    if (line != "3 4 0 3")
      out << line << "\n";
  out.close();
  const std::string ring = cli::join(source, "prm/v2-lame-ring.prm");
  // The slit's face carries its own unknowns on both sides: at Refinements
  // = 3 the radial face of a patch has 2 + 8 = 10 control points (degree 2,
  // 8 spans) and 2 * 8 + 1 = 17 FE_Q(2) nodes, two components each.
  for (const auto &[type, extra] :
       {std::make_pair(std::string("nurbs"), 20),
        std::make_pair(std::string("lagrange"), 34)})
    {
      SCOPED_TRACE(type);
      const std::string set    = "--set Discretization/Type=" + type;
      const auto        closed = run(folder, ring, set, "closed-" + type);
      const auto        slit   = run(folder,
                            ring,
                            set + " --set 'Body 1/Geometry file=" +
                              cli::join(folder.path, "slit.xml") + "'",
                            "slit-" + type);
      ASSERT_FALSE(closed.is_null());
      ASSERT_FALSE(slit.is_null());
      EXPECT_EQ(slit.at("n_dofs").get<int>(),
                closed.at("n_dofs").get<int>() + extra);
    }
}



TEST(CliMultiPatch, ExportedRingReadsBackToTheSameFigures)
{
  using namespace multi_patch_test;
  const cli::ScratchFolder folder("multi-patch-export");
  const std::string        ring = cli::join(source, "prm/v2-lame-ring.prm");
  const auto first = run(folder, ring, "--export-geometry", "first");
  // The analysis geometry (after Refinements = 3) read as the file, not
  // refined again.
  const auto again = run(folder,
                         ring,
                         "--set 'Body 1/Geometry file=" +
                           cli::join(folder.path, "first/body1-geometry.xml") +
                           "' --set Discretization/Refinements=0",
                         "again");
  ASSERT_FALSE(first.is_null());
  ASSERT_FALSE(again.is_null());
  EXPECT_EQ(again.at("n_dofs"), first.at("n_dofs"));
  EXPECT_EQ(again.at("bodies")[0].at("patches"), 4);
  EXPECT_NEAR(l2(again), l2(first), 1e-12 * l2(first));
  EXPECT_NEAR(energy(again), energy(first), 1e-12 * energy(first));
}



TEST(CliMultiPatch, BadMultiPatchInputIsRefusedWhenRead)
{
  using namespace multi_patch_test;
  const cli::ScratchFolder folder("multi-patch-bad");
  const std::string ring = "'" + cli::join(source, "prm/v2-lame-ring.prm") +
                           "' --set Output/Directory=out ";
  cli::expect_refused(
    ring + "--set 'Body 1/Supports=4.2: y'",
    folder,
    "Body 1/Supports: face 4.2 is on patch 4, but the geometry "
    "has 4 patches");
  cli::expect_refused("'" + cli::join(source, "prm/v2-lame-cylinder.prm") +
                        "' --set 'Body 1/Supports=1.2: y'",
                      folder,
                      "Body 1/Supports: face '1.2' in '1.2: y' must be a patch "
                      "face 0..3");
  // Subdivisions apply per direction of each patch: a patch of the ring
  // turned by 90 degrees in its parameters would not match; here two
  // rings of different spans along the angle cannot be told apart, so the
  // L of unit squares with its middle patch transposed is used.
  std::ofstream(cli::join(folder.path, "l.xml"))
    << "<xml>\n"
    << "<Geometry type=\"TensorBSpline2\" id=\"0\"><Basis "
       "type=\"TensorBSplineBasis2\"><Basis type=\"BSplineBasis\" "
       "index=\"0\"><KnotVector degree=\"1\">0 0 1 1</KnotVector></Basis>"
       "<Basis type=\"BSplineBasis\" index=\"1\"><KnotVector degree=\"1\">0 "
       "0 1 1</KnotVector></Basis></Basis><coefs geoDim=\"2\">0 -1 1 -1 0 0 "
       "1 0</coefs></Geometry>\n"
    << "<Geometry type=\"TensorBSpline2\" id=\"1\"><Basis "
       "type=\"TensorBSplineBasis2\"><Basis type=\"BSplineBasis\" "
       "index=\"0\"><KnotVector degree=\"1\">0 0 1 1</KnotVector></Basis>"
       "<Basis type=\"BSplineBasis\" index=\"1\"><KnotVector degree=\"1\">0 "
       "0 1 1</KnotVector></Basis></Basis><coefs geoDim=\"2\">-1 -1 -1 0 0 "
       "-1 0 0</coefs></Geometry>\n"
    << "<MultiPatch parDim=\"2\" id=\"9\"><patches type=\"id_range\">0 "
       "1</patches><interfaces>1 4 0 1</interfaces></MultiPatch>\n"
    << "</xml>\n";
  cli::expect_refused(ring + "--set 'Body 1/Geometry file=" +
                        cli::join(folder.path, "l.xml") +
                        "' --set 'Body 1/Point supports=' --set 'Body "
                        "1/Tractions=' --set 'Body 1/Supports=0.2: x y' --set "
                        "'Body 1/Subdivisions=2, 3'",
                      folder,
                      "interface (patch 1 face 3, patch 0 face 0) is not "
                      "conforming after Degree, Subdivisions and Refinements");
  EXPECT_FALSE(std::filesystem::exists(cli::join(folder.path, "out")));
}



TEST(CliMultiPatch, ContactSurfacesOverThreePatchesPassThePatchTest)
{
  using namespace multi_patch_test;
  for (const std::string type : {"nurbs", "lagrange"})
    for (const unsigned int dim : {2u, 3u})
      {
        SCOPED_TRACE(type + " " + std::to_string(dim) + "D");
        const cli::ScratchFolder folder("multi-patch-contact-" + type +
                                        std::to_string(dim));
        const std::string scene = write_split_patch_test(folder.path, dim);
        const std::string discretization = "--set Discretization/Type=" + type;
        // Node-to-surface, both surfaces over three patches.
        const auto s = run(folder.path, scene, discretization, "out");
        ASSERT_FALSE(s.is_null());
        // Every pair carries the applied pressure (the criterion of V3).
        EXPECT_LT(s.at("checks").at("pressure_uniformity").get<double>(), 1e-8);
        EXPECT_EQ(s.at("bodies")[0].at("patches"), 3);
        EXPECT_EQ(s.at("bodies")[1].at("patches"), 3);
        // Weighted gap: the slave surface over three patches against a
        // one-patch block of three spans per direction, whose mesh does not
        // match (the mortar pairing passes the patch test there too).
        const std::string block =
          dim == 2 ? "--set 'Body 2/Lower corner=0, -1' --set 'Body 2/Upper "
                     "corner=1, 0' --set 'Body 2/Supports=0: x; 2: y'" :
                     "--set 'Body 2/Lower corner=0, -1, 0' --set 'Body "
                     "2/Upper corner=1, 0, 1' --set 'Body 2/Supports=0: x; "
                     "2: y; 4: z; 5: z'";
        const auto w =
          run(folder.path,
              scene,
              discretization +
                " --set 'Body 2/Geometry=box' --set 'Body 2/Subdivisions=3' " +
                block +
                " --set 'Contact/Master face=3' --set "
                "Contact/Pairing=weighted-gap",
              "weighted");
        ASSERT_FALSE(w.is_null());
        EXPECT_LT(w.at("checks").at("pressure_uniformity").get<double>(), 1e-8);
        // Weighted gap with the master surface over three patches too,
        // split where the slave's are not (slave elements straddle its
        // patch boundaries) and with three spans per patch.
        const auto m = run(folder.path,
                           scene,
                           discretization +
                             " --set 'Body 2/Geometry file=lower-shifted.xml' "
                             "--set 'Body 2/Subdivisions=3' --set "
                             "Contact/Pairing=weighted-gap",
                           "master");
        ASSERT_FALSE(m.is_null());
        EXPECT_LT(m.at("checks").at("pressure_uniformity").get<double>(), 1e-8);
      }
}
