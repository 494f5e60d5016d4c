#include <igabde/base/disjoint_sets.h>
#include <igabde/base/files.h>
#include <igabde/base/utilities.h>

#include <igabde/nurbs/geometry_builders.h>
#include <igabde/nurbs/geometry_file.h>
#include <igabde/nurbs/multi_patch.h>

#include <igabde/discretization/body_description.h>

#include <igabde/scene/geometry.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /// The patches and interfaces of the body's geometry file.
      template <int dim>
      nurbs::MultiPatchGeometry<dim>
      read_patches(const BodyParameters &body, const std::string &where)
      {
        try
          {
            return nurbs::read_geometry_file<dim>(body.geometry_path);
          }
        catch (const base::ExcInput &e)
          {
            AssertThrow(false,
                        base::ExcInput(where + base::exception_message(e)));
          }
        return {};
      }
    } // namespace



    unsigned int
    check_geometry_file(const BodyParameters &body,
                        const unsigned int    dimension,
                        const unsigned int    degree,
                        const std::string    &where)
    {
      // Read, and for several patches also subdivided and glued: an
      // interface that Subdivisions or Grading make non-conforming is
      // refused now, before anything is built.
      const auto check = [&](const auto &file) -> unsigned int {
        const unsigned int n = file.patches.size();
        if (n == 1)
          return 1;
        // A body is one piece: every patch reached through interfaces.
        base::DisjointSets pieces(n);
        for (const auto &i : file.interfaces)
          pieces.join(i.patch[0], i.patch[1]);
        for (unsigned int p = 0; p < n; ++p)
          AssertThrow(pieces.find(p) == 0,
                      base::ExcInput(
                        where + body.geometry_path + " holds " +
                        std::to_string(n) +
                        " patches, but no interface "
                        "joins patch " +
                        std::to_string(p) +
                        " to patch 0: a body is one connected piece; list "
                        "the interfaces in a MultiPatch element (patch, "
                        "side, patch, side per line), or put separate parts "
                        "in separate bodies."));
        return n;
      };
      if (dimension == 2)
        {
          const unsigned int n = check(read_patches<2>(body, where));
          if (n > 1)
            make_geometry<2>(body, where, degree);
          return n;
        }
      const unsigned int n = check(read_patches<3>(body, where));
      if (n > 1)
        make_geometry<3>(body, where, degree);
      return n;
    }



    template <int dim>
    nurbs::MultiPatchGeometry<dim>
    make_geometry(const BodyParameters          &body,
                  const std::string             &where,
                  const unsigned int             degree,
                  std::array<unsigned int, dim> *subdivisions)
    {
      const auto need_2d = [&]() {
        AssertThrow(dim == 2,
                    base::ExcInput(where +
                                   "Geometry = " + to_string(body.geometry) +
                                   " is a 2D geometry; set Dimension = 2 "
                                   "or choose a 3D geometry."));
      };
      const auto need_3d = [&]() {
        AssertThrow(dim == 3,
                    base::ExcInput(where +
                                   "Geometry = " + to_string(body.geometry) +
                                   " is a 3D geometry; set Dimension = 3."));
      };
      AssertThrow(body.geometry == Geometry::box ||
                    body.geometry == Geometry::file ||
                    body.geometry == Geometry::plate_with_hole ||
                    body.geometry == Geometry::hertz_quarter_disc ||
                    body.geometry == Geometry::full_disc ||
                    body.geometry == Geometry::half_disc ||
                    body.geometry == Geometry::full_cylinder ||
                    body.geometry == Geometry::half_cylinder ||
                    body.inner_radius < body.outer_radius,
                  base::ExcInput(where + "Inner radius (" +
                                 std::to_string(body.inner_radius) +
                                 ") must be smaller than Outer radius (" +
                                 std::to_string(body.outer_radius) + ")."));

      nurbs::NurbsPatch<dim>         patch;
      nurbs::MultiPatchGeometry<dim> file;
      if (body.geometry == Geometry::box)
        {
          // Empty corners: the unit box [0, 1]^dim.
          Point<dim> lo, hi;
          for (unsigned int d = 0; d < dim; ++d)
            hi[d] = 1.;
          for (unsigned int d = 0; d < dim && !body.lower_corner.empty(); ++d)
            lo[d] = body.lower_corner[d];
          for (unsigned int d = 0; d < dim && !body.upper_corner.empty(); ++d)
            hi[d] = body.upper_corner[d];
          for (unsigned int d = 0; d < dim; ++d)
            AssertThrow(lo[d] < hi[d],
                        base::ExcInput(where + "Lower corner must be below "
                                               "Upper corner in every "
                                               "coordinate."));
          patch = nurbs::make_box<dim>(lo, hi);
        }
      else if (body.geometry == Geometry::quarter_annulus ||
               body.geometry == Geometry::thick_cylinder)
        {
          if constexpr (dim == 2)
            patch =
              nurbs::make_quarter_annulus(body.inner_radius, body.outer_radius);
          else
            patch = nurbs::make_thick_cylinder_quarter<dim>(body.inner_radius,
                                                            body.outer_radius,
                                                            body.width);
        }
      else if (body.geometry == Geometry::plate_with_hole)
        {
          need_2d();
          if constexpr (dim == 2)
            patch =
              nurbs::make_plate_with_hole(body.inner_radius, body.plate_size);
        }
      else if (body.geometry == Geometry::hertz_quarter_disc)
        {
          need_2d();
          if constexpr (dim == 2)
            patch = nurbs::make_hertz_quarter_disc(body.radius);
        }
      else if (body.geometry == Geometry::full_disc ||
               body.geometry == Geometry::half_disc ||
               body.geometry == Geometry::full_cylinder ||
               body.geometry == Geometry::half_cylinder)
        {
          const bool cylinder = (body.geometry == Geometry::full_cylinder ||
                                 body.geometry == Geometry::half_cylinder);
          cylinder ? need_3d() : need_2d();
          AssertThrow(body.radius > 0.,
                      base::ExcInput(where +
                                     "Radius = " + std::to_string(body.radius) +
                                     " must be > 0 for Geometry = " +
                                     to_string(body.geometry) + "."));
          AssertThrow(!cylinder || body.width > 0.,
                      base::ExcInput(where +
                                     "Width = " + std::to_string(body.width) +
                                     " must be > 0 for Geometry = " +
                                     to_string(body.geometry) + "."));
          Point<dim> c;
          for (unsigned int d = 0; d < dim && !body.centre.empty(); ++d)
            c[d] = body.centre[d];
          const bool full = (body.geometry == Geometry::full_disc ||
                             body.geometry == Geometry::full_cylinder);
          if constexpr (dim == 2)
            patch = full ? nurbs::make_full_disc(c, body.radius) :
                           nurbs::make_half_disc(c, body.radius);
          else
            patch = nurbs::make_cylinder(c, body.radius, body.width, full);
        }
      else if (body.geometry == Geometry::file)
        {
          file =
            read_patches<dim>(body,
                              where + "Geometry file = " + body.geometry_file +
                                ": ");
          patch = file.patches.front();
        }
      else if (body.geometry == Geometry::curved_beam)
        {
          need_3d();
          if constexpr (dim == 3)
            patch = nurbs::make_curved_beam(body.inner_radius,
                                            body.outer_radius,
                                            body.width);
        }
      else
        AssertThrow(false,
                    base::ExcInput(where + "Geometry = '" +
                                   to_string(body.geometry) + "' is unknown."));

      // A built-in shape is one patch.
      if (body.geometry != Geometry::file)
        file.patches = {patch};

      // Read and checked with the scene (BodyParameters::parse_parameters).
      std::array<unsigned int, dim> n_spans;
      for (unsigned int d = 0; d < dim; ++d)
        n_spans[d] = body.subdivisions[d];
      // k-refinement: elevate first, then insert knots, so that the base
      // subdivisions (and later refinements) give C^{p-1} spaces, not the C0
      // space that inserting before elevating would leave.
      for (auto &part : file.patches)
        nurbs::elevate_to_degree(part, degree);

      // Point loads lie in or on the body: checked here, when the scene is
      // read, on copies split into at most 8 parts per span (starting
      // points enough for the closest-point Newton; the image is the same).
      if (!body.point_loads.empty())
        {
          std::vector<nurbs::NurbsPatch<dim>> checks;
          Point<dim> lo = file.patches[0].control_point(0), hi = lo;
          for (const auto &part : file.patches)
            {
              nurbs::NurbsPatch<dim>        check = part;
              std::array<unsigned int, dim> parts;
              for (unsigned int d = 0; d < dim; ++d)
                parts[d] = std::min(n_spans[d], 8u);
              nurbs::subdivide(check, parts);
              for (unsigned int a = 0; a < check.n_control_points(); ++a)
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    lo[d] = std::min(lo[d], check.control_point(a)[d]);
                    hi[d] = std::max(hi[d], check.control_point(a)[d]);
                  }
              checks.push_back(std::move(check));
            }
          const double diameter = (hi - lo).norm();
          for (const auto &load : body.point_loads)
            {
              Point<dim> x;
              for (unsigned int d = 0; d < dim; ++d)
                x[d] = load.location[d];
              double     distance = std::numeric_limits<double>::max();
              Point<dim> closest;
              for (const auto &check : checks)
                {
                  double           d = 0.;
                  const Point<dim> xi =
                    check.closest_parametric_point(x, nullptr, &d);
                  if (d < distance)
                    {
                      distance = d;
                      closest  = check.value(xi);
                    }
                }
              // The coincidence tolerance of the pairing (doc/robustness.md).
              if (distance > 1e-8 * diameter)
                {
                  std::ostringstream m;
                  m << where << "Point loads: the point (" << x
                    << ") is not in the body (distance " << distance
                    << " from its closest point (" << closest
                    << ")); give a point in or on the body.";
                  AssertThrow(false, base::ExcInput(m.str()));
                }
            }
        }

      if (subdivisions != nullptr)
        *subdivisions = n_spans;
      else
        {
          std::array<double, dim>                grading;
          std::array<bool, dim>                  toward_high;
          std::array<std::array<double, 2>, dim> bands;
          for (unsigned int d = 0; d < dim; ++d)
            {
              grading[d]     = body.grading[d];
              toward_high[d] = body.grading_toward_high[d];
              bands[d]       = d < body.grading_band.size() ?
                                 body.grading_band[d] :
                                 std::array<double, 2>{{0., 0.}};
            }
          for (auto &part : file.patches)
            nurbs::subdivide(part, n_spans, grading, toward_high, bands);
          // Subdivisions apply per parametric direction of each patch, so
          // they may leave an interface non-conforming: refused here.
          if (file.patches.size() > 1)
            nurbs::glue_control_points(file.patches,
                                       file.interfaces,
                                       where + "Geometry file = " +
                                         body.geometry_file + ": ");
        }
      return file;
    }



    std::vector<std::string>
    patch_faces(const Geometry geometry, const unsigned int dimension)
    {
      // As the builders in nurbs/geometry_builders.h number them: face f at
      // the low (f even) or high (f odd) end of parametric direction f/2.
      if (geometry == Geometry::box)
        {
          std::vector<std::string> faces = {"x = lower",
                                            "x = upper",
                                            "y = lower",
                                            "y = upper"};
          if (dimension == 3)
            faces.insert(faces.end(), {"z = lower", "z = upper"});
          return faces;
        }
      if (geometry == Geometry::quarter_annulus ||
          geometry == Geometry::thick_cylinder)
        {
          std::vector<std::string> faces = {"inner arc r = r0",
                                            "outer arc r = r1",
                                            "theta = 0 (y = 0)",
                                            "theta = 90 deg (x = 0)"};
          if (dimension == 3)
            faces.insert(faces.end(), {"z = 0", "z = width"});
          return faces;
        }
      if (geometry == Geometry::plate_with_hole && dimension == 2)
        return {"the hole",
                "the outer edges x = L, y = L",
                "symmetry edge y = 0",
                "symmetry edge x = 0"};
      if (geometry == Geometry::hertz_quarter_disc && dimension == 2)
        return {"symmetry segment x = 0",
                "upper arc",
                "lower arc (contact)",
                "cut y = R"};
      if ((geometry == Geometry::full_disc && dimension == 2) ||
          (geometry == Geometry::full_cylinder && dimension == 3))
        {
          std::vector<std::string> faces = {"left arc",
                                            "right arc",
                                            "bottom arc",
                                            "top arc"};
          if (dimension == 3)
            faces.insert(faces.end(), {"z = Centre z", "z = Centre z + Width"});
          return faces;
        }
      if ((geometry == Geometry::half_disc && dimension == 2) ||
          (geometry == Geometry::half_cylinder && dimension == 3))
        {
          std::vector<std::string> faces = {"left arc",
                                            "right arc",
                                            "bottom arc",
                                            "diameter y = Centre y"};
          if (dimension == 3)
            faces.insert(faces.end(), {"z = Centre z", "z = Centre z + Width"});
          return faces;
        }
      if (geometry == Geometry::curved_beam && dimension == 3)
        return {"inner face r = r0",
                "outer face r = r1",
                "theta = 0 (z = 0)",
                "theta = 90 deg (x = 0)",
                "y = 0",
                "y = width"};
      if (geometry == Geometry::file)
        {
          std::vector<std::string> faces = {"xi_0 = low",
                                            "xi_0 = high",
                                            "xi_1 = low",
                                            "xi_1 = high"};
          if (dimension == 3)
            faces.insert(faces.end(), {"xi_2 = low", "xi_2 = high"});
          return faces;
        }
      return {};
    }



    template <int dim>
    nlohmann::json
    body_record(const BodyParameters            &parameters,
                const unsigned int               degree,
                const discretization::Body<dim> &body)
    {
      // The measure of the exact geometry, from its patches before
      // Subdivisions and Refinements (the same map with the fewest spans:
      // the quadrature cost does not grow with the mesh).
      std::array<unsigned int, dim>        subdivisions;
      const nurbs::MultiPatchGeometry<dim> coarse =
        make_geometry<dim>(parameters, "", degree, &subdivisions);
      double measure = 0.;
      for (const auto &patch : coarse.patches)
        measure += nurbs::patch_measure(patch);
      // Control points of the analysis space: a NURBS body's glued ones,
      // the geometry map's of a (single-patch) Lagrange body.
      const unsigned int n_control_points =
        body.n_patches() == 1 ? body.geometry_patch(0).n_control_points() :
                                static_cast<unsigned int>(body.n_dofs() / dim);
      return nlohmann::json{{"geometry",
                             parameters.geometry == Geometry::file ?
                               parameters.geometry_file :
                               to_string(parameters.geometry)},
                            {"patches", coarse.patches.size()},
                            {"control_points", n_control_points},
                            {"measure", measure},
                            {"name", body.name()},
                            {"n_dofs",
                             static_cast<unsigned long long>(body.n_dofs())},
                            {"n_elements", body.n_elements()},
                            {"matrix_entries", body.n_matrix_entries()},
                            {"free_rigid_modes", body.free_rigid_mode_names()},
                            {"held_rigid_modes", body.held_rigid_mode_names()}};
    }



    template <int dim>
    void
    export_geometry(const discretization::Body<dim> &body,
                    const std::string               &directory)
    {
      nurbs::MultiPatchGeometry<dim> geometry;
      for (unsigned int p = 0; p < body.n_patches(); ++p)
        geometry.patches.push_back(body.geometry_patch(p));
      geometry.interfaces     = body.description().interfaces;
      const std::string  name = body.name();
      std::ostringstream xml;
      nurbs::write_geometry_file(geometry, xml);
      base::write_file_atomically(directory + "/" + name + "-geometry.xml",
                                  xml.str());
      std::ofstream vtu(directory + "/" + name + "-control-net.vtu");
      nurbs::write_control_net_vtu(geometry, vtu);
      AssertThrow(vtu.good(),
                  base::ExcInput("cannot write " + directory + "/" + name +
                                 "-control-net.vtu; check that the output "
                                 "folder is writable."));
    }



    template nlohmann::json
    body_record(const BodyParameters &,
                unsigned int,
                const discretization::Body<2> &);
    template nlohmann::json
    body_record(const BodyParameters &,
                unsigned int,
                const discretization::Body<3> &);
    template void
    export_geometry<2>(const discretization::Body<2> &, const std::string &);
    template void
    export_geometry<3>(const discretization::Body<3> &, const std::string &);
    template nurbs::MultiPatchGeometry<2>
    make_geometry<2>(const BodyParameters &,
                     const std::string &,
                     unsigned int,
                     std::array<unsigned int, 2> *);
    template nurbs::MultiPatchGeometry<3>
    make_geometry<3>(const BodyParameters &,
                     const std::string &,
                     unsigned int,
                     std::array<unsigned int, 3> *);
  } // namespace scene
} // namespace igabde
