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

#include <deal.II/fe/fe_poly.h>
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

// The fields of a Lagrange body: errors against an exact solution, stresses,
// the internal force at finite strain and its follower pressures, and the
// VTU output.

namespace igabde
{
  namespace discretization
  {
    template <int dim>
    ErrorNorms
    LagrangeBody<dim>::compute_errors(const Vector<double>     &u,
                                      const ExactSolution<dim> &exact) const
    {
      elasticity::FEValuesEvaluator<dim> values(*mapping,
                                                fe,
                                                QGauss<dim>(fe.degree + 3),
                                                update_values |
                                                  update_gradients |
                                                  update_quadrature_points |
                                                  update_JxW_values);
      return elasticity::compute_error_norms<dim>(dof_handler.begin_active(),
                                                  dof_handler.end(),
                                                  values,
                                                  u,
                                                  this->material(),
                                                  exact);
    }



    template <int dim>
    template <typename Value>
    auto
    LagrangeBody<dim>::mean_over_cells(const Vector<double> &u,
                                       const Point<dim>     &location,
                                       const Value          &value) const
    {
      // The cells and unit points come from the one search of find_cells():
      // a second search around its cell
      // (GridTools::find_all_active_cells_around_point) inverted the map on
      // every neighbour again.
      const auto cells = find_cells(location, 1e-8);
      AssertThrow(!cells.empty(), ExcInternalError());
      decltype(value(std::declval<const elasticity::FEValuesEvaluator<dim> &>(),
                     std::declval<const std::vector<double> &>())) sum;
      for (const auto &[cell, unit] : cells)
        {
          const Quadrature<dim> quadrature(std::vector<Point<dim>>(1, unit));
          elasticity::FEValuesEvaluator<dim> values(*mapping,
                                                    fe,
                                                    quadrature,
                                                    update_gradients);
          values.reinit(cell);
          std::vector<double> local_u;
          elasticity::get_local_values(values, u, local_u);
          sum += value(values, local_u);
        }
      return sum / static_cast<double>(cells.size());
    }



    template <int dim>
    SymmetricTensor<2, dim>
    LagrangeBody<dim>::stress(const Vector<double> &u,
                              const Point<dim>     &location) const
    {
      // The FE_Q stress jumps across cells: at a point on a face, edge or
      // vertex it is the mean over the cells that hold the point (within
      // 1e-8 in unit coordinates), so that the value does not depend on
      // which of them a search meets first (mean_over_cells()).
      return mean_over_cells(
        u,
        location,
        [this](const elasticity::FEValuesEvaluator<dim> &values,
               const std::vector<double>                &local_u) {
          return elasticity::stress(elasticity::strain<dim>(values, local_u, 0),
                                    this->material());
        });
    }



    namespace
    {
      /// Fields computed from the displacement gradient at each output
      /// point: @p names, their values written by @p fields.
      template <int dim>
      class GradientFieldsPostprocessor : public DataPostprocessor<dim>
      {
      public:
        using Fields = std::function<void(const Tensor<2, dim> &, double *)>;

        GradientFieldsPostprocessor(std::vector<std::string> names,
                                    Fields                   fields)
          : names(std::move(names))
          , fields(std::move(fields))
        {}

        void
        evaluate_vector_field(
          const DataPostprocessorInputs::Vector<dim> &inputs,
          std::vector<Vector<double>> &computed_quantities) const override
        {
          for (unsigned int q = 0; q < inputs.solution_gradients.size(); ++q)
            {
              Tensor<2, dim> grad;
              for (unsigned int c = 0; c < dim; ++c)
                grad[c] = inputs.solution_gradients[q][c];
              fields(grad, computed_quantities[q].data());
            }
        }

        std::vector<std::string>
        get_names() const override
        {
          return names;
        }

        UpdateFlags
        get_needed_update_flags() const override
        {
          return update_gradients;
        }

      private:
        const std::vector<std::string> names;
        const Fields                   fields;
      };

      /**
       * The strain and stress fields @p body writes: at small strain the
       * strain, Hooke's stress and its von Mises stress (components i <= j
       * row by row), at finite strain elasticity::finite_strain_fields().
       */
      template <int dim>
      std::unique_ptr<DataPostprocessor<dim>>
      output_postprocessor(const Body<dim> &body)
      {
        if (body.finite_strain())
          {
            const auto law = body.finite_law();
            return std::make_unique<GradientFieldsPostprocessor<dim>>(
              elasticity::finite_strain_field_names<dim>(),
              [law](const Tensor<2, dim> &grad, double *values) {
                elasticity::finite_strain_fields<dim>(grad, law, values);
              });
          }
        std::vector<std::string> names;
        const char               xyz[] = "xyz";
        for (const std::string prefix : {"strain_", "stress_"})
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = i; j < dim; ++j)
              names.push_back(prefix + xyz[i] + xyz[j]);
        names.push_back("von_mises");
        const elasticity::IsotropicMaterial<dim> material = body.material();
        return std::make_unique<GradientFieldsPostprocessor<dim>>(
          names,
          [material](const Tensor<2, dim> &grad, double *values) {
            const SymmetricTensor<2, dim> eps = symmetrize(grad);
            const SymmetricTensor<2, dim> sigma =
              elasticity::stress(eps, material);
            unsigned int k = 0;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = i; j < dim; ++j)
                values[k++] = eps[i][j];
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = i; j < dim; ++j)
                values[k++] = sigma[i][j];
            values[k] = elasticity::von_mises(sigma, material);
          });
      }



      /// The fields of LagrangeBody::write_vtu(): the displacement (a
      /// vector) and @p stresses' strain, stress and von Mises fields.
      template <int dim>
      void
      attach_output_fields(DataOut<dim>                 &data_out,
                           const DoFHandler<dim>        &dof_handler,
                           const Vector<double>         &u,
                           const DataPostprocessor<dim> &stresses)
      {
        data_out.attach_dof_handler(dof_handler);
        std::vector<DataComponentInterpretation::DataComponentInterpretation>
          interpretation(
            dim,
            DataComponentInterpretation::component_is_part_of_vector);
        data_out.add_data_vector(u,
                                 std::vector<std::string>(dim, "displacement"),
                                 DataOut<dim>::type_dof_data,
                                 interpretation);
        data_out.add_data_vector(u, stresses);
      }
    } // namespace



    template <int dim>
    void
    LagrangeBody<dim>::write_vtu(const Vector<double> &u,
                                 const std::string    &filename,
                                 const unsigned int    piece,
                                 const unsigned int    n_pieces) const
    {
      const auto   postprocessor = output_postprocessor<dim>(*this);
      DataOut<dim> data_out;
      attach_output_fields(data_out, dof_handler, u, *postprocessor);
      // The active cells [first, end) in their order.
      using cell_iterator   = typename Triangulation<dim>::cell_iterator;
      using active_iterator = typename Triangulation<dim>::active_cell_iterator;
      const auto [first, end] = this->output_cells(piece, n_pieces);
      data_out.set_cell_selection(
        [first = first, end = end](const Triangulation<dim> &tria) {
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->active_cell_index() >= first)
              {
                if (cell->active_cell_index() < end)
                  return cell_iterator(cell);
                break;
              }
          return tria.end();
        },
        [end = end](const Triangulation<dim> &tria, const cell_iterator &cell) {
          active_iterator next(cell);
          ++next;
          if (next == tria.end() || next->active_cell_index() >= end)
            return tria.end();
          return cell_iterator(next);
        });
      data_out.build_patches(*mapping,
                             std::max(fe.degree,
                                      output_subdivisions_for<dim>(
                                        this->settings.output_subdivisions,
                                        triangulation.n_active_cells())),
                             DataOut<dim>::curved_inner_cells);
      data_out.set_flags(base::vtu_flags(data_out.get_patches()));
      std::ofstream out = base::open_for_writing(filename);
      data_out.write_vtu(out);
    }



    template <int dim>
    void
    LagrangeBody<dim>::write_pvtu_record(
      const std::string              &filename,
      const std::vector<std::string> &piece_files) const
    {
      const auto           postprocessor = output_postprocessor<dim>(*this);
      DataOut<dim>         data_out;
      const Vector<double> u(dof_handler.n_dofs());
      attach_output_fields(data_out, dof_handler, u, *postprocessor);
      std::ofstream out = base::open_for_writing(filename);
      data_out.write_pvtu_record(out, piece_files);
    }



    template <int dim>
    double
    LagrangeBody<dim>::measure() const
    {
      elasticity::FEValuesEvaluator<dim> values(*mapping,
                                                fe,
                                                QGauss<dim>(fe.degree + 1),
                                                update_JxW_values);
      return elasticity::integrate_measure(dof_handler.begin_active(),
                                           dof_handler.end(),
                                           values);
    }



    template <int dim>
    std::pair<double, Point<dim>>
    LagrangeBody<dim>::largest_strain(const Vector<double> &u) const
    {
      AssertDimension(u.size(), this->n_unknowns);
      elasticity::FEValuesEvaluator<dim> values(*mapping,
                                                fe,
                                                QGauss<dim>(fe.degree + 1),
                                                update_values |
                                                  update_gradients |
                                                  update_quadrature_points);
      return elasticity::largest_strain<dim>(dof_handler.begin_active(),
                                             dof_handler.end(),
                                             values,
                                             u);
    }



    template <int dim>
    void
    LagrangeBody<dim>::add_follower_pressure(
      const Vector<double>      &u,
      const std::vector<double> &factors,
      Vector<double>            &residual,
      SparseMatrix<double>      *tangent) const
    {
      const auto pressures = this->follower_pressures(factors);
      if (pressures.empty())
        return;
      elasticity::FEValuesEvaluator<dim, FEFaceValues<dim>> face_values(
        *mapping,
        fe,
        QGauss<dim - 1>(fe.degree + 2),
        update_values | update_gradients | update_normal_vectors |
          update_JxW_values);
      elasticity::assemble_follower_pressure<dim>(dof_handler.begin_active(),
                                                  dof_handler.end(),
                                                  face_values,
                                                  pressures,
                                                  u,
                                                  residual,
                                                  tangent);
    }



    template <int dim>
    double
    LagrangeBody<dim>::internal_force(
      const Vector<double>                        &u,
      const elasticity::HyperelasticMaterial<dim> &material,
      Vector<double>                              &force,
      SparseMatrix<double>                        *tangent) const
    {
      AssertDimension(u.size(), this->n_unknowns);
      AssertDimension(force.size(), this->n_unknowns);
      // P = F S is of higher degree than the linear stress: one point more
      // per direction than the stiffness.
      const elasticity::FEValuesEvaluator<dim> values(
        *mapping,
        fe,
        QGauss<dim>(fe.degree + 2),
        update_values | update_gradients | update_JxW_values);
      return elasticity::assemble_internal_force<dim>(
        dof_handler.begin_active(),
        dof_handler.end(),
        values,
        material,
        u,
        force,
        tangent);
    }



    template <int dim>
    Tensor<2, dim>
    LagrangeBody<dim>::displacement_gradient(const Vector<double> &u,
                                             const Point<dim> &location) const
    {
      return mean_over_cells(
        u,
        location,
        [](const elasticity::FEValuesEvaluator<dim> &values,
           const std::vector<double>                &local_u) {
          return elasticity::displacement_gradient<dim>(values, local_u, 0);
        });
    }



    template <int dim>
    FaceGrid<dim>
    LagrangeBody<dim>::face_grid(const types::boundary_id face) const
    {
      AssertThrow(patch_of_face<dim>(face) < patches.size(),
                  ExcMessage("Body '" + this->description().name + "': face " +
                             this->face_name(face) + " does not exist."));
      const auto   &patch = patches[patch_of_face<dim>(face)];
      FaceGrid<dim> grid;
      for (unsigned int e = 0, k = 0; e < dim; ++e)
        if (e != local_face<dim>(face) / 2)
          grid.breaks[k++] = patch.breakpoints(e);
      grid.degree = fe.degree;
      return grid;
    }



    template <int dim>
    std::pair<typename DoFHandler<dim>::active_cell_iterator, Point<dim>>
    LagrangeBody<dim>::face_cell(const types::boundary_id body_face,
                                 const Point<dim - 1>    &eta) const
    {
      const unsigned int p     = patch_of_face<dim>(body_face);
      const unsigned int face  = local_face<dim>(body_face);
      const auto        &patch = patches.at(p);
      const unsigned int d     = face / 2;
      // The parametric point of the patch, its span and cell.
      Point<dim> xi;
      for (unsigned int e = 0, k = 0; e < dim; ++e)
        xi[e] = (e == d ? (face % 2 == 0 ? patch.parametric_lower()[d] :
                                           patch.parametric_upper()[d]) :
                          eta[k++]);
      std::array<std::vector<double>, dim> breaks;
      for (unsigned int e = 0; e < dim; ++e)
        breaks[e] = patch.breakpoints(e);
      const auto it =
        cell_of_span[p].find(nurbs::span_of_point<dim>(breaks, xi));
      Assert(it != cell_of_span[p].end(), ExcInternalError());
      const auto           &cell = it->second;
      const CellParameters &c    = cell_parameters[cell->active_cell_index()];

      // Unit coordinates in the cell: unit axis e runs along parametric
      // direction c.direction[e].
      Point<dim> unit;
      for (unsigned int e = 0; e < dim; ++e)
        {
          const unsigned int k = c.direction[e];
          unit[e] =
            std::min(1., std::max(0., (xi[k] - c.origin[k]) / c.length[e]));
          // On the face exactly, so that the functions of the other nodes
          // vanish there.
          if (k == d)
            unit[e] = std::round(unit[e]);
        }
      return {cell, unit};
    }



    template <int dim>
    FacePoint<dim>
    LagrangeBody<dim>::face_point(const types::boundary_id body_face,
                                  const Point<dim - 1>    &eta) const
    {
      const unsigned int d    = local_face<dim>(body_face) / 2;
      const unsigned int face = local_face<dim>(body_face);
      const auto [cell, unit] = face_cell(body_face, eta);
      const CellParameters &c = cell_parameters[cell->active_cell_index()];
      std::vector<types::global_dof_index> local(fe.n_dofs_per_cell());
      cell->get_dof_indices(local);
      const auto           &base = fe.base_element(0);
      const Vector<double> &x    = surface_geometry();
      FacePoint<dim>        result;
      result.op.weights.resize(base.n_dofs_per_cell());
      result.op.dofs.resize(base.n_dofs_per_cell());
      // Every shape function's value and gradient at once, from the
      // element's polynomial space (the same numbers as shape_value() and
      // shape_grad() one by one, each of which evaluates the 1D
      // polynomials again).
      const unsigned int                       n_shape = base.n_dofs_per_cell();
      thread_local std::vector<double>         values;
      thread_local std::vector<Tensor<1, dim>> grads;
      thread_local std::vector<Tensor<2, dim>> no_second;
      thread_local std::vector<Tensor<3, dim>> no_third;
      thread_local std::vector<Tensor<4, dim>> no_fourth;
      values.resize(n_shape);
      grads.resize(n_shape);
      const auto *poly = dynamic_cast<const FE_Poly<dim> *>(&base);
      if (poly != nullptr)
        poly->get_poly_space()
          .evaluate(unit, values, grads, no_second, no_third, no_fourth);
      else
        for (unsigned int k = 0; k < n_shape; ++k)
          {
            values[k] = base.shape_value(k, unit);
            grads[k]  = base.shape_grad(k, unit);
          }
      Tensor<2, dim> J; // dx/dxi (patch coordinates)
      result.gradients.assign(n_shape, std::array<double, dim - 1>());
      for (unsigned int k = 0; k < n_shape; ++k)
        {
          const double          value = values[k];
          const Tensor<1, dim> &grad  = grads[k];
          result.op.weights[k]        = value;
          // d/deta: face coordinate f is patch direction e_f (e_f != d),
          // unit axis a of the cell with c.direction[a] = e_f.
          for (unsigned int a = 0; a < dim; ++a)
            if (c.direction[a] != d)
              result.gradients[k][c.direction[a] < d ? c.direction[a] :
                                                       c.direction[a] - 1] =
                grad[a] / c.length[a];
          for (unsigned int comp = 0; comp < dim; ++comp)
            {
              const auto i = local[fe.component_to_system_index(comp, k)];
              result.op.dofs[k][comp] = i;
              result.location[comp] += value * x[i];
              for (unsigned int e = 0; e < dim; ++e)
                J[comp][c.direction[e]] += x[i] * grad[e] / c.length[e];
            }
        }
      // Outward normal along +-grad xi_d = J^-T e_d; dGamma = |det J|
      // |J^-T e_d| deta.
      const Tensor<2, dim> G = transpose(invert(J));
      Tensor<1, dim>       g = G * Tensor<1, dim>(Point<dim>::unit_vector(d));
      const double         norm = g.norm();
      result.normal             = (face % 2 == 0 ? -1. : 1.) / norm * g;
      result.measure            = std::abs(determinant(J)) * norm;
      for (unsigned int e = 0, k = 0; e < dim; ++e)
        if (e != d)
          {
            for (unsigned int comp = 0; comp < dim; ++comp)
              result.tangents[k][comp] = J[comp][e];
            ++k;
          }
      return result;
    }



    template <int dim>
    FaceSecondDerivatives<dim>
    LagrangeBody<dim>::face_second_derivatives(
      const types::boundary_id body_face,
      const Point<dim - 1>    &eta) const
    {
      const unsigned int d       = local_face<dim>(body_face) / 2;
      const auto [cell, unit]    = face_cell(body_face, eta);
      const CellParameters &c    = cell_parameters[cell->active_cell_index()];
      const auto           &base = fe.base_element(0);
      const unsigned int    n_shape = base.n_dofs_per_cell();
      std::vector<types::global_dof_index> local(fe.n_dofs_per_cell());
      cell->get_dof_indices(local);
      // The cell's unit axis of each face coordinate.
      std::array<unsigned int, dim - 1> axis;
      for (unsigned int a = 0; a < dim; ++a)
        if (c.direction[a] != d)
          axis[c.direction[a] < d ? c.direction[a] : c.direction[a] - 1] = a;
      const Vector<double>      &x = surface_geometry();
      FaceSecondDerivatives<dim> result;
      for (unsigned int k = 0; k < n_shape; ++k)
        {
          const Tensor<2, dim> hessian = base.shape_grad_grad(k, unit);
          for (unsigned int comp = 0; comp < dim; ++comp)
            {
              const double xk = x[local[fe.component_to_system_index(comp, k)]];
              for (unsigned int a = 0; a + 1 < dim; ++a)
                for (unsigned int b = 0; b + 1 < dim; ++b)
                  result[a][b][comp] += xk * hessian[axis[a]][axis[b]] /
                                        (c.length[axis[a]] * c.length[axis[b]]);
            }
        }
      return result;
    }



    template FaceGrid<2>
    LagrangeBody<2>::face_grid(const types::boundary_id face) const;
    template FaceGrid<3>
    LagrangeBody<3>::face_grid(const types::boundary_id face) const;
    template FacePoint<2>
    LagrangeBody<2>::face_point(const types::boundary_id body_face,
                                const Point<2 - 1>      &eta) const;
    template FacePoint<3>
    LagrangeBody<3>::face_point(const types::boundary_id body_face,
                                const Point<3 - 1>      &eta) const;
    template FaceSecondDerivatives<2>
    LagrangeBody<2>::face_second_derivatives(const types::boundary_id,
                                             const Point<2 - 1> &) const;
    template FaceSecondDerivatives<3>
    LagrangeBody<3>::face_second_derivatives(const types::boundary_id,
                                             const Point<3 - 1> &) const;
    template ErrorNorms
    LagrangeBody<2>::compute_errors(const Vector<double>   &u,
                                    const ExactSolution<2> &exact) const;
    template ErrorNorms
    LagrangeBody<3>::compute_errors(const Vector<double>   &u,
                                    const ExactSolution<3> &exact) const;
    template SymmetricTensor<2, 2>
    LagrangeBody<2>::stress(const Vector<double> &u,
                            const Point<2>       &location) const;
    template SymmetricTensor<2, 3>
    LagrangeBody<3>::stress(const Vector<double> &u,
                            const Point<3>       &location) const;
    template void
    LagrangeBody<2>::write_vtu(const Vector<double> &u,
                               const std::string    &filename,
                               const unsigned int    piece,
                               const unsigned int    n_pieces) const;
    template void
    LagrangeBody<3>::write_vtu(const Vector<double> &u,
                               const std::string    &filename,
                               const unsigned int    piece,
                               const unsigned int    n_pieces) const;
    template void
    LagrangeBody<2>::write_pvtu_record(
      const std::string              &filename,
      const std::vector<std::string> &piece_files) const;
    template void
    LagrangeBody<3>::write_pvtu_record(
      const std::string              &filename,
      const std::vector<std::string> &piece_files) const;
    template double
    LagrangeBody<2>::measure() const;
    template double
    LagrangeBody<3>::measure() const;
    template std::pair<double, Point<2>>
    LagrangeBody<2>::largest_strain(const Vector<double> &u) const;
    template std::pair<double, Point<3>>
    LagrangeBody<3>::largest_strain(const Vector<double> &u) const;
    template void
    LagrangeBody<2>::add_follower_pressure(const Vector<double>      &u,
                                           const std::vector<double> &factors,
                                           Vector<double>            &residual,
                                           SparseMatrix<double> *tangent) const;
    template void
    LagrangeBody<3>::add_follower_pressure(const Vector<double>      &u,
                                           const std::vector<double> &factors,
                                           Vector<double>            &residual,
                                           SparseMatrix<double> *tangent) const;
    template double
    LagrangeBody<2>::internal_force(
      const Vector<double>                      &u,
      const elasticity::HyperelasticMaterial<2> &material,
      Vector<double>                            &force,
      SparseMatrix<double>                      *tangent) const;
    template double
    LagrangeBody<3>::internal_force(
      const Vector<double>                      &u,
      const elasticity::HyperelasticMaterial<3> &material,
      Vector<double>                            &force,
      SparseMatrix<double>                      *tangent) const;
    template Tensor<2, 2>
    LagrangeBody<2>::displacement_gradient(const Vector<double> &u,
                                           const Point<2> &location) const;
    template Tensor<2, 3>
    LagrangeBody<3>::displacement_gradient(const Vector<double> &u,
                                           const Point<3> &location) const;
  } // namespace discretization
} // namespace igabde
