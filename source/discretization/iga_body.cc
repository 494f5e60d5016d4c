#include <igabde/base/files.h>
#include <igabde/base/utilities.h>
#include <igabde/linear_algebra/dense_lu.h>

#include <igabde/nurbs/geometry_builders.h>
#include <igabde/nurbs/multi_patch.h>
#include <igabde/nurbs/parametric_mesh.h>

#include <igabde/discretization/iga_body.h>

#include <igabde/elasticity/assembly.h>
#include <igabde/elasticity/finite_output.h>
#include <igabde/elasticity/finite_strain.h>
#include <igabde/elasticity/stress_measures.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

namespace igabde
{
  namespace discretization
  {
    template <int dim>
    IgaBody<dim>::IgaBody(const BodyDescription<dim>   &description,
                          const DiscretizationSettings &settings)
      : Body<dim>(description, settings)
    {
      AssertThrow(description.geometry.n_control_points() > 0,
                  ExcMessage("Body '" + description.name +
                             "': the description has no NURBS geometry; "
                             "build one with the nurbs/geometry_builders."));
      AssertThrow(settings.degree >= 1,
                  ExcMessage("Body '" + description.name +
                             "': the NURBS degree must be at least 1."));
      spaces.resize(description.n_patches());
      std::vector<nurbs::NurbsPatch<dim>> patches;
      for (unsigned int p = 0; p < spaces.size(); ++p)
        {
          PatchSpace &space = spaces[p];
          space.geometry    = description.patch(p);
          // An exact geometry cannot be lowered (a circle needs rational
          // degree 2): running at the geometry's degree while reporting
          // the requested one would be a silent wrong answer.
          for (unsigned int d = 0; d < dim; ++d)
            AssertThrow(
              space.geometry.degree(d) <= settings.degree,
              base::ExcInput(
                "Discretization/Degree = " + std::to_string(settings.degree) +
                " is below the degree " +
                std::to_string(space.geometry.degree(d)) + " of " +
                description.name +
                "'s exact geometry in parametric "
                "direction " +
                std::to_string(d) +
                (spaces.size() > 1 ? " of patch " + std::to_string(p) : "") +
                "; use Degree >= " + std::to_string(space.geometry.degree(d)) +
                " with NURBS, or Discretization/Type = lagrange for an "
                "FE_Q approximation of this geometry."));
          nurbs::elevate_to_degree(space.geometry, settings.degree);
          for (unsigned int r = 0; r < settings.refinements; ++r)
            space.geometry.refine_uniformly(1);

          nurbs::make_parametric_triangulation(space.geometry, space.mesh);
          for (unsigned int d = 0; d < dim; ++d)
            space.breaks[d] = space.geometry.knot_vector(d).breakpoints();
          space.orientation = space.geometry.orientation();

          // Newton starts for the point inversion: breakpoints and span
          // midpoints per direction; their tensor grid is evaluated and
          // indexed at the first inversion.
          for (unsigned int d = 0; d < dim; ++d)
            {
              const auto &b = space.breaks[d];
              for (unsigned int e = 0; e + 1 < b.size(); ++e)
                {
                  space.sample_coordinates[d].push_back(b[e]);
                  space.sample_coordinates[d].push_back(0.5 *
                                                        (b[e] + b[e + 1]));
                }
              space.sample_coordinates[d].push_back(b.back());
            }
          patches.push_back(space.geometry);
        }
      // The interfaces were checked to be conforming when the scene was
      // read; refinement keeps them so, and gluing checks it again.
      auto [numbers, n] =
        nurbs::glue_control_points(patches,
                                   description.interfaces,
                                   "Body '" + description.name + "': ");
      n_points = n;
      for (unsigned int p = 0; p < spaces.size(); ++p)
        spaces[p].numbers = std::move(numbers[p]);

      default_placement = settings.pair_placement;

      Point<dim> lo = spaces[0].geometry.control_point(0), hi = lo;
      for (const PatchSpace &space : spaces)
        for (unsigned int a = 0; a < space.geometry.n_control_points(); ++a)
          for (unsigned int d = 0; d < dim; ++d)
            {
              lo[d] = std::min(lo[d], space.geometry.control_point(a)[d]);
              hi[d] = std::max(hi[d], space.geometry.control_point(a)[d]);
            }
      diameter = (hi - lo).norm();
    }



    template <int dim>
    std::string
    IgaBody<dim>::discretization_name() const
    {
      return "nurbs";
    }



    template <int dim>
    double
    IgaBody<dim>::mesh_bytes() const
    {
      double bytes = 0.;
      for (const PatchSpace &space : spaces)
        {
          bytes += space.mesh.memory_consumption() +
                   space.geometry.memory_consumption() +
                   base::vector_bytes(space.numbers);
          for (unsigned int d = 0; d < dim; ++d)
            bytes += base::vector_bytes(space.breaks[d]) +
                     base::vector_bytes(space.sample_coordinates[d]);
        }
      return bytes;
    }



    template <int dim>
    unsigned int
    IgaBody<dim>::n_elements() const
    {
      unsigned int n = 0;
      for (const PatchSpace &space : spaces)
        n += space.mesh.n_active_cells();
      return n;
    }



    template <int dim>
    unsigned int
    IgaBody<dim>::n_patches() const
    {
      return spaces.size();
    }



    template <int dim>
    const nurbs::NurbsPatch<dim> &
    IgaBody<dim>::patch(const unsigned int p) const
    {
      return spaces.at(p).geometry;
    }



    template <int dim>
    const Triangulation<dim> &
    IgaBody<dim>::triangulation(const unsigned int p) const
    {
      return spaces.at(p).mesh;
    }



    template <int dim>
    const std::vector<unsigned int> &
    IgaBody<dim>::control_point_numbers(const unsigned int p) const
    {
      return spaces.at(p).numbers;
    }



    template <int dim>
    unsigned int
    IgaBody<dim>::max_degree() const
    {
      unsigned int p = 0;
      for (const PatchSpace &space : spaces)
        for (unsigned int d = 0; d < dim; ++d)
          p = std::max(p, space.geometry.degree(d));
      return p;
    }



    template <int dim>
    unsigned int
    IgaBody<dim>::n_quadrature_points_1d() const
    {
      bool rational = false;
      for (const PatchSpace &space : spaces)
        for (unsigned int a = 1; a < space.geometry.n_control_points(); ++a)
          rational =
            rational || (space.geometry.weight(a) != space.geometry.weight(0));
      return max_degree() + (rational ? 2 : 1);
    }



    template <int dim>
    std::pair<double, Tensor<1, dim>>
    IgaBody<dim>::face_measure_and_normal(const unsigned int    face,
                                          const Tensor<2, dim> &J,
                                          const double          orientation)
    {
      const unsigned int   d    = face / 2;
      const double         side = (face % 2 == 0 ? -1. : 1.);
      const Tensor<1, dim> c    = nurbs::cofactor_column(J, d);
      const double         norm = c.norm();
      Tensor<1, dim>       n;
      if (norm > 0.)
        n = (side * orientation / norm) * c;
      return {norm, n};
    }



    template <int dim>
    std::pair<const typename IgaBody<dim>::PatchSpace *, unsigned int>
    IgaBody<dim>::patch_face(const types::boundary_id face) const
    {
      AssertThrow(patch_of_face<dim>(face) < spaces.size(),
                  ExcMessage("Body '" + this->description().name + "': face " +
                             (spaces.size() == 1 ?
                                std::to_string(face) +
                                  " does not exist; patch faces "
                                  "are 0.." +
                                  std::to_string(2 * dim - 1) + "." :
                                std::to_string(patch_of_face<dim>(face)) + "." +
                                  std::to_string(local_face<dim>(face)) +
                                  " does not exist; the body has " +
                                  std::to_string(spaces.size()) +
                                  " patches (faces p.f, p = 0.." +
                                  std::to_string(spaces.size() - 1) +
                                  ", f = 0.." + std::to_string(2 * dim - 1) +
                                  ").")));
      return {&spaces[patch_of_face<dim>(face)], local_face<dim>(face)};
    }



    template <int dim>
    void
    IgaBody<dim>::setup_space()
    {
      this->n_unknowns = dim * n_points;
      this->dof_locations.resize(this->n_unknowns);
      this->dof_components.resize(this->n_unknowns);
      for (const PatchSpace &space : spaces)
        for (unsigned int a = 0; a < space.numbers.size(); ++a)
          for (unsigned int c = 0; c < dim; ++c)
            {
              this->dof_locations[dim * space.numbers[a] + c] =
                space.geometry.control_point(a);
              this->dof_components[dim * space.numbers[a] + c] = c;
            }
      // With open knot vectors only a face's own control points have a
      // non-zero trace on it (patch interfaces count too: conservative).
      this->on_boundary.assign(this->n_unknowns, false);
      for (const PatchSpace &space : spaces)
        for (unsigned int f = 0; f < 2 * dim; ++f)
          for (const unsigned int a : space.geometry.face_control_points(f))
            for (unsigned int c = 0; c < dim; ++c)
              this->on_boundary[dim * space.numbers[a] + c] = true;

      // Supports: with open knot vectors only the face's control points
      // have a nonzero trace there, and sum R = 1 makes a constant value
      // exact when it is given to all of them.
      const std::string name = this->description().name;
      this->constraints.clear();
      this->prescribed_constraints.clear();
      this->prescribed_history.clear();
      std::map<types::global_dof_index, double> values;
      this->dirichlet_dofs.assign(this->description().dirichlet.size(), {});
      for (unsigned int b = 0; b < this->description().dirichlet.size(); ++b)
        {
          const auto &bc           = this->description().dirichlet[b];
          const auto [space, face] = patch_face(bc.boundary_id);
          const auto &geometry     = space->geometry;
          // A value given as a function of the point: the face's
          // control-point values that interpolate it at the face's
          // Greville points.
          const std::vector<unsigned int> face_points =
            geometry.face_control_points(face);
          std::array<std::vector<double>, dim> field_values;
          for (unsigned int c = 0; c < dim; ++c)
            if (bc.components[c] && bc.field[c])
              field_values[c] =
                nurbs::interpolate_on_face(geometry, face, bc.field[c]);
          for (unsigned int k = 0; k < face_points.size(); ++k)
            for (unsigned int c = 0; c < dim; ++c)
              if (bc.components[c])
                {
                  const unsigned int a = space->numbers[face_points[k]];
                  const double       value =
                    bc.field[c] ? field_values[c][k] : bc.value[c];
                  const types::global_dof_index i  = dim * a + c;
                  const auto                    it = values.find(i);
                  if (it != values.end())
                    {
                      // Equal to round-off of the values and of the body's
                      // size (a prescribed zero against 1e-17 m agrees).
                      AssertThrow(std::abs(it->second - value) <=
                                    1e-12 * std::max({std::abs(value),
                                                      std::abs(it->second),
                                                      diameter}),
                                  base::ExcInput(
                                    "Body '" + name +
                                    "': two supports prescribe different "
                                    "values of component " +
                                    std::to_string(c) +
                                    " where their faces meet (face " +
                                    std::to_string(bc.boundary_id) +
                                    "); make them agree on the common edge."));
                      // A non-zero value on two histories would follow
                      // whichever came last.
                      AssertThrow(value == 0. ||
                                    this->prescribed_history[i] == bc.history,
                                  base::ExcInput(
                                    "Body '" + name +
                                    "': two supports prescribe component " +
                                    std::to_string(c) +
                                    " on different load histories where "
                                    "their faces meet (face " +
                                    std::to_string(bc.boundary_id) +
                                    "); give them the same '@ history'."));
                    }
                  values[i]                   = value;
                  this->prescribed_history[i] = bc.history;
                  this->dirichlet_dofs[b].push_back(i);
                }
        }
      // Point supports: at a patch corner the corner control point's basis
      // function is one and every other vanishes, so holding that control
      // point holds the point.
      for (const auto &support : this->description().point_supports)
        {
          std::vector<std::pair<unsigned int, Point<dim>>> corners;
          for (const PatchSpace &space : spaces)
            for (unsigned int v = 0; v < (1u << dim); ++v)
              {
                std::vector<unsigned int> common =
                  space.geometry.face_control_points((v & 1u) ? 1 : 0);
                std::sort(common.begin(), common.end());
                for (unsigned int d = 1; d < dim; ++d)
                  {
                    std::vector<unsigned int> face =
                      space.geometry.face_control_points(2 * d +
                                                         ((v >> d) & 1u));
                    std::sort(face.begin(), face.end());
                    std::vector<unsigned int> both;
                    std::set_intersection(common.begin(),
                                          common.end(),
                                          face.begin(),
                                          face.end(),
                                          std::back_inserter(both));
                    common.swap(both);
                  }
                for (const unsigned int a : common)
                  if (std::none_of(corners.begin(),
                                   corners.end(),
                                   [&](const auto &c) {
                                     return c.first == space.numbers[a];
                                   }))
                    corners.emplace_back(space.numbers[a],
                                         space.geometry.control_point(a));
              }
          const auto at =
            std::find_if(corners.begin(),
                         corners.end(),
                         [&](const auto &corner) {
                           return corner.second.distance(support.location) <=
                                  1e-10 * diameter;
                         });
          std::string corner_list;
          for (const auto &corner : corners)
            corner_list +=
              std::string(&corner == &corners.front() ? "" : ", ") + "(" +
              base::to_string(corner.second) + ")";
          AssertThrow(at != corners.end(),
                      base::ExcInput("Body '" + name +
                                     "': the point support at (" +
                                     base::to_string(support.location) +
                                     ") is not a corner of the patch" +
                                     (spaces.size() > 1 ? "es" : "") +
                                     "; a NURBS body takes point supports at "
                                     "its corners " +
                                     corner_list +
                                     " (or use Discretization/Type = lagrange, "
                                     "whose every mesh node can take one)."));
          for (unsigned int c = 0; c < dim; ++c)
            if (support.components[c])
              {
                const types::global_dof_index i     = dim * at->first + c;
                const double                  value = support.value[c];
                // A support already there must agree, on the same history
                // where the value is not zero.
                AssertThrow(values.find(i) == values.end() ||
                              (values[i] == value &&
                               (value == 0. || this->prescribed_history[i] ==
                                                 support.history)),
                            base::ExcInput("Body '" + name +
                                           "': a point support prescribes "
                                           "component " +
                                           std::to_string(c) +
                                           " at a corner where a support "
                                           "prescribes another value (or the "
                                           "same on another history)."));
                if (values.find(i) == values.end() || value != 0.)
                  this->prescribed_history[i] = support.history;
                values[i] = value;
              }
        }
      for (const auto &[i, v] : values)
        {
          this->constraints.add_line(i);
          this->prescribed_constraints.add_line(i);
          this->prescribed_constraints.set_inhomogeneity(i, v);
        }
      this->constraints.close();
      this->prescribed_constraints.close();

      // Couplings of the control points first (the scalar basis functions
      // of each knot span), then each expanded to its dim x dim block of
      // unknowns: dim^2 less work than adding every unknown of every span.
      DynamicSparsityPattern               points(n_points, n_points);
      std::vector<types::global_dof_index> dofs, span_points;
      for (const PatchSpace &space : spaces)
        {
          nurbs::NurbsValues<dim> span_values(space.geometry,
                                              Quadrature<dim>(),
                                              update_default);
          span_values.number_unknowns_by(space.numbers);
          for (const auto &cell : space.mesh.active_cell_iterators())
            {
              span_values.reinit(cell);
              span_values.get_dof_indices(dofs);
              span_points.clear();
              for (const auto i : dofs)
                if (i % dim == 0)
                  span_points.push_back(i / dim);
              std::sort(span_points.begin(), span_points.end());
              for (const auto a : span_points)
                points.add_entries(a,
                                   span_points.begin(),
                                   span_points.end(),
                                   true);
            }
        }
      std::vector<unsigned int> row_lengths(this->n_unknowns);
      for (unsigned int a = 0; a < n_points; ++a)
        for (unsigned int c = 0; c < dim; ++c)
          row_lengths[dim * a + c] = dim * points.row_length(a);
      this->sparsity.reinit(this->n_unknowns, this->n_unknowns, row_lengths);
      std::vector<types::global_dof_index> columns;
      for (unsigned int a = 0; a < n_points; ++a)
        {
          columns.clear();
          for (auto entry = points.begin(a); entry != points.end(a); ++entry)
            for (unsigned int d = 0; d < dim; ++d)
              columns.push_back(dim * entry->column() + d);
          for (unsigned int c = 0; c < dim; ++c)
            this->sparsity.add_entries(dim * a + c,
                                       columns.begin(),
                                       columns.end(),
                                       true);
        }
      this->sparsity.compress();
    }



    template <int dim>
    void
    IgaBody<dim>::assemble()
    {
      const auto &desc = this->description();
      // Each patch's tractions, on its own face numbers.
      for (const auto &t : desc.tractions)
        patch_face(t.boundary_id);
      const auto on_patch = [&](const std::vector<NeumannCondition<dim>> &all,
                                const unsigned int                        p) {
        std::vector<NeumannCondition<dim>> mine;
        for (const auto &t : all)
          if (patch_of_face<dim>(t.boundary_id) == p)
            {
              mine.push_back(t);
              mine.back().boundary_id = local_face<dim>(t.boundary_id);
            }
        return mine;
      };

      // Cells: p+1 (p+2 rational) Gauss points per direction; faces one
      // more.
      std::vector<std::unique_ptr<nurbs::NurbsValues<dim>>> cell_values,
        face_values;
      for (const PatchSpace &space : spaces)
        {
          cell_values.push_back(std::make_unique<nurbs::NurbsValues<dim>>(
            space.geometry,
            QGauss<dim>(n_quadrature_points_1d()),
            update_values | update_gradients | update_JxW_values |
              (desc.body_force_field ? update_quadrature_points :
                                       update_default)));
          cell_values.back()->check_orientation(
            "Body '" + desc.name + "'" +
            (spaces.size() > 1 ?
               " patch " + std::to_string(cell_values.size() - 1) :
               ""));
          cell_values.back()->number_unknowns_by(space.numbers);
          face_values.push_back(std::make_unique<nurbs::NurbsValues<dim>>(
            space.geometry,
            QGauss<dim - 1>(n_quadrature_points_1d() + 1),
            update_values | update_quadrature_points | update_normal_vectors |
              update_JxW_values));
          face_values.back()->number_unknowns_by(space.numbers);
        }
      // One load vector per load history; K with history 0, which holds
      // the body force.
      this->assemble_history_loads(
        [&](const elasticity::BodyForce<dim>         &body_force,
            const std::vector<NeumannCondition<dim>> &tractions,
            SparseMatrix<double>                     &matrix,
            Vector<double>                           &rhs) {
          // The cells of this rank's share (all of them in one process),
          // numbered through the patches in order.
          const unsigned int first  = this->assembly_cells.first;
          const unsigned int end    = this->assembly_cells.second;
          unsigned int       offset = 0;
          for (unsigned int p = 0; p < spaces.size(); ++p)
            {
              elasticity::assemble_system<dim>(
                spaces[p].mesh.begin_active(),
                spaces[p].mesh.end(),
                *cell_values[p],
                *face_values[p],
                desc.material,
                body_force,
                on_patch(tractions, p),
                matrix,
                rhs,
                [first, end, offset](const auto &cell) {
                  const unsigned int index = offset + cell->active_cell_index();
                  return index >= first && index < end;
                });
              offset += spaces[p].mesh.n_active_cells();
            }
        },
        // Point loads: P_A = R_A(xi_X) P (method.md, sec. 3).
        [&](const PointLoad<dim> &load, Vector<double> &rhs) {
          point_operator(load.location).distribute(load.force, rhs);
        });
    }



    template <int dim>
    std::pair<unsigned int, Point<dim>>
    IgaBody<dim>::locate(const Point<dim> &location) const
    {
      std::call_once(index_built, [this]() {
        for (const PatchSpace &space : spaces)
          sample_index.push_back(std::make_unique<base::NearestPoints<dim>>(
            space.geometry.values_on_grid(space.sample_coordinates)));
      });
      // Each patch's nearest sample (ties to the first, as a scan would);
      // its parametric point: the grid index, direction 0 fastest. The
      // patches are tried from the nearest sample on until one holds the
      // point (one patch: the first).
      std::vector<std::pair<double, unsigned int>> order;
      std::vector<Point<dim>>                      starts(spaces.size());
      for (unsigned int p = 0; p < spaces.size(); ++p)
        {
          const auto  &coordinates = spaces[p].sample_coordinates;
          unsigned int rest        = sample_index[p]->nearest(location);
          const double distance = (*sample_index[p])[rest].distance(location);
          for (unsigned int d = 0; d < dim; ++d)
            {
              starts[p][d] = coordinates[d][rest % coordinates[d].size()];
              rest /= coordinates[d].size();
            }
          order.emplace_back(distance, p);
        }
      std::sort(order.begin(), order.end());
      double       best = std::numeric_limits<double>::max();
      Point<dim>   best_xi;
      unsigned int best_patch = 0;
      for (const auto &[sample_distance, p] : order)
        {
          double           distance = 0.;
          const Point<dim> xi =
            spaces[p].geometry.closest_parametric_point(location,
                                                        &starts[p],
                                                        &distance);
          if (distance < best)
            {
              best       = distance;
              best_xi    = xi;
              best_patch = p;
            }
          if (best <= 1e-8 * diameter)
            break;
        }
      if (best > 1e-8 * diameter)
        {
          std::ostringstream s;
          s << "Body '" << this->description().name << "': the point ("
            << location << ") is not in the body (distance " << best
            << " from its closest point ("
            << spaces[best_patch].geometry.value(best_xi)
            << ")); point loads and probes must lie in or on the body.";
          AssertThrow(false, ExcMessage(s.str()));
        }
      return {best_patch, best_xi};
    }



    template <int dim>
    Point<dim>
    IgaBody<dim>::parametric_point(const Point<dim> &location) const
    {
      return locate(location).second;
    }



    template <int dim>
    PointOperator<dim>
    IgaBody<dim>::parametric_point_operator(const Point<dim>  &xi,
                                            const unsigned int p) const
    {
      std::vector<unsigned int> indices;
      PointOperator<dim>        op;
      spaces.at(p).geometry.basis(xi, indices, op.weights);
      number_operator(indices, p, op);
      return op;
    }



    template <int dim>
    void
    IgaBody<dim>::number_operator(const std::vector<unsigned int> &indices,
                                  const unsigned int               p,
                                  PointOperator<dim>              &op) const
    {
      const std::vector<unsigned int> &numbers = spaces.at(p).numbers;
      op.dofs.resize(indices.size());
      for (unsigned int k = 0; k < indices.size(); ++k)
        for (unsigned int c = 0; c < dim; ++c)
          op.dofs[k][c] = dim * numbers[indices[k]] + c;
    }



    template <int dim>
    PointOperator<dim>
    IgaBody<dim>::point_operator(const Point<dim> &location) const
    {
      const auto [p, xi] = locate(location);
      return parametric_point_operator(xi, p);
    }



    template <int dim>
    Tensor<1, dim>
    IgaBody<dim>::displacement_at_parametric(const Vector<double> &u,
                                             const Point<dim>     &xi,
                                             const unsigned int    p) const
    {
      return parametric_point_operator(xi, p).displacement(u);
    }



    template class IgaBody<2>;
    template class IgaBody<3>;
  } // namespace discretization
} // namespace igabde
