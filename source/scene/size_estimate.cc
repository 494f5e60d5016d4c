#include <igabde/base/utilities.h>

#include <igabde/scene/geometry.h>
#include <igabde/scene/size_estimate.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>
#include <unistd.h>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /**
       * Factor entries per k^2 w^2 n log2(n) (2D) or k^2 w^2 n^{4/3} (3D),
       * where n counts nodes (control points), k the components and w the
       * width of a separator in node layers (p for a C^{p-1} spline, about
       * (q+1)/2 for FE_Q(q)). Measured with MUMPS' nested-dissection
       * factorisation (the larger ratio seen on V5, B2, NURBS p = 2, 3 and
       * FE_Q(1), FE_Q(2), with a margin for the pre-asymptotic growth in
       * 3D): doc/robustness.md.
       */
      constexpr double factor_constant_2d = 3.;
      constexpr double factor_constant_3d = 10.;

      /**
       * Factor entries of a nested dissection of an n[0] x n[1] x n[2]
       * node grid with k unknowns per node and separators w node layers
       * wide: cut the longest direction, count the separator's front (its
       * unknowns times themselves and the rim of the ancestors' separators
       * around it), recurse into the halves. Unlike k^2 w^2 n^{4/3}, it
       * sees that a thin slab factorises like a 2D grid of columns.
       */
      double
      bisection_factor_entries(std::array<double, 3> n,
                               const double          k,
                               const double          w)
      {
        std::sort(n.begin(), n.end(), std::greater<double>());
        if (n[0] <= 2. * w + 1.)
          {
            const double u = k * n[0] * n[1] * n[2];
            return u * u / 2.;
          }
        const double separator = k * w * n[1] * n[2];
        const double rim       = k * w * 2. * (n[1] * w + n[2] * w);
        return separator * (separator / 2. + rim) +
               2. * bisection_factor_entries({{(n[0] - w) / 2., n[1], n[2]}},
                                             k,
                                             w);
      }

      /**
       * MUMPS' factor entries over bisection_factor_entries(), the largest
       * seen (B2's beam at 16x64x16, NURBS p = 2; the others 1.0 to 2.7:
       * boxes and slabs from 10x10x10 to 80x80x1 spans, NURBS p = 2, 3 and
       * FE_Q(2); doc/robustness.md).
       */
      constexpr double bisection_constant = 3.7;

      /// Bytes per sparse-matrix entry: the value and column index of the
      /// assembled matrix (12) and the solver's copy of its upper triangle
      /// (16 per entry, half of them).
      constexpr double bytes_per_matrix_entry = 20.;
      /// Bytes per factor entry: the value and the solver's working space
      /// (MUMPS' default relaxation, 20 %, rounded up).
      constexpr double bytes_per_factor_entry = 8. * 1.25;

      /// Resident size of an igabde process before the scene is built,
      /// taken from the resident set a small scene (V3 2D, 144 unknowns)
      /// ends with (doc/robustness.md).
      constexpr double bytes_per_process = 170. * 1024. * 1024.;



      template <int dim>
      SizeEstimate::BodySize
      estimate_body(const BodyParameters                         &body,
                    const std::string                            &name,
                    const discretization::DiscretizationSettings &settings,
                    const unsigned int                            refinements,
                    const std::vector<unsigned int>              &contact_faces,
                    const std::string                            &scene_file)
      {
        // The exact geometry before its subdivisions (a split beyond the
        // memory must not be built to be counted).
        std::array<unsigned int, dim>        subdivisions;
        const nurbs::MultiPatchGeometry<dim> patches =
          make_geometry<dim>(body,
                             scene_file + ": " + name + "/",
                             settings.degree,
                             &subdivisions);
        const bool   nurbs = (settings.type == discretization::Type::nurbs);
        const double split = std::pow(2., refinements);
        std::array<double, dim> nodes;
        SizeEstimate::BodySize  size;
        size.name       = name;
        size.n_elements = 0.;
        // Separator width (node layers) and matrix entries per row and
        // component, per direction; nodes of all patches (an interface's
        // shared nodes counted twice: an upper bound).
        double width = 0., couplings = 1., n = 0.;
        for (unsigned int p = 0; p < patches.patches.size(); ++p)
          {
            const nurbs::NurbsPatch<dim> &geometry = patches.patches[p];
            double                        elements = 1., patch_couplings = 1.;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double base_spans = geometry.breakpoints(d).size() - 1.;
                const double spans      = base_spans * subdivisions[d];
                elements *= spans * split;
                if (nurbs)
                  {
                    const unsigned int degree = geometry.degree(d);
                    // Subdivisions and refinements insert simple knots.
                    nodes[d] = geometry.n_control_points(d) +
                               base_spans * (subdivisions[d] * split - 1.);
                    patch_couplings *= 2. * degree + 1.;
                    width = std::max(width, double(degree));
                  }
                else
                  {
                    const double q = settings.degree;
                    nodes[d]       = q * spans * split + 1.;
                    // A node on a cell edge couples with 2q+1 nodes, one inside
                    // a cell with q+1.
                    patch_couplings *=
                      ((2. * q + 1.) + (q - 1.) * (q + 1.)) / q;
                    width = std::max(width, (q + 1.) / 2.);
                  }
              }
            size.n_elements += elements;
            couplings          = std::max(couplings, patch_couplings);
            double patch_nodes = 1.;
            for (unsigned int d = 0; d < dim; ++d)
              patch_nodes *= nodes[d];
            n += patch_nodes;
            // The contact faces of this patch (of several, their shared
            // nodes counted twice).
            for (const unsigned int contact_face : contact_faces)
              if (p == contact_face / (2 * dim))
                {
                  double face = 1.;
                  for (unsigned int d = 0; d < dim; ++d)
                    if (d != (contact_face % (2 * dim)) / 2)
                      face *= nodes[d];
                  size.face_unknowns += dim * face;
                }
          }
        const double k      = dim;
        size.n_unknowns     = k * n;
        size.matrix_entries = k * k * n * couplings;
        const double growth =
          (dim == 2 ? n * std::log2(std::max(n, 2.)) : n * std::cbrt(n));
        size.factor_entries =
          (dim == 2 ? factor_constant_2d : factor_constant_3d) * k * k * width *
          width * growth;
        // Nested bisection of one patch's node grid.
        if (dim == 3 && patches.patches.size() == 1)
          size.factor_entries =
            std::min(size.factor_entries,
                     bisection_constant *
                       bisection_factor_entries({{nodes[0],
                                                  nodes[dim > 1 ? 1 : 0],
                                                  nodes[dim > 2 ? 2 : 0]}},
                                                k,
                                                width));
        size.factor_entries =
          std::min(size.factor_entries, size.n_unknowns * size.n_unknowns / 2.);
        return size;
      }



      template <int dim>
      SizeEstimate
      estimate(const AllParameters &parameters,
               const std::string   &scene_file,
               const unsigned int   refinements)
      {
        const auto &c = parameters.contact;
        // A body's contact faces in every interaction (none without
        // contact), and whether it is a slave in one.
        const auto contact_faces = [&](const unsigned int b) {
          std::vector<unsigned int> faces;
          if (c.enabled)
            for (const InteractionParameters &i : c.interactions)
              {
                if (i.slave_body == b + 1)
                  faces.insert(faces.end(),
                               i.slave_faces.begin(),
                               i.slave_faces.end());
                if (i.master_body == b + 1)
                  faces.insert(faces.end(),
                               i.master_faces.begin(),
                               i.master_faces.end());
              }
          return faces;
        };
        SizeEstimate      e;
        std::vector<bool> slave;
        e.bytes_process = bytes_per_process;
        for (const unsigned int b : parameters.deformable_bodies())
          {
            e.bodies.push_back(
              estimate_body<dim>(parameters.bodies[b],
                                 "Body " + std::to_string(b + 1),
                                 parameters.discretization,
                                 refinements,
                                 contact_faces(b),
                                 scene_file));
            slave.push_back(std::any_of(c.interactions.begin(),
                                        c.interactions.end(),
                                        [&](const auto &i) {
                                          return i.slave_body == b + 1;
                                        }));
          }
        const bool friction = std::any_of(c.interactions.begin(),
                                          c.interactions.end(),
                                          [](const auto &i) {
                                            return i.friction_coefficient > 0.;
                                          });
        const bool direct   = (parameters.discretization.linear_solver !=
                             discretization::LinearSolver::cg_amg);
        double     vectors  = 0.;
        for (const auto &b : e.bodies)
          {
            e.bytes_matrix += bytes_per_matrix_entry * b.matrix_entries;
            // Multigrid hierarchy: about the matrix again.
            e.bytes_factor +=
              (direct ? bytes_per_factor_entry * b.factor_entries :
                        12. * b.matrix_entries);
            // Solution, load and prescribed fields, right-hand sides.
            vectors += 8. * 8. * b.n_unknowns;
          }
        e.bytes_matrix += vectors;
        if (c.enabled)
          {
            // One pair per node of a slave's contact faces.
            double pairs = 0.;
            for (unsigned int b = 0; b < e.bodies.size(); ++b)
              if (slave[b])
                pairs += e.bodies[b].face_unknowns / static_cast<double>(dim);
            e.contact_unknowns = pairs * (friction ? dim : 1.);
            const double n_c   = e.contact_unknowns;
            // Schur complement and its product with the point operators per
            // body; flexibility, Newton matrix and its factor.
            for (const auto &b : e.bodies)
              e.bytes_dense += 8. * (b.face_unknowns * b.face_unknowns +
                                     b.face_unknowns * n_c);
            e.bytes_dense += 8. * 3. * n_c * n_c;
            // The coupled system: both bodies' matrices again (Trilinos'
            // copy) and, direct, MUMPS' LU of the whole: L and U, of the
            // bodies pressed face to face and factorised as one, in the
            // nested-dissection order: 1.75 times the bodies' estimated
            // factors together (three before that order; 1.5 while the
            // bodies' own factors stayed in memory beside it and covered
            // the rest; the 3D contact-patch family's peak memory against
            // this estimate: doc/performance.md).
            double matrix = 0., factor = 0.;
            for (const auto &b : e.bodies)
              {
                matrix += b.matrix_entries;
                factor += b.factor_entries;
              }
            e.bytes_coupled =
              bytes_per_matrix_entry * matrix +
              (c.full_system_solver == coupled::Solver::gmres_amg ?
                 12. * matrix :
                 bytes_per_factor_entry * 1.75 * factor);
            e.automatic_path = (c.path == contact::Path::automatic &&
                                c.algorithm == contact::Algorithm::bde);
            if (c.path == contact::Path::full ||
                c.algorithm != contact::Algorithm::bde)
              e.path = contact::Path::full;
          }
        if (parameters.output.write_vtu)
          {
            // Patches of (s+1)^dim points per cell with the coordinates,
            // displacement, strain, stress and von Mises stress, and the
            // writer's copy.
            const double fields = dim + dim + dim * (dim + 1) + 1;
            for (const auto &b : e.bodies)
              {
                const double points =
                  std::pow(discretization::output_subdivisions_for<dim>(
                             parameters.discretization.output_subdivisions,
                             b.n_elements) +
                             1.,
                           dim);
                e.bytes_output =
                  std::max(e.bytes_output,
                           2. * 8. * fields * points * b.n_elements);
              }
          }
        return e;
      }
    } // namespace



    double
    SizeEstimate::total_bytes() const
    {
      return total_bytes(path);
    }



    double
    SizeEstimate::total_bytes(const contact::Path p) const
    {
      // On the full path the bodies free their factors once their load
      // cases are solved, before the coupled system is set up: the two
      // are not held at the same time.
      return bytes_process + bytes_matrix + bytes_output +
             (p == contact::Path::full ? std::max(bytes_factor, bytes_coupled) :
                                         bytes_factor + bytes_dense);
    }



    std::string
    SizeEstimate::choose_path_for_memory(const double available)
    {
      if (!automatic_path || path != contact::Path::condensed ||
          total_bytes(contact::Path::condensed) <= available ||
          total_bytes(contact::Path::full) > available)
        return "";
      path = contact::Path::full;
      std::ostringstream s;
      const double       gib = std::pow(2., 30);
      s << std::setprecision(3) << "auto: the condensed path needs about "
        << total_bytes(contact::Path::condensed) / gib << " GiB (dense blocks "
        << bytes_dense / gib << " GiB for " << contact_unknowns
        << " contact unknowns), more than the " << available / gib
        << " GiB free; the full path about "
        << total_bytes(contact::Path::full) / gib << " GiB";
      return s.str();
    }



    double
    SizeEstimate::total_unknowns() const
    {
      double n = 0.;
      for (const auto &b : bodies)
        n += b.n_unknowns;
      return n;
    }



    std::string
    SizeEstimate::describe() const
    {
      double factor = 0.;
      for (const auto &b : bodies)
        factor += b.factor_entries;
      std::ostringstream s;
      s << std::setprecision(3) << total_unknowns() << " unknowns, " << factor
        << " factor entries, " << contact_unknowns
        << " contact unknowns: about " << total_bytes() / std::pow(2., 30)
        << " GiB";
      return s.str();
    }



    nlohmann::json
    SizeEstimate::to_json() const
    {
      nlohmann::json j;
      nlohmann::json per_body = nlohmann::json::array();
      for (const auto &b : bodies)
        per_body.push_back({{"name", b.name},
                            {"n_elements", b.n_elements},
                            {"n_unknowns", b.n_unknowns},
                            {"matrix_entries", b.matrix_entries},
                            {"factor_entries", b.factor_entries},
                            {"face_unknowns", b.face_unknowns}});
      j["bodies"]           = per_body;
      j["contact_unknowns"] = contact_unknowns;
      j["path"]             = contact::to_string(path);
      j["bytes"]            = {{"matrix", bytes_matrix},
                               {"factor", bytes_factor},
                               {"dense", bytes_dense},
                               {"coupled", bytes_coupled},
                               {"output", bytes_output},
                               {"process", bytes_process},
                               {"total", total_bytes()}};
      return j;
    }



    SizeEstimate
    estimate_size(const AllParameters &parameters,
                  const std::string   &scene_file,
                  const int            refinements)
    {
      const unsigned int r =
        (refinements < 0 ? parameters.discretization.refinements :
                           static_cast<unsigned int>(refinements));
      return parameters.dimension == 2 ?
               estimate<2>(parameters, scene_file, r) :
               estimate<3>(parameters, scene_file, r);
    }



    double
    available_memory_bytes()
    {
      double        available = std::numeric_limits<double>::max();
      std::ifstream meminfo("/proc/meminfo");
      std::string   key;
      double        kib = 0.;
      std::string   unit;
      bool          found = false;
      while (!found && meminfo >> key >> kib >> unit)
        if (key == "MemAvailable:")
          {
            available = kib * 1024.;
            found     = true;
          }
      if (!found)
        {
          const long pages = sysconf(_SC_PHYS_PAGES);
          const long size  = sysconf(_SC_PAGE_SIZE);
          if (pages > 0 && size > 0)
            available = double(pages) * double(size);
        }
      // A share of a machine others use too.
      if (const char *limit = std::getenv("IGABDE_MEMORY_LIMIT"))
        {
          char        *end = nullptr;
          const double gib = std::strtod(limit, &end);
          AssertThrow(
            end != limit && *end == '\0' && std::isfinite(gib) && gib > 0.,
            base::ExcInput(std::string("IGABDE_MEMORY_LIMIT = '") + limit +
                           "' must be a positive number of GiB (e.g. 8)"));
          available = std::min(available, gib * std::pow(2., 30));
        }
      return available;
    }



    SizeEstimate
    check_size(const AllParameters &parameters,
               const std::string   &scene_file,
               const double         available)
    {
      SizeEstimate e = estimate_size(parameters, scene_file);
      e.choose_path_for_memory(available);
      const double need = e.total_bytes();
      if (std::isfinite(need) && need <= available)
        return e;

      const double gib      = std::pow(2., 30);
      const auto   bytes_at = [&](const int r) {
        SizeEstimate smaller = estimate_size(parameters, scene_file, r);
        smaller.choose_path_for_memory(available);
        return smaller.total_bytes();
      };
      std::ostringstream m;
      m << std::setprecision(3) << scene_file
        << ": this scene needs more memory than the machine has free: "
        << e.describe() << ", against " << available / gib << " GiB free. ";
      int fits = -1;
      for (int r = static_cast<int>(parameters.discretization.refinements) - 1;
           r >= 0;
           --r)
        if (bytes_at(r) <= available)
          {
            fits = r;
            break;
          }
      if (fits >= 0)
        m << "Discretization/Refinements = " << fits << " fits (about "
          << bytes_at(fits) / gib << " GiB); ";
      else
        m << "Even Discretization/Refinements = 0 does not fit: use fewer "
             "Subdivisions; ";
      m << "igabde --force runs it anyway.";
      AssertThrow(false, base::ExcInput(m.str()));
      return e;
    }
  } // namespace scene
} // namespace igabde
