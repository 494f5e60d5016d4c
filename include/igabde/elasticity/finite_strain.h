#ifndef igabde_elasticity_finite_strain_h
#define igabde_elasticity_finite_strain_h

#include <igabde/elasticity/hyperelastic.h>

#include <deal.II/base/parallel.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/thread_local_storage.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <type_traits>
#include <vector>

/**
 * @file
 * Finite-strain elasticity written once for both discretisations, against
 * the evaluator interface of elasticity/assembly.h (deal.II's FEValues
 * through FEValuesEvaluator, the NURBS knot-span evaluator NurbsValues):
 * the total Lagrangian internal force of a cell and its consistent
 * tangent, with gradients with respect to the reference configuration.
 */

namespace igabde
{
  namespace elasticity
  {
    using namespace dealii;

    /**
     * @brief grad u_h(X_q) (reference gradient, grad_u[c][J] = d u_c /
     * d X_J) from the cell coefficients @p local_u (cell-local order).
     */
    template <int dim, typename Values>
    Tensor<2, dim>
    displacement_gradient(const Values              &values,
                          const std::vector<double> &local_u,
                          const unsigned int         q)
    {
      Tensor<2, dim> grad_u;
      for (unsigned int l = 0; l < values.n_basis(); ++l)
        {
          const Tensor<1, dim> &g = values.shape_grad(l, q);
          for (unsigned int c = 0; c < dim; ++c)
            grad_u[c] += local_u[values.local_dof(l, c)] * g;
        }
      return grad_u;
    }

    /**
     * @brief The cell's internal force r_i = int P : grad(N_i) dX
     * (P = F S, the first Piola-Kirchhoff stress) at the displacement
     * @p local_u, added to @p residual, and with @p tangent (not nullptr)
     * its derivative K_ij = d r_i / d u_j added to it:
     * int dE_i : D : dE_j + grad N_i . S grad N_j delta_cd dX, the material
     * and the geometric (initial stress) parts, dE_i = sym(F^T grad(N_i)).
     * Returns the smallest det F at the cell's points (not positive: the
     * map has inverted there and the stress is not defined, which the
     * caller must treat as a failed iterate).
     */
    template <int dim, typename Values>
    double
    add_cell_internal_force(const Values                    &values,
                            const std::vector<double>       &local_u,
                            const HyperelasticMaterial<dim> &material,
                            Vector<double>                  &residual,
                            FullMatrix<double>              *tangent)
    {
      const unsigned int n_basis = values.n_basis();
      double             min_J   = std::numeric_limits<double>::max();
      for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
        {
          const Tensor<2, dim> F = deformation_gradient<dim>(
            displacement_gradient<dim>(values, local_u, q));
          const double J = determinant(F);
          min_J          = std::min(min_J, J);
          if (!(J > 0.))
            continue;
          const SymmetricTensor<2, dim> C = right_cauchy_green(F);
          const SymmetricTensor<2, dim> S = material.second_piola_kirchhoff(C);
          const Tensor<2, dim>          P = F * Tensor<2, dim>(S);
          const double                  JxW = values.JxW(q);
          for (unsigned int l = 0; l < n_basis; ++l)
            {
              const Tensor<1, dim> &g  = values.shape_grad(l, q);
              const Tensor<1, dim>  Pg = P * g;
              for (unsigned int c = 0; c < dim; ++c)
                residual[values.local_dof(l, c)] += Pg[c] * JxW;
            }
          if (tangent == nullptr)
            continue;
          // K(lc, md) = dE_lc : D : dE_md + delta_cd grad N_l . S grad N_m
          // with dE_md = sym(F^T (e_d x grad N_m)): for symmetric
          // S_lc = D : dE_lc, S_lc : dE_md = (F S_lc grad N_m)_d, so one
          // 3 x 3 product A_lc = F S_lc per local unknown gives its row
          // for every m at dim^2 multiply-adds per basis function.
          const SymmetricTensor<4, dim> D = material.tangent(C);
          for (unsigned int l = 0; l < n_basis; ++l)
            {
              const Tensor<1, dim> &g  = values.shape_grad(l, q);
              const Tensor<1, dim>  Sg = S * g;
              for (unsigned int c = 0; c < dim; ++c)
                {
                  // (F^T (e_c x g))_IJ = F_cI g_J, symmetrised.
                  SymmetricTensor<2, dim> dE;
                  for (unsigned int I = 0; I < dim; ++I)
                    for (unsigned int K = I; K < dim; ++K)
                      dE[I][K] = 0.5 * (F[c][I] * g[K] + F[c][K] * g[I]);
                  const Tensor<2, dim> A = F * Tensor<2, dim>(D * dE) * JxW;
                  const unsigned int   i = values.local_dof(l, c);
                  for (unsigned int m = 0; m < n_basis; ++m)
                    {
                      const Tensor<1, dim> &gm = values.shape_grad(m, q);
                      const Tensor<1, dim>  Ag = A * gm;
                      for (unsigned int d = 0; d < dim; ++d)
                        (*tangent)(i, values.local_dof(m, d)) +=
                          Ag[d] + (c == d ? (Sg * gm) * JxW : 0.);
                    }
                }
            }
        }
      return min_J;
    }

    /**
     * @brief A follower pressure @p p on the face @p face_values
     * (reinitialised on a cell face; shape gradients, reference normals,
     * JxW): the load -p n da on the current surface, as
     * -p J F^-T N dA on the reference one (Nanson), subtracted from
     * @p residual (the residual is f_int - f_ext) and, with @p tangent
     * (not nullptr), its derivative (the load stiffness, not symmetric)
     * added to it:
     * d(J F^-T N)[e_d x g] = J ((F^-1 e_d . g) F^-T N - (F^-T N)_d F^-T g).
     */
    template <int dim, typename FaceValues>
    void
    add_face_follower_pressure(const FaceValues          &face_values,
                               const std::vector<double> &local_u,
                               const double               p,
                               Vector<double>            &residual,
                               FullMatrix<double>        *tangent)
    {
      const unsigned int n_basis = face_values.n_basis();
      for (unsigned int q = 0; q < face_values.n_quadrature_points(); ++q)
        {
          const Tensor<2, dim> F = deformation_gradient<dim>(
            displacement_gradient<dim>(face_values, local_u, q));
          const double         J     = determinant(F);
          const Tensor<2, dim> F_inv = invert(F);
          const Tensor<1, dim> n0 =
            transpose(F_inv) * face_values.normal_vector(q);
          const double pJxW = p * J * face_values.JxW(q);
          for (unsigned int l = 0; l < n_basis; ++l)
            {
              const double N = face_values.shape_value(l, q);
              for (unsigned int c = 0; c < dim; ++c)
                residual[face_values.local_dof(l, c)] += pJxW * N * n0[c];
            }
          if (tangent == nullptr)
            continue;
          for (unsigned int m = 0; m < n_basis; ++m)
            {
              const Tensor<1, dim> &g     = face_values.shape_grad(m, q);
              const Tensor<1, dim>  FTg   = transpose(F_inv) * g;
              const Tensor<1, dim>  Finvg = g * F_inv; // (F^-1 e_d . g)_d
              for (unsigned int d = 0; d < dim; ++d)
                for (unsigned int l = 0; l < n_basis; ++l)
                  {
                    const double N = face_values.shape_value(l, q);
                    for (unsigned int c = 0; c < dim; ++c)
                      (*tangent)(face_values.local_dof(l, c),
                                 face_values.local_dof(m, d)) +=
                        pJxW * N * (Finvg[d] * n0[c] - n0[d] * FTg[c]);
                  }
            }
        }
    }



    /**
     * @brief The cell's stored energy int W(C) dX at @p local_u (infinite
     * where det F <= 0).
     */
    template <int dim, typename Values>
    double
    cell_energy(const Values                    &values,
                const std::vector<double>       &local_u,
                const HyperelasticMaterial<dim> &material)
    {
      double energy = 0.;
      for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
        {
          const Tensor<2, dim> F = deformation_gradient<dim>(
            displacement_gradient<dim>(values, local_u, q));
          if (!(determinant(F) > 0.))
            return std::numeric_limits<double>::infinity();
          energy += material.energy(right_cauchy_green(F)) * values.JxW(q);
        }
      return energy;
    }



    /**
     * @brief The internal force f_int(u) of the cells [@p begin, @p end)
     * added to @p force and, with @p tangent (not nullptr; its pattern must
     * hold the cell couplings), its tangent added to it, on all cores
     * (blocks of cells computed in parallel, added in the cells' order, so
     * that the result does not depend on the threads). Returns the smallest
     * det F at the quadrature points.
     *
     * @param cell_values Prototype of the cell evaluator (gradients, JxW),
     *   copied per thread.
     */
    template <int dim, typename Iterator, typename CellValues>
    double
    assemble_internal_force(const Iterator                         &begin,
                            const std::enable_if_t<true, Iterator> &end,
                            const CellValues                       &cell_values,
                            const HyperelasticMaterial<dim>        &material,
                            const Vector<double>                   &u,
                            Vector<double>                         &force,
                            SparseMatrix<double>                   *tangent)
    {
      struct Scratch
      {
        CellValues          cell;
        std::vector<double> local_u;
      };
      struct Copy
      {
        FullMatrix<double>                   matrix;
        Vector<double>                       force;
        std::vector<types::global_dof_index> dofs;
        double                               min_J = 0.;
      };
      std::vector<Iterator> cells;
      for (Iterator cell = begin; cell != end; ++cell)
        cells.push_back(cell);
      const unsigned int block = 256;
      std::vector<Copy>  copies(std::min<std::size_t>(block, cells.size()));
      Threads::ThreadLocalStorage<std::unique_ptr<Scratch>> scratch;
      double min_J = std::numeric_limits<double>::max();
      for (std::size_t first = 0; first < cells.size(); first += block)
        {
          const std::size_t last = std::min(cells.size(), first + block);
          parallel::apply_to_subranges(
            first,
            last,
            [&](const std::size_t from, const std::size_t to) {
              std::unique_ptr<Scratch> &mine = scratch.get();
              if (!mine)
                mine = std::make_unique<Scratch>(Scratch{cell_values, {}});
              for (std::size_t c = from; c < to; ++c)
                {
                  Copy &copy = copies[c - first];
                  mine->cell.reinit(cells[c]);
                  mine->cell.get_dof_indices(copy.dofs);
                  mine->local_u.resize(copy.dofs.size());
                  for (unsigned int i = 0; i < copy.dofs.size(); ++i)
                    mine->local_u[i] = u[copy.dofs[i]];
                  copy.force.reinit(copy.dofs.size());
                  if (tangent != nullptr)
                    copy.matrix.reinit(copy.dofs.size(), copy.dofs.size());
                  copy.min_J = add_cell_internal_force<dim>(mine->cell,
                                                            mine->local_u,
                                                            material,
                                                            copy.force,
                                                            tangent != nullptr ?
                                                              &copy.matrix :
                                                              nullptr);
                }
            },
            8);
          for (std::size_t c = first; c < last; ++c)
            {
              const Copy &copy = copies[c - first];
              min_J            = std::min(min_J, copy.min_J);
              if (tangent != nullptr)
                tangent->add(copy.dofs, copy.matrix);
              for (unsigned int i = 0; i < copy.dofs.size(); ++i)
                force[copy.dofs[i]] += copy.force[i];
            }
        }
      return min_J;
    }


    /**
     * @brief The follower pressures @p pressures (a face's boundary id and
     * its pressure p each) on the boundary faces of the cells [@p begin,
     * @p end) at the displacement @p u: each face's load -p n da on the
     * current surface added to the residual @p residual (f_int - f_ext, so
     * + p J F^-T N dA) and, with @p tangent (not nullptr), its derivative
     * to it (add_face_follower_pressure()). Serial: the loaded faces are a
     * surface's few.
     *
     * @param face_values Face evaluator with values, gradients, normal
     *   vectors and JxW, reinitialised here on each loaded face.
     */
    template <int dim, typename Iterator, typename FaceValues>
    void
    assemble_follower_pressure(
      const Iterator                                           &begin,
      const std::enable_if_t<true, Iterator>                   &end,
      FaceValues                                               &face_values,
      const std::vector<std::pair<types::boundary_id, double>> &pressures,
      const Vector<double>                                     &u,
      Vector<double>                                           &residual,
      SparseMatrix<double>                                     *tangent)
    {
      std::vector<types::global_dof_index> dofs;
      std::vector<double>                  local_u;
      Vector<double>                       local_residual;
      FullMatrix<double>                   local_tangent;
      for (Iterator cell = begin; cell != end; ++cell)
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            for (const auto &[id, p] : pressures)
              if (id == cell->face(f)->boundary_id() && p != 0.)
                {
                  face_values.reinit(cell, f);
                  face_values.get_dof_indices(dofs);
                  local_u.resize(dofs.size());
                  for (unsigned int i = 0; i < dofs.size(); ++i)
                    local_u[i] = u[dofs[i]];
                  local_residual.reinit(dofs.size());
                  if (tangent != nullptr)
                    local_tangent.reinit(dofs.size(), dofs.size());
                  add_face_follower_pressure<dim>(face_values,
                                                  local_u,
                                                  p,
                                                  local_residual,
                                                  tangent != nullptr ?
                                                    &local_tangent :
                                                    nullptr);
                  for (unsigned int i = 0; i < dofs.size(); ++i)
                    residual[dofs[i]] += local_residual[i];
                  if (tangent != nullptr)
                    tangent->add(dofs, local_tangent);
                }
    }
  } // namespace elasticity
} // namespace igabde

#endif
