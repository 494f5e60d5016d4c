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

// The fields of a NURBS body: errors against an exact solution, stresses,
// the internal force at finite strain and its follower pressures, and the
// VTU output.

namespace igabde
{
  namespace discretization
  {
    template <int dim>
    ErrorNorms
    IgaBody<dim>::compute_errors(const Vector<double>     &u,
                                 const ExactSolution<dim> &exact) const
    {
      AssertDimension(u.size(), this->n_unknowns);
      // The norms of every patch, from their integrals.
      ErrorNorms result;
      for (const PatchSpace &space : spaces)
        {
          nurbs::NurbsValues<dim> values(space.geometry,
                                         QGauss<dim>(max_degree() + 3),
                                         update_values | update_gradients |
                                           update_quadrature_points |
                                           update_JxW_values);
          values.number_unknowns_by(space.numbers);
          result.add(
            elasticity::compute_error_norms<dim>(space.mesh.begin_active(),
                                                 space.mesh.end(),
                                                 values,
                                                 u,
                                                 this->material(),
                                                 exact),
            static_cast<bool>(exact.stress));
        }
      return result;
    }



    template <int dim>
    SymmetricTensor<2, dim>
    IgaBody<dim>::stress(const Vector<double> &u,
                         const Point<dim>     &location) const
    {
      const auto [p, xi] = locate(location);
      return elasticity::stress(strain_at_parametric(u, xi, p),
                                this->material());
    }



    template <int dim>
    double
    IgaBody<dim>::measure() const
    {
      // Affine (polynomial) patches are integrated exactly by p+1 points;
      // rational ones need many more for round-off accuracy.
      const bool        rational = n_quadrature_points_1d() > max_degree() + 1;
      const QGauss<dim> quadrature(rational ? std::max(max_degree() + 1, 12u) :
                                              max_degree() + 1);
      double            result = 0.;
      for (const PatchSpace &space : spaces)
        {
          nurbs::NurbsValues<dim> values(space.geometry,
                                         quadrature,
                                         update_JxW_values);
          result += elasticity::integrate_measure(space.mesh.begin_active(),
                                                  space.mesh.end(),
                                                  values);
        }
      return result;
    }



    template <int dim>
    std::pair<double, Point<dim>>
    IgaBody<dim>::largest_strain(const Vector<double> &u) const
    {
      AssertDimension(u.size(), this->n_unknowns);
      std::pair<double, Point<dim>> result(0., Point<dim>());
      for (const PatchSpace &space : spaces)
        {
          nurbs::NurbsValues<dim> values(space.geometry,
                                         QGauss<dim>(max_degree() + 1),
                                         update_values | update_gradients |
                                           update_quadrature_points);
          values.number_unknowns_by(space.numbers);
          const auto part =
            elasticity::largest_strain<dim>(space.mesh.begin_active(),
                                            space.mesh.end(),
                                            values,
                                            u);
          if (&space == &spaces.front() ||
              std::abs(part.first) > std::abs(result.first))
            result = part;
        }
      return result;
    }



    template <int dim>
    void
    IgaBody<dim>::add_follower_pressure(const Vector<double>      &u,
                                        const std::vector<double> &factors,
                                        Vector<double>            &residual,
                                        SparseMatrix<double> *tangent) const
    {
      const auto pressures = this->follower_pressures(factors);
      if (pressures.empty())
        return;
      // Each patch's pressures on its own face numbers, with as many face
      // points as the tractions of the linear path.
      for (unsigned int p = 0; p < spaces.size(); ++p)
        {
          std::vector<std::pair<types::boundary_id, double>> mine;
          for (const auto &[id, pressure] : pressures)
            if (patch_of_face<dim>(id) == p)
              mine.emplace_back(local_face<dim>(id), pressure);
          if (mine.empty())
            continue;
          nurbs::NurbsValues<dim> face_values(spaces[p].geometry,
                                              QGauss<dim - 1>(
                                                n_quadrature_points_1d() + 1),
                                              update_values | update_gradients |
                                                update_normal_vectors |
                                                update_JxW_values);
          face_values.number_unknowns_by(spaces[p].numbers);
          elasticity::assemble_follower_pressure<dim>(
            spaces[p].mesh.begin_active(),
            spaces[p].mesh.end(),
            face_values,
            mine,
            u,
            residual,
            tangent);
        }
    }



    template <int dim>
    double
    IgaBody<dim>::internal_force(
      const Vector<double>                        &u,
      const elasticity::HyperelasticMaterial<dim> &material,
      Vector<double>                              &force,
      SparseMatrix<double>                        *tangent) const
    {
      AssertDimension(u.size(), this->n_unknowns);
      AssertDimension(force.size(), this->n_unknowns);
      // P = F S is of higher degree than the linear stress: one point more
      // per direction than the stiffness.
      double min_J = std::numeric_limits<double>::max();
      for (const PatchSpace &space : spaces)
        {
          nurbs::NurbsValues<dim> values(
            space.geometry,
            QGauss<dim>(n_quadrature_points_1d() + 1),
            update_values | update_gradients | update_JxW_values);
          values.number_unknowns_by(space.numbers);
          min_J = std::min(
            min_J,
            elasticity::assemble_internal_force<dim>(space.mesh.begin_active(),
                                                     space.mesh.end(),
                                                     values,
                                                     material,
                                                     u,
                                                     force,
                                                     tangent));
        }
      return min_J;
    }



    template <int dim>
    SymmetricTensor<2, dim>
    IgaBody<dim>::strain_at_parametric(const Vector<double> &u,
                                       const Point<dim>     &xi_in,
                                       const unsigned int    p) const
    {
      AssertDimension(u.size(), this->n_unknowns);
      // Where the map is singular (a collapsed corner, or two faces meeting
      // at a straight angle) the discrete strain has no limit: its
      // components across the degenerate direction are a difference of
      // parametric derivatives that the discrete field does not cancel,
      // divided by det J, and grow like 1/distance (V5's corner read a von
      // Mises stress of 1.6e5 against 54 elsewhere one step of 1e-8 in).
      // It is therefore read a short step inside, towards the centre of
      // the parametric box, where J is well conditioned: |det J| at least
      // 1e-3 |J|^dim, about 1e-3 of the patch from the corner.
      const auto [points, gradients] = basis_gradients(xi_in, p);
      SymmetricTensor<2, dim> eps;
      for (unsigned int l = 0; l < points.size(); ++l)
        for (unsigned int c = 0; c < dim; ++c)
          elasticity::add_basis_strain<dim>(u[dim * points[l] + c],
                                            gradients[l],
                                            c,
                                            eps);
      return eps;
    }



    template <int dim>
    std::pair<Point<dim>, Tensor<2, dim>>
    IgaBody<dim>::regular_point(const Point<dim>  &xi_in,
                                const unsigned int p) const
    {
      const auto      &geometry = spaces.at(p).geometry;
      const Point<dim> lo       = geometry.parametric_lower();
      const Point<dim> hi       = geometry.parametric_upper();
      const Point<dim> centre   = 0.5 * (lo + hi);
      Point<dim>       xi       = xi_in;
      Tensor<2, dim>   J        = geometry.jacobian(xi);
      for (unsigned int k = 0; k < 8; ++k)
        {
          const double scale = std::pow(J.norm(), dim);
          if (std::abs(determinant(J)) > 1e-3 * scale && scale > 0.)
            break;
          xi = xi + std::pow(10., -8. + k) * (centre - xi_in);
          J  = geometry.jacobian(xi);
        }
      return {xi, J};
    }



    template <int dim>
    std::pair<std::vector<unsigned int>, std::vector<Tensor<1, dim>>>
    IgaBody<dim>::basis_gradients(const Point<dim>  &xi_in,
                                  const unsigned int p) const
    {
      const auto &geometry = spaces.at(p).geometry;
      const auto &numbers  = spaces[p].numbers;
      const auto [xi, J]   = regular_point(xi_in, p);
      std::vector<unsigned int>   indices;
      std::vector<double>         R;
      std::vector<Tensor<1, dim>> dR;
      geometry.basis(xi, indices, R, &dR);
      const Tensor<2, dim>        JinvT = transpose(invert(J));
      std::vector<Tensor<1, dim>> gradients(indices.size());
      for (unsigned int l = 0; l < indices.size(); ++l)
        {
          gradients[l] = JinvT * dR[l];
          indices[l]   = numbers[indices[l]];
        }
      return {indices, gradients};
    }



    template <int dim>
    Tensor<2, dim>
    IgaBody<dim>::gradient_at_parametric(const Vector<double> &u,
                                         const Point<dim>     &xi_in,
                                         const unsigned int    p) const
    {
      AssertDimension(u.size(), this->n_unknowns);
      const auto [points, gradients] = basis_gradients(xi_in, p);
      Tensor<2, dim> grad_u;
      for (unsigned int l = 0; l < points.size(); ++l)
        for (unsigned int c = 0; c < dim; ++c)
          grad_u[c] += u[dim * points[l] + c] * gradients[l];
      return grad_u;
    }



    template <int dim>
    Tensor<2, dim>
    IgaBody<dim>::displacement_gradient(const Vector<double> &u,
                                        const Point<dim>     &location) const
    {
      const auto [p, xi] = locate(location);
      return gradient_at_parametric(u, xi, p);
    }



    namespace
    {
      /// The symmetric tensor components written: (i, i), then (i, j), i < j.
      template <int dim>
      std::vector<std::pair<unsigned int, unsigned int>>
      iga_output_components()
      {
        std::vector<std::pair<unsigned int, unsigned int>> comps;
        for (unsigned int i = 0; i < dim; ++i)
          comps.emplace_back(i, i);
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i + 1; j < dim; ++j)
            comps.emplace_back(i, j);
        return comps;
      }



      /// The fields of IgaBody::write_vtu(), in their order: displacement,
      /// strain and stress components (xx, yy[, zz], then the pairs i < j),
      /// von Mises; at @p finite strain those of
      /// elasticity::finite_strain_field_names(); and the displacement as
      /// one vector.
      template <int dim>
      std::pair<std::vector<std::string>,
                std::vector<std::tuple<
                  unsigned int,
                  unsigned int,
                  std::string,
                  DataComponentInterpretation::DataComponentInterpretation>>>
      iga_output_fields(const bool finite)
      {
        static const char       *axis = "xyz";
        std::vector<std::string> names(dim, "displacement");
        if (finite)
          for (const std::string &name :
               elasticity::finite_strain_field_names<dim>())
            names.push_back(name);
        else
          {
            for (const auto &[i, j] : iga_output_components<dim>())
              names.push_back(std::string("strain_") + axis[i] + axis[j]);
            for (const auto &[i, j] : iga_output_components<dim>())
              names.push_back(std::string("stress_") + axis[i] + axis[j]);
            names.emplace_back("von_mises");
          }
        return {names,
                {{0,
                  dim - 1,
                  "displacement",
                  DataComponentInterpretation::component_is_part_of_vector}}};
      }
    } // namespace



    template <int dim>
    void
    IgaBody<dim>::write_vtu(const Vector<double> &u,
                            const std::string    &filename,
                            const unsigned int    piece,
                            const unsigned int    n_pieces) const
    {
      AssertDimension(u.size(), this->n_unknowns);
      const unsigned int n_sub =
        output_subdivisions_for<dim>(this->settings.output_subdivisions,
                                     n_elements());
      const auto &material = this->material();

      // Output points: lexicographic (n+1)^dim grid on [0, 1]^dim.
      std::vector<Point<dim>> ref;
      {
        const unsigned int n1 = n_sub + 1;
        unsigned int       n  = 1;
        for (unsigned int d = 0; d < dim; ++d)
          n *= n1;
        ref.resize(n);
        for (unsigned int s = 0; s < n; ++s)
          {
            unsigned int rest = s;
            for (unsigned int d = 0; d < dim; ++d)
              {
                ref[s][d] = static_cast<double>(rest % n1) / n_sub;
                rest /= n1;
              }
          }
      }

      const auto comps = iga_output_components<dim>();
      const auto [names, ranges] =
        iga_output_fields<dim>(this->finite_strain());
      const unsigned int n_data = names.size();
      const auto [first, end]   = this->output_cells(piece, n_pieces);

      std::vector<DataOutBase::Patch<dim, dim>> patches;
      std::vector<double>                       local_u;
      // At finite strain: the law and one point's values.
      std::optional<elasticity::HyperelasticMaterial<dim>> law;
      if (this->finite_strain())
        law.emplace(this->finite_law());
      std::vector<double> finite_values(n_data + dim);
      unsigned int        index = 0, cell_index = 0;
      for (unsigned int p = 0; p < spaces.size(); ++p)
        {
          nurbs::NurbsValues<dim> ev(spaces[p].geometry,
                                     Quadrature<dim>(ref),
                                     update_values | update_gradients |
                                       update_quadrature_points);
          ev.number_unknowns_by(spaces[p].numbers);
          for (const auto &cell : spaces[p].mesh.active_cell_iterators())
            {
              if (cell_index < first || cell_index >= end)
                {
                  ++cell_index;
                  continue;
                }
              ++cell_index;
              ev.reinit(cell);
              elasticity::get_local_values(ev, u, local_u);
              DataOutBase::Patch<dim, dim> patch;
              patch.n_subdivisions       = n_sub;
              patch.points_are_available = true;
              patch.patch_index          = index++;
              patch.reference_cell       = ReferenceCells::get_hypercube<dim>();
              for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell;
                   ++v)
                {
                  unsigned int s = 0, stride = 1;
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      s += ((v >> d) & 1u) * n_sub * stride;
                      stride *= n_sub + 1;
                    }
                  patch.vertices[v] = ev.quadrature_point(s);
                }
              patch.data.reinit(n_data + dim, ref.size());
              for (unsigned int q = 0; q < ref.size(); ++q)
                {
                  const Tensor<1, dim> uh =
                    elasticity::displacement<dim>(ev, local_u, q);
                  if (law)
                    {
                      const Tensor<2, dim> grad_u =
                        ev.regular(q) ?
                          elasticity::displacement_gradient<dim>(ev,
                                                                 local_u,
                                                                 q) :
                          gradient_at_parametric(u, ev.parametric_point(q), p);
                      for (unsigned int c = 0; c < dim; ++c)
                        finite_values[c] = uh[c];
                      elasticity::finite_strain_fields<dim>(
                        grad_u,
                        *law,
                        finite_values.data() + dim);
                      for (unsigned int d = 0; d < dim; ++d)
                        finite_values[n_data + d] = ev.quadrature_point(q)[d];
                      for (unsigned int row = 0; row < n_data + dim; ++row)
                        patch.data(row, q) = finite_values[row];
                      continue;
                    }
                  // Where the map is singular (a collapsed corner) the strain
                  // is read a short step inside (strain_at_parametric()).
                  const SymmetricTensor<2, dim> eps =
                    ev.regular(q) ?
                      elasticity::strain<dim>(ev, local_u, q) :
                      strain_at_parametric(u, ev.parametric_point(q), p);
                  const SymmetricTensor<2, dim> sigma =
                    elasticity::stress(eps, material);
                  const double vm = elasticity::von_mises(sigma, material);

                  unsigned int row = 0;
                  for (unsigned int c = 0; c < dim; ++c)
                    patch.data(row++, q) = uh[c];
                  for (const auto &[i, j] : comps)
                    patch.data(row++, q) = eps[i][j];
                  for (const auto &[i, j] : comps)
                    patch.data(row++, q) = sigma[i][j];
                  patch.data(row++, q) = vm;
                  for (unsigned int d = 0; d < dim; ++d)
                    patch.data(row++, q) = ev.quadrature_point(q)[d];
                }
              patches.push_back(std::move(patch));
            }
        }

      std::ofstream out = base::open_for_writing(filename);
      DataOutBase::write_vtu(patches,
                             names,
                             ranges,
                             base::vtu_flags(patches),
                             out);
    }



    template <int dim>
    void
    IgaBody<dim>::write_pvtu_record(
      const std::string              &filename,
      const std::vector<std::string> &piece_files) const
    {
      const auto [names, ranges] =
        iga_output_fields<dim>(this->finite_strain());
      std::ofstream out = base::open_for_writing(filename);
      DataOutBase::write_pvtu_record(out,
                                     piece_files,
                                     names,
                                     ranges,
                                     DataOutBase::VtkFlags());
    }



    template ErrorNorms
    IgaBody<2>::compute_errors(const Vector<double>   &u,
                               const ExactSolution<2> &exact) const;
    template ErrorNorms
    IgaBody<3>::compute_errors(const Vector<double>   &u,
                               const ExactSolution<3> &exact) const;
    template SymmetricTensor<2, 2>
    IgaBody<2>::stress(const Vector<double> &u, const Point<2> &location) const;
    template SymmetricTensor<2, 3>
    IgaBody<3>::stress(const Vector<double> &u, const Point<3> &location) const;
    template double
    IgaBody<2>::measure() const;
    template double
    IgaBody<3>::measure() const;
    template std::pair<double, Point<2>>
    IgaBody<2>::largest_strain(const Vector<double> &u) const;
    template std::pair<double, Point<3>>
    IgaBody<3>::largest_strain(const Vector<double> &u) const;
    template void
    IgaBody<2>::add_follower_pressure(const Vector<double>      &u,
                                      const std::vector<double> &factors,
                                      Vector<double>            &residual,
                                      SparseMatrix<double>      *tangent) const;
    template void
    IgaBody<3>::add_follower_pressure(const Vector<double>      &u,
                                      const std::vector<double> &factors,
                                      Vector<double>            &residual,
                                      SparseMatrix<double>      *tangent) const;
    template double
    IgaBody<2>::internal_force(
      const Vector<double>                      &u,
      const elasticity::HyperelasticMaterial<2> &material,
      Vector<double>                            &force,
      SparseMatrix<double>                      *tangent) const;
    template double
    IgaBody<3>::internal_force(
      const Vector<double>                      &u,
      const elasticity::HyperelasticMaterial<3> &material,
      Vector<double>                            &force,
      SparseMatrix<double>                      *tangent) const;
    template void
    IgaBody<2>::write_vtu(const Vector<double> &u,
                          const std::string    &filename,
                          const unsigned int    piece,
                          const unsigned int    n_pieces) const;
    template void
    IgaBody<3>::write_vtu(const Vector<double> &u,
                          const std::string    &filename,
                          const unsigned int    piece,
                          const unsigned int    n_pieces) const;
    template void
    IgaBody<2>::write_pvtu_record(
      const std::string              &filename,
      const std::vector<std::string> &piece_files) const;
    template void
    IgaBody<3>::write_pvtu_record(
      const std::string              &filename,
      const std::vector<std::string> &piece_files) const;
    template SymmetricTensor<2, 2>
    IgaBody<2>::strain_at_parametric(const Vector<double> &u,
                                     const Point<2>       &xi_in,
                                     const unsigned int    p) const;
    template SymmetricTensor<2, 3>
    IgaBody<3>::strain_at_parametric(const Vector<double> &u,
                                     const Point<3>       &xi_in,
                                     const unsigned int    p) const;
    template std::pair<Point<2>, Tensor<2, 2>>
    IgaBody<2>::regular_point(const Point<2>    &xi_in,
                              const unsigned int p) const;
    template std::pair<Point<3>, Tensor<2, 3>>
    IgaBody<3>::regular_point(const Point<3>    &xi_in,
                              const unsigned int p) const;
    template std::pair<std::vector<unsigned int>, std::vector<Tensor<1, 2>>>
    IgaBody<2>::basis_gradients(const Point<2>    &xi_in,
                                const unsigned int p) const;
    template std::pair<std::vector<unsigned int>, std::vector<Tensor<1, 3>>>
    IgaBody<3>::basis_gradients(const Point<3>    &xi_in,
                                const unsigned int p) const;
    template Tensor<2, 2>
    IgaBody<2>::gradient_at_parametric(const Vector<double> &u,
                                       const Point<2>       &xi_in,
                                       const unsigned int    p) const;
    template Tensor<2, 3>
    IgaBody<3>::gradient_at_parametric(const Vector<double> &u,
                                       const Point<3>       &xi_in,
                                       const unsigned int    p) const;
    template Tensor<2, 2>
    IgaBody<2>::displacement_gradient(const Vector<double> &u,
                                      const Point<2>       &location) const;
    template Tensor<2, 3>
    IgaBody<3>::displacement_gradient(const Vector<double> &u,
                                      const Point<3>       &location) const;
  } // namespace discretization
} // namespace igabde
