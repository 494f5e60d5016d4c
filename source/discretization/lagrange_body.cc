#include <igabde/base/files.h>
#include <igabde/base/nearest_points.h>
#include <igabde/base/utilities.h>

#include <igabde/nurbs/parametric_mesh.h>

#include <igabde/discretization/lagrange_body.h>

#include <igabde/elasticity/assembly.h>
#include <igabde/elasticity/fe_values_evaluator.h>
#include <igabde/elasticity/finite_output.h>
#include <igabde/elasticity/finite_strain.h>
#include <igabde/elasticity/stress_measures.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>

#include <deal.II/grid/grid_reordering.h>
#include <deal.II/grid/grid_tools.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_cartesian.h>

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/rtree.h>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

namespace igabde
{
  namespace discretization
  {
    namespace
    {
      /**
       * The cells around @p location and the point's unit coordinates in
       * each, nearest first: every cell within @p tolerance of the point in
       * unit coordinates, or the nearest alone when none is. deal.II returns
       * an invalid iterator for a point outside the mesh; this throws
       * instead, so that Body::contains() can tell the bodies apart (a probe
       * on Body 2 is first looked for on Body 1).
       */
      template <int dim>
      std::vector<
        std::pair<typename DoFHandler<dim>::active_cell_iterator, Point<dim>>>
      locate_all(const GridTools::Cache<dim> &cache,
                 const DoFHandler<dim>       &dof_handler,
                 const Point<dim>            &location,
                 const double                 tolerance)
      {
        // Candidates from the cache's tree of cell bounding boxes: the
        // cells whose box holds the point, else the eight nearest boxes
        // (a point on a curved face may lie just outside the boxes of the
        // mapped support points). deal.II's find_active_cell_around_point
        // falls back to inverting the map on every cell when the cells
        // around the nearest vertex miss the point, which made the
        // recovered pressures of V7's graded 3D mesh slow, and a search
        // over every cell is slow per point too (V6's block;
        // doc/architecture.md).
        namespace bgi = boost::geometry::index;
        using Entry =
          std::pair<BoundingBox<dim>,
                    typename Triangulation<dim>::active_cell_iterator>;
        const auto        &tree = cache.get_cell_bounding_boxes_rtree();
        std::vector<Entry> candidates;
        tree.query(bgi::intersects(location), std::back_inserter(candidates));
        if (candidates.empty())
          tree.query(bgi::nearest(location, 8), std::back_inserter(candidates));
        const Mapping<dim> &mapping = cache.get_mapping();
        std::vector<
          std::tuple<double,
                     typename Triangulation<dim>::active_cell_iterator,
                     Point<dim>>>
          found;
        for (const auto &[box, cell] : candidates)
          {
            try
              {
                const Point<dim> unit =
                  mapping.transform_real_to_unit_cell(cell, location);
                found.emplace_back(GeometryInfo<dim>::distance_to_unit_cell(
                                     unit),
                                   cell,
                                   unit);
              }
            catch (const typename Mapping<dim>::ExcTransformationFailed &)
              {
                // Newton left the cell's neighbourhood: not this cell.
              }
          }
        std::stable_sort(found.begin(),
                         found.end(),
                         [](const auto &a, const auto &b) {
                           return std::get<0>(a) < std::get<0>(b);
                         });
        // Stable: among cells at the same distance (a point on a shared
        // vertex) the tree's first stays first, as find_cell() always chose.
        AssertThrow(!found.empty() && std::get<0>(found.front()) <= 1e-3,
                    ExcMessage("The point lies outside the body."));
        std::vector<
          std::pair<typename DoFHandler<dim>::active_cell_iterator, Point<dim>>>
          cells;
        for (const auto &[distance, cell, unit] : found)
          if (cells.empty() || distance <= tolerance)
            cells.emplace_back(typename DoFHandler<dim>::active_cell_iterator(
                                 &dof_handler.get_triangulation(),
                                 cell->level(),
                                 cell->index(),
                                 &dof_handler),
                               unit);
        return cells;
      }

      /**
       * Position of the unit point @p unit on the sub-entity of the unit cell
       * whose coordinates d with bit d of @p fixed set are fixed to bit d of
       * @p values (0 or 1): the map @p exact if no vertex of the entity is
       * marked in @p singular (deal.II's lexicographic vertex numbers), else
       * the transfinite interpolation of the entity's boundary (Gordon and
       * Hall), recursively: sum over the non-empty sets S of free directions,
       * with sign (-1)^(|S|+1), of the blended positions on the entities with
       * S fixed at 0 and 1. A line touching a singular vertex is its chord, a
       * quadrilateral the Coons patch of its four lines, and so on.
       */
      template <int dim>
      Point<dim>
      transfinite_position(
        const std::function<Point<dim>(const Point<dim> &)>          &exact,
        const std::array<bool, GeometryInfo<dim>::vertices_per_cell> &singular,
        const Point<dim>                                             &unit,
        const unsigned int                                            fixed,
        const unsigned int                                            values)
      {
        Point<dim> on_entity = unit;
        for (unsigned int d = 0; d < dim; ++d)
          if (fixed & (1u << d))
            on_entity[d] = (values >> d) & 1u;
        const unsigned int all     = (1u << dim) - 1;
        const unsigned int free    = all & ~fixed;
        bool               touches = false;
        for (unsigned int v = 0; v <= all; ++v)
          touches = touches || ((v & fixed) == values && singular[v]);
        if (!touches || free == 0)
          return exact(on_entity);

        Point<dim> x;
        for (unsigned int S = free; S != 0; S = (S - 1) & free)
          {
            const double sign =
              (std::bitset<dim>(S).count() % 2 == 1) ? 1. : -1.;
            // Every assignment c of 0 or 1 to the directions in S.
            for (unsigned int c = S;; c = (c - 1) & S)
              {
                double weight = sign;
                for (unsigned int d = 0; d < dim; ++d)
                  if (S & (1u << d))
                    weight *=
                      (c & (1u << d)) ? on_entity[d] : 1. - on_entity[d];
                x += weight * transfinite_position<dim>(exact,
                                                        singular,
                                                        unit,
                                                        fixed | S,
                                                        values | c);
                if (c == 0)
                  break;
              }
          }
        return x;
      }
    } // namespace



    template <int dim>
    LagrangeBody<dim>::LagrangeBody(const BodyDescription<dim>   &description,
                                    const DiscretizationSettings &settings)
      : Body<dim>(description, settings)
      , fe(FE_Q<dim>(settings.degree), dim)
    {
      for (unsigned int p = 0; p < description.n_patches(); ++p)
        patches.push_back(description.patch(p));
      AssertThrow(settings.degree >= 1 && settings.degree <= 4,
                  ExcMessage("Discretization/Degree: the Lagrange path "
                             "supports FE_Q degrees 1 to 4, got " +
                             std::to_string(settings.degree) + "."));
    }



    template <int dim>
    std::string
    LagrangeBody<dim>::discretization_name() const
    {
      return "lagrange";
    }



    template <int dim>
    double
    LagrangeBody<dim>::mesh_bytes() const
    {
      double bytes =
        triangulation.memory_consumption() + dof_handler.memory_consumption() +
        euler_vector.memory_consumption() + base::vector_bytes(cell_parameters);
      for (const auto &patch : patches)
        bytes += patch.memory_consumption();
      return bytes;
    }



    template <int dim>
    unsigned int
    LagrangeBody<dim>::n_elements() const
    {
      return triangulation.n_active_cells();
    }



    template <int dim>
    Point<dim>
    LagrangeBody<dim>::unit_centre()
    {
      Point<dim> centre;
      for (unsigned int d = 0; d < dim; ++d)
        centre[d] = 0.5;
      return centre;
    }



    template <int dim>
    unsigned int
    LagrangeBody<dim>::patch_of(
      const typename Triangulation<dim>::cell_iterator &cell) const
    {
      return cell_parameters[cell->active_cell_index()].patch;
    }



    template <int dim>
    Point<dim>
    LagrangeBody<dim>::parametric_point(
      const typename Triangulation<dim>::cell_iterator &cell,
      const Point<dim>                                 &unit) const
    {
      const CellParameters &c  = cell_parameters[cell->active_cell_index()];
      Point<dim>            xi = c.origin;
      for (unsigned int e = 0; e < dim; ++e)
        xi[c.direction[e]] += unit[e] * c.length[e];
      return xi;
    }



    template <int dim>
    void
    LagrangeBody<dim>::make_mesh()
    {
      // deal.II cells need a positive Jacobian. A left-handed patch (the
      // curved beam) is meshed with its last parametric direction reversed:
      // the mesh lays that direction's spans out mirrored (so that its
      // cells are the patch's spans also when they are graded), and the
      // two faces of that direction swap their boundary ids so that every
      // face keeps its patch face number.
      const auto meshed = [&](const unsigned int p, Triangulation<dim> &mesh) {
        const bool reflect = (patches[p].orientation() < 0);
        nurbs::make_parametric_triangulation(patches[p], mesh, reflect);
        if (reflect)
          for (const auto &cell : mesh.active_cell_iterators())
            for (const auto f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() / 2 == dim - 1)
                cell->face(f)->set_boundary_id(cell->face(f)->boundary_id() ^
                                               1);
        // The patch's parametric point of a point of the mesh.
        return [reflect,
                lo = patches[p].parametric_lower(),
                hi = patches[p].parametric_upper()](Point<dim> xi) {
          if (reflect)
            xi[dim - 1] = lo[dim - 1] + hi[dim - 1] - xi[dim - 1];
          return xi;
        };
      };
      // The box of a cell from the parametric points of its vertices
      // (axis-parallel: one direction changes along each unit axis).
      const auto parameters = [](const unsigned int             p,
                                 const std::vector<Point<dim>> &xi) {
        CellParameters c;
        c.patch  = p;
        c.origin = xi[0];
        for (unsigned int e = 0; e < dim; ++e)
          {
            const Tensor<1, dim> axis = xi[1u << e] - xi[0];
            unsigned int         d    = 0;
            for (unsigned int k = 1; k < dim; ++k)
              if (std::abs(axis[k]) > std::abs(axis[d]))
                d = k;
            c.direction[e] = d;
            c.length[e]    = axis[d];
          }
        return c;
      };

      cell_parameters.clear();
      if (patches.size() == 1)
        {
          // One patch: the parametric mesh itself (vertices are parametric
          // points), the map follows from its cells.
          const auto to_patch = meshed(0, triangulation);
          cell_parameters.resize(triangulation.n_active_cells());
          for (const auto &cell : triangulation.active_cell_iterators())
            {
              std::vector<Point<dim>> xi;
              for (const auto v : cell->vertex_indices())
                xi.push_back(to_patch(cell->vertex(v)));
              cell_parameters[cell->active_cell_index()] = parameters(0, xi);
            }
          return;
        }

      // Several patches: every patch's parametric mesh laid out in space
      // (its vertices mapped), the vertices that patches share (conforming
      // interfaces) made one, cells kept with the parametric points of
      // their vertices in their own patch.
      std::vector<Point<dim>>                                       vertices;
      std::vector<std::vector<std::pair<unsigned int, Point<dim>>>> vertex_xi;
      std::vector<CellData<dim>>                                    cells;
      double                                                        size = 0.;
      for (const auto &patch : patches)
        for (unsigned int a = 0; a < patch.n_control_points(); ++a)
          size = std::max(size, patch.control_point(a).norm());
      const double tolerance = 1e-10 * std::max(size, 1.);
      std::unique_ptr<base::NearestPoints<dim>> index;
      const auto glued = [&](const unsigned int p, const unsigned int q) {
        for (const auto &i : this->description().interfaces)
          if ((i.patch[0] == p && i.patch[1] == q) ||
              (i.patch[0] == q && i.patch[1] == p))
            return true;
        return false;
      };
      for (unsigned int p = 0; p < patches.size(); ++p)
        {
          Triangulation<dim> mesh;
          const auto         to_patch = meshed(p, mesh);
          // The vertices so far, indexed to find the shared ones.
          if (!vertices.empty())
            index = std::make_unique<base::NearestPoints<dim>>(vertices);
          const unsigned int        first_new = vertices.size();
          std::vector<unsigned int> number(mesh.n_vertices());
          for (unsigned int v = 0; v < mesh.n_vertices(); ++v)
            {
              const Point<dim> xi = to_patch(mesh.get_vertices()[v]);
              const Point<dim> x  = patches[p].value(xi);
              unsigned int     n  = vertices.size();
              // Shared with a patch that an interface joins to this one;
              // patches that merely touch stay apart (a slit), as on the
              // NURBS path.
              if (index)
                {
                  const unsigned int near = index->nearest(x);
                  if (near < first_new &&
                      (*index)[near].distance(x) <= tolerance &&
                      std::any_of(vertex_xi[near].begin(),
                                  vertex_xi[near].end(),
                                  [&](const auto &entry) {
                                    return glued(p, entry.first);
                                  }))
                    n = near;
                }
              if (n == vertices.size())
                {
                  vertices.push_back(x);
                  vertex_xi.emplace_back();
                }
              vertex_xi[n].emplace_back(p, xi);
              number[v] = n;
            }
          for (const auto &cell : mesh.active_cell_iterators())
            {
              CellData<dim> data;
              for (const auto v : cell->vertex_indices())
                data.vertices[v] = number[cell->vertex_index(v)];
              data.material_id = p;
              cells.push_back(data);
            }
        }
      GridTools::consistently_order_cells(cells);
      triangulation.clear();
      triangulation.create_triangulation(vertices, cells, SubCellData());

      cell_parameters.resize(triangulation.n_active_cells());
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          const unsigned int      p = cell->material_id();
          std::vector<Point<dim>> xi;
          for (const auto v : cell->vertex_indices())
            for (const auto &[q, point] : vertex_xi[cell->vertex_index(v)])
              if (q == p)
                {
                  xi.push_back(point);
                  break;
                }
          AssertThrow(xi.size() == cell->n_vertices(), ExcInternalError());
          cell_parameters[cell->active_cell_index()] = parameters(p, xi);
        }
      // Boundary ids: the patch face each boundary face lies on, p 2 dim + f.
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const unsigned int p = patch_of(cell);
              // The unit cell's face f: its normal axis at 0 or 1.
              Point<dim> unit       = unit_centre();
              unit[f / 2]           = f % 2;
              const Point<dim> xi   = parametric_point(cell, unit);
              const auto      &lo   = patches[p].parametric_lower();
              const auto      &hi   = patches[p].parametric_upper();
              unsigned int     face = numbers::invalid_unsigned_int;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const double tol = 1e-12 * (hi[d] - lo[d]);
                  if (std::abs(xi[d] - lo[d]) <= tol)
                    face = 2 * d;
                  else if (std::abs(xi[d] - hi[d]) <= tol)
                    face = 2 * d + 1;
                }
              AssertThrow(face != numbers::invalid_unsigned_int,
                          ExcMessage("Body '" + this->description().name +
                                     "': a boundary face of patch " +
                                     std::to_string(p) +
                                     " lies on no patch face: two patches "
                                     "touch where no interface glues "
                                     "them."));
              cell->face(f)->set_boundary_id(face_id<dim>(p, face));
            }
    }



    template <int dim>
    void
    LagrangeBody<dim>::setup_space()
    {
      for (auto &patch : patches)
        for (unsigned int r = 0; r < this->settings.refinements; ++r)
          patch.refine_uniformly(1);
      make_mesh();
      dof_handler.reinit(triangulation);
      dof_handler.distribute_dofs(fe);
      this->n_unknowns = dof_handler.n_dofs();

      // The cells by patch and span, for face_point().
      cell_of_span.assign(patches.size(), {});
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          const CellParameters &c = cell_parameters[cell->active_cell_index()];
          std::array<std::vector<double>, dim> breaks;
          for (unsigned int d = 0; d < dim; ++d)
            breaks[d] = patches[c.patch].breakpoints(d);
          cell_of_span[c.patch][nurbs::span_of_point<
            dim>(breaks, parametric_point(cell, unit_centre()))] = cell;
        }

      // Geometry: the exact NURBS map at the support points.
      euler_vector.reinit(this->n_unknowns);
      this->dof_locations.resize(this->n_unknowns);
      this->dof_components.resize(this->n_unknowns);
      const auto &base = fe.base_element(0);
      {
        std::vector<types::global_dof_index> local(fe.n_dofs_per_cell());
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            const auto &map = patches[patch_of(cell)];
            cell->get_dof_indices(local);
            for (unsigned int i = 0; i < local.size(); ++i)
              {
                const auto [component, k] = fe.system_to_component_index(i);
                const Point<dim> x =
                  map.value(parametric_point(cell, base.unit_support_point(k)));
                this->dof_components[local[i]] = component;
                euler_vector[local[i]]         = x[component];
                this->dof_locations[local[i]]  = x;
              }
          }
      }

      this->on_boundary.assign(this->n_unknowns, false);
      for (const auto i : DoFTools::extract_boundary_dofs(dof_handler))
        this->on_boundary[i] = true;

      // Where the NURBS map is singular (det J = 0 at a cell vertex: the
      // 180-degree corner where the two arcs of the Hertz quarter disc meet,
      // the doubled control point at the corner (L, L) of the plate with
      // hole), no interpolant of the map is a valid element: its Jacobian at
      // that vertex is interpolation error of either sign (for FE_Q(2) and
      // FE_Q(3) on V5's mesh it is negative: a folded sliver). Every line,
      // face and cell touching such a vertex takes instead the transfinite
      // interpolation of its boundary (Coons), lines the straight chord of
      // their end points: the corner of the cell is then the convex corner
      // of two chords, and everything that does not touch the vertex keeps
      // the interpolated NURBS map, so the neighbours do not change. A
      // vertex is singular when |det J| there is round-off next to its value
      // at the cell centre (the builders' regular vertices have ratios of
      // order one, singular ones about 1e-16).
      {
        std::vector<types::global_dof_index> local(fe.n_dofs_per_cell());
        std::array<bool, GeometryInfo<dim>::vertices_per_cell> singular;
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            const auto  &map    = patches[patch_of(cell)];
            const double centre = std::abs(
              determinant(map.jacobian(parametric_point(cell, unit_centre()))));
            for (const auto v : cell->vertex_indices())
              singular[v] =
                std::abs(determinant(map.jacobian(
                  parametric_point(cell,
                                   GeometryInfo<dim>::unit_cell_vertex(v))))) <=
                1e-8 * centre;
            if (std::none_of(singular.begin(), singular.end(), [](bool b) {
                  return b;
                }))
              continue;
            const auto exact = [&](const Point<dim> &unit) {
              return map.value(parametric_point(cell, unit));
            };
            cell->get_dof_indices(local);
            for (unsigned int i = 0; i < local.size(); ++i)
              {
                const auto [component, k] = fe.system_to_component_index(i);
                const Point<dim> x =
                  transfinite_position<dim>(exact,
                                            singular,
                                            base.unit_support_point(k),
                                            0u,
                                            0u);
                euler_vector[local[i]]        = x[component];
                this->dof_locations[local[i]] = x;
              }
          }
      }
      mapping =
        std::make_unique<MappingFEField<dim, dim>>(dof_handler, euler_vector);

      // A geometry that is not one-to-one would give wrong integrals,
      // probes and output without any other sign (deal.II only checks in
      // Debug builds): check it at the quadrature and output points.
      {
        const unsigned int n_sub = std::max(
          fe.degree,
          output_subdivisions_for<dim>(this->settings.output_subdivisions,
                                       triangulation.n_active_cells()));
        std::vector<Point<dim>> points =
          QIterated<dim>(QTrapezoid<1>(), n_sub).get_points();
        const auto gauss = QGauss<dim>(fe.degree + 1).get_points();
        points.insert(points.end(), gauss.begin(), gauss.end());
        const auto [ratio, centre] = min_jacobian_ratio(points);
        std::ostringstream message;
        message << "The FE_Q geometry of the body is not valid: the Jacobian "
                   "of the cell around ("
                << centre << ") changes sign (det ratio " << ratio
                << "): the FE_Q(" << fe.degree
                << ") interpolation of the NURBS map folds there. Use a "
                   "finer mesh (Subdivisions, Refinements), a lower "
                   "Discretization/Degree or Discretization/Type = nurbs.";
        AssertThrow(ratio > 0., ExcMessage(message.str()));
      }

      // Supports on patch faces, exact for constant values.
      this->constraints.clear();
      this->prescribed_constraints.clear();
      this->prescribed_history.clear();
      // Values given as functions of the point: taken at the nodes.
      std::map<types::global_dof_index, Point<dim>> nodes;
      for (const auto &bc : this->description().dirichlet)
        for (unsigned int c = 0; c < dim; ++c)
          if (bc.field[c] && nodes.empty())
            DoFTools::map_dofs_to_support_points(*mapping, dof_handler, nodes);
      this->dirichlet_dofs.assign(this->description().dirichlet.size(), {});
      for (unsigned int b = 0; b < this->description().dirichlet.size(); ++b)
        {
          const auto       &bc = this->description().dirichlet[b];
          std::vector<bool> mask(bc.components.begin(), bc.components.end());
          const IndexSet    dofs =
            DoFTools::extract_boundary_dofs(dof_handler,
                                            ComponentMask(mask),
                                            {bc.boundary_id});
          for (const auto i : dofs)
            {
              if (!this->constraints.is_constrained(i))
                this->constraints.add_line(i);
              if (!this->prescribed_constraints.is_constrained(i))
                this->prescribed_constraints.add_line(i);
              else
                // A non-zero value on two histories would follow whichever
                // came last.
                AssertThrow((bc.value[this->dof_components[i]] == 0. &&
                             !bc.field[this->dof_components[i]]) ||
                              this->prescribed_history[i] == bc.history,
                            base::ExcInput(
                              "Body '" + this->description().name +
                              "': two supports prescribe component " +
                              std::to_string(this->dof_components[i]) +
                              " on different load histories where their "
                              "faces meet (face " +
                              std::to_string(bc.boundary_id) +
                              "); give them the same '@ history'."));
              const unsigned int c = this->dof_components[i];
              this->prescribed_constraints.set_inhomogeneity(
                i,
                bc.field[c] ? bc.field[c](nodes.at(i)) : bc.value[c]);
              this->prescribed_history[i] = bc.history;
              this->dirichlet_dofs[b].push_back(i);
            }
        }
      // Point supports: at a node its Lagrange function is one and every
      // other vanishes, so holding the node's unknowns holds the point.
      if (!this->description().point_supports.empty())
        {
          std::map<types::global_dof_index, Point<dim>> all_nodes;
          DoFTools::map_dofs_to_support_points(*mapping,
                                               dof_handler,
                                               all_nodes);
          const double size = GridTools::diameter(triangulation);
          for (const auto &support : this->description().point_supports)
            {
              bool found = false;
              for (const auto &[i, node] : all_nodes)
                if (node.distance(support.location) <= 1e-10 * size &&
                    support.components[this->dof_components[i]])
                  {
                    found = true;
                    if (!this->constraints.is_constrained(i))
                      this->constraints.add_line(i);
                    const double value = support.value[this->dof_components[i]];
                    if (!this->prescribed_constraints.is_constrained(i))
                      {
                        this->prescribed_constraints.add_line(i);
                        this->prescribed_constraints.set_inhomogeneity(i,
                                                                       value);
                        this->prescribed_history[i] = support.history;
                      }
                    // A support already there must agree, on the same
                    // history where the value is not zero.
                    AssertThrow(this->prescribed_constraints.get_inhomogeneity(
                                  i) == value &&
                                  (value == 0. || this->prescribed_history[i] ==
                                                    support.history),
                                base::ExcInput(
                                  "Body '" + this->description().name +
                                  "': a point support prescribes a node "
                                  "where a support prescribes another value "
                                  "(or the same on another history)."));
                  }
              AssertThrow(found,
                          base::ExcInput(
                            "Body '" + this->description().name +
                            "': the point support at (" +
                            base::to_string(support.location) +
                            ") is not a node of the FE_Q(" +
                            std::to_string(fe.degree) +
                            ") mesh; put it at a vertex or node."));
            }
        }
      this->constraints.close();
      this->prescribed_constraints.close();

      DynamicSparsityPattern dsp(this->n_unknowns);
      DoFTools::make_sparsity_pattern(dof_handler, dsp);
      this->sparsity.copy_from(dsp);
    }



    template <int dim>
    std::pair<double, Point<dim>>
    LagrangeBody<dim>::min_jacobian_ratio(
      const std::vector<Point<dim>> &unit_points) const
    {
      // From the nodes and the shape gradients directly, not through
      // FEValues, which stops a Debug build at the first bad point.
      const auto        &base   = fe.base_element(0);
      const unsigned int n_base = base.n_dofs_per_cell();
      Point<dim>         middle;
      for (unsigned int d = 0; d < dim; ++d)
        middle[d] = 0.5;
      std::vector<double>                      middle_values(n_base);
      std::vector<Tensor<1, dim>>              middle_gradients(n_base);
      std::vector<std::vector<Tensor<1, dim>>> gradients(
        unit_points.size(),
        std::vector<Tensor<1, dim>>(n_base));
      for (unsigned int k = 0; k < n_base; ++k)
        {
          middle_values[k]    = base.shape_value(k, middle);
          middle_gradients[k] = base.shape_grad(k, middle);
          for (unsigned int q = 0; q < unit_points.size(); ++q)
            gradients[q][k] = base.shape_grad(k, unit_points[q]);
        }
      const auto jacobian = [&](const std::vector<Point<dim>>     &nodes,
                                const std::vector<Tensor<1, dim>> &grads) {
        Tensor<2, dim> J;
        for (unsigned int k = 0; k < n_base; ++k)
          J += outer_product(static_cast<const Tensor<1, dim> &>(nodes[k]),
                             grads[k]);
        return determinant(J);
      };

      std::pair<double, Point<dim>> worst(
        std::numeric_limits<double>::infinity(),
        Point<dim>());
      std::vector<types::global_dof_index> local(fe.n_dofs_per_cell());
      std::vector<Point<dim>>              nodes(n_base);
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          cell->get_dof_indices(local);
          for (unsigned int i = 0; i < local.size(); ++i)
            {
              const auto [component, k] = fe.system_to_component_index(i);
              nodes[k][component]       = euler_vector[local[i]];
            }
          // Relative to |det J| at the centre, so that a cell inverted as a
          // whole counts as negative too.
          const double centre = std::abs(jacobian(nodes, middle_gradients));
          for (unsigned int q = 0; q < unit_points.size(); ++q)
            {
              const double ratio = jacobian(nodes, gradients[q]) / centre;
              if (!(ratio >= worst.first)) // NaN (centre = 0) is worst
                {
                  worst.first  = ratio;
                  worst.second = Point<dim>();
                  for (unsigned int k = 0; k < n_base; ++k)
                    worst.second += middle_values[k] * nodes[k];
                }
            }
        }
      return worst;
    }



    template <int dim>
    void
    LagrangeBody<dim>::assemble()
    {
      const auto &description = this->description();

      const elasticity::FEValuesEvaluator<dim> cell_values(
        *mapping,
        fe,
        QGauss<dim>(fe.degree + 1),
        update_values | update_gradients | update_JxW_values |
          (description.body_force_field ? update_quadrature_points :
                                          update_default));
      const elasticity::FEValuesEvaluator<dim, FEFaceValues<dim>> face_values(
        *mapping,
        fe,
        QGauss<dim - 1>(fe.degree + 1),
        update_values | update_quadrature_points | update_normal_vectors |
          update_JxW_values);
      this->assemble_history_loads(
        [&](const elasticity::BodyForce<dim>         &body_force,
            const std::vector<NeumannCondition<dim>> &tractions,
            SparseMatrix<double>                     &matrix,
            Vector<double>                           &rhs) {
          const auto [first, end] = this->assembly_cells;
          elasticity::assemble_system<dim>(
            dof_handler.begin_active(),
            dof_handler.end(),
            cell_values,
            face_values,
            description.material,
            body_force,
            tractions,
            matrix,
            rhs,
            [first = first, end = end](const auto &cell) {
              return cell->active_cell_index() >= first &&
                     cell->active_cell_index() < end;
            });
        },
        [&](const PointLoad<dim> &load, Vector<double> &rhs) {
          point_operator(load.location).distribute(load.force, rhs);
        });
    }



    template <int dim>
    std::pair<typename DoFHandler<dim>::active_cell_iterator, Point<dim>>
    LagrangeBody<dim>::find_cell(const Point<dim> &location) const
    {
      return find_cells(location, 0.).front();
    }



    template <int dim>
    std::vector<
      std::pair<typename DoFHandler<dim>::active_cell_iterator, Point<dim>>>
    LagrangeBody<dim>::find_cells(const Point<dim> &location,
                                  const double      tolerance) const
    {
      // Built once, on first use; its own data structures fill lazily, so
      // every search holds the lock (point searches run from threads).
      std::lock_guard<std::mutex> lock(cache_mutex);
      if (!cache)
        cache =
          std::make_unique<GridTools::Cache<dim>>(triangulation, *mapping);
      return locate_all(*cache, dof_handler, location, tolerance);
    }



    template <int dim>
    PointOperator<dim>
    LagrangeBody<dim>::point_operator(const Point<dim> &location) const
    {
      const auto  cell_and_point = find_cell(location);
      const auto &cell           = cell_and_point.first;
      Point<dim>  unit           = cell_and_point.second;
      for (unsigned int d = 0; d < dim; ++d)
        unit[d] = std::min(1., std::max(0., unit[d]));

      std::vector<types::global_dof_index> local(fe.n_dofs_per_cell());
      cell->get_dof_indices(local);
      const auto &base = fe.base_element(0);

      PointOperator<dim> op;
      op.weights.resize(base.n_dofs_per_cell());
      op.dofs.resize(base.n_dofs_per_cell());
      for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
        {
          const auto [component, k] = fe.system_to_component_index(i);
          op.dofs[k][component]     = local[i];
          if (component == 0)
            op.weights[k] = base.shape_value(k, unit);
        }
      return op;
    }



    template <int dim>
    std::vector<SurfacePoint<dim>>
    LagrangeBody<dim>::surface_points(const types::boundary_id face) const
    {
      // Pairs sit at the nodes of the face. The normal is the mesh normal,
      // averaged over the faces sharing a node; the tributary area is the
      // integral of the node's shape function over the face, which makes a
      // uniform pressure exact.
      std::map<types::global_dof_index, SurfacePoint<dim>> nodes;
      std::map<types::global_dof_index, Tensor<1, dim>>    normals;

      const auto &base        = fe.base_element(0);
      const auto &unit_points = base.get_unit_face_support_points(0);
      const Quadrature<dim - 1>            node_quadrature(unit_points);
      FEFaceValues<dim>                    node_values(surface_mapping(),
                                    fe,
                                    node_quadrature,
                                    update_quadrature_points |
                                      update_normal_vectors);
      FEFaceValues<dim>                    area_values(surface_mapping(),
                                    fe,
                                    QGauss<dim - 1>(fe.degree + 2),
                                    update_values | update_JxW_values);
      std::vector<types::global_dof_index> local(fe.n_dofs_per_cell());

      for (const auto &cell : dof_handler.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == face)
            {
              cell->get_dof_indices(local);
              node_values.reinit(cell, f);
              area_values.reinit(cell, f);
              for (unsigned int j = 0; j < base.n_dofs_per_face(); ++j)
                {
                  const unsigned int i_base = base.face_to_cell_index(j, f);
                  const unsigned int i_sys =
                    fe.component_to_system_index(0, i_base);
                  const types::global_dof_index key   = local[i_sys];
                  auto                         &point = nodes[key];
                  if (point.op.weights.empty())
                    {
                      point.location   = node_values.quadrature_point(j);
                      point.op.weights = {1.};
                      point.op.dofs.resize(1);
                      for (unsigned int c = 0; c < dim; ++c)
                        point.op.dofs[0][c] =
                          local[fe.component_to_system_index(c, i_base)];
                    }
                  normals[key] += node_values.normal_vector(j);
                  for (unsigned int q = 0; q < area_values.n_quadrature_points;
                       ++q)
                    point.tributary_area +=
                      area_values.shape_value(i_sys, q) * area_values.JxW(q);
                }
            }

      std::vector<SurfacePoint<dim>> result;
      for (auto &[key, point] : nodes)
        {
          point.normal = normals[key] / normals[key].norm();
          result.push_back(point);
        }
      return result;
    }



    template <int dim>
    void
    LagrangeBody<dim>::move_surface_geometry(const Vector<double> *u) const
    {
      moved_mapping.reset();
      moved_euler_vector.reinit(0);
      if (u == nullptr)
        return;
      // The unknowns and the support points share the DoF handler.
      moved_euler_vector = euler_vector;
      moved_euler_vector += *u;
      moved_mapping =
        std::make_unique<MappingFEField<dim, dim>>(dof_handler,
                                                   moved_euler_vector);
    }



    template class LagrangeBody<2>;
    template class LagrangeBody<3>;
  } // namespace discretization
} // namespace igabde
