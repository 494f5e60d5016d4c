#ifndef igabde_elasticity_assembly_h
#define igabde_elasticity_assembly_h

#include <igabde/elasticity/body_force.h>
#include <igabde/elasticity/error_norms.h>
#include <igabde/elasticity/material.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/thread_local_storage.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <type_traits>
#include <vector>

/**
 * @file
 * Linear elasticity written once for both discretisations, against a small
 * evaluator interface that deal.II's FEValues (through
 * elasticity::FEValuesEvaluator) and the NURBS knot-span evaluator
 * (nurbs::NurbsValues) provide:
 *
 * - `reinit(cell)` (faces: `reinit(cell, face_no)`);
 * - `n_quadrature_points()`, `n_basis()` (scalar basis functions of the
 *   cell), `dofs_per_cell()` (= dim n_basis());
 * - `local_dof(l, c)`: the cell-local index of basis function l times e_c;
 * - `get_dof_indices(v)`: the global unknowns in cell-local order;
 * - `shape_value(l, q)`, `shape_grad(l, q)` (physical gradient),
 *   `JxW(q)`, `quadrature_point(q)`, and on faces `normal_vector(q)`.
 *
 * Templates (not virtual calls) keep the inner loops as fast as the
 * hand-written ones they replace.
 */

namespace igabde
{
  namespace elasticity
  {
    using namespace dealii;

    /**
     * @brief Lamé's lambda and mu of the isotropic @p material, read off its
     * stiffness (plane stress has the reduced lambda).
     */
    template <int dim>
    std::pair<double, double>
    lame_parameters(const IsotropicMaterial<dim> &material)
    {
      const SymmetricTensor<4, dim> C = material.stiffness();
      return {C[0][0][1][1], C[0][1][0][1]};
    }



    /**
     * @brief Symmetric gradient of the vector function N e_c with gradient
     * @p grad of N, scaled by @p coefficient and added to @p eps.
     */
    template <int dim>
    inline void
    add_basis_strain(const double             coefficient,
                     const Tensor<1, dim>    &grad,
                     const unsigned int       c,
                     SymmetricTensor<2, dim> &eps)
    {
      for (unsigned int j = 0; j < dim; ++j)
        eps[c][j] += coefficient * (c == j ? grad[j] : 0.5 * grad[j]);
    }



    /**
     * @brief Displacement u_h(x_q) from the cell coefficients @p local_u
     * (cell-local order).
     */
    template <int dim, typename Values>
    Tensor<1, dim>
    displacement(const Values              &values,
                 const std::vector<double> &local_u,
                 const unsigned int         q)
    {
      Tensor<1, dim> u;
      for (unsigned int l = 0; l < values.n_basis(); ++l)
        for (unsigned int c = 0; c < dim; ++c)
          u[c] += values.shape_value(l, q) * local_u[values.local_dof(l, c)];
      return u;
    }



    /**
     * @brief Strain eps(u_h)(x_q) from the cell coefficients @p local_u.
     */
    template <int dim, typename Values>
    SymmetricTensor<2, dim>
    strain(const Values              &values,
           const std::vector<double> &local_u,
           const unsigned int         q)
    {
      SymmetricTensor<2, dim> eps;
      for (unsigned int l = 0; l < values.n_basis(); ++l)
        for (unsigned int c = 0; c < dim; ++c)
          add_basis_strain<dim>(local_u[values.local_dof(l, c)],
                                values.shape_grad(l, q),
                                c,
                                eps);
      return eps;
    }



    /**
     * @brief The cell's coefficients of @p u in cell-local order.
     */
    template <typename Values>
    void
    get_local_values(const Values         &values,
                     const Vector<double> &u,
                     std::vector<double>  &local_u)
    {
      std::vector<types::global_dof_index> dofs;
      values.get_dof_indices(dofs);
      local_u.resize(dofs.size());
      for (unsigned int i = 0; i < dofs.size(); ++i)
        local_u[i] = u[dofs[i]];
    }



    /**
     * @brief Scratch space of add_cell_stiffness(), kept per thread so that
     * the cell loop allocates nothing.
     */
    struct CellStiffnessScratch
    {
      /// Row c n + a, column q: JxW_q d_c N_a(x_q).
      Eigen::MatrixXd weighted_gradients;
      /// Row c n + a, column q: d_c N_a(x_q).
      Eigen::MatrixXd gradients;
      /// Block (c, d) holds A_cd(a, b) = sum_q JxW_q d_c N_a d_d N_b.
      Eigen::MatrixXd products;
    };



    /**
     * @brief Adds the stiffness int eps(v) : C : eps(u) dx of the cell to
     * @p matrix (cell-local order), for the isotropic C = lambda I x I + 2 mu
     * I^s: K(ac, bd) = lambda g_a[c] g_b[d] + mu (delta_cd g_a . g_b +
     * g_a[d] g_b[c]).
     *
     * Written as one matrix product over the quadrature points: with
     * A_cd(a, b) = sum_q JxW_q g_a[c] g_b[d] (all dim^2 blocks from one
     * (dim n) x n_q times n_q x (dim n) product, BLAS-3 through Eigen),
     * K(ac, bd) = lambda A_cd(a, b) + mu (A_dc(a, b) + delta_cd
     * sum_e A_ee(a, b)). The same flops as a loop over pairs of basis
     * functions, but vectorised: less CPU time, as on the 2 048 quadratic
     * NURBS hexahedra (27 basis functions, 27 points) of B2 at 8x16x8 per
     * beam (doc/performance.md).
     */
    template <int dim, typename Values>
    void
    add_cell_stiffness(const Values         &values,
                       const double          lambda,
                       const double          mu,
                       FullMatrix<double>   &matrix,
                       CellStiffnessScratch &scratch)
    {
      const unsigned int n   = values.n_basis();
      const unsigned int n_q = values.n_quadrature_points();
      scratch.weighted_gradients.resize(dim * n, n_q);
      scratch.gradients.resize(dim * n, n_q);
      for (unsigned int q = 0; q < n_q; ++q)
        {
          const double JxW = values.JxW(q);
          for (unsigned int a = 0; a < n; ++a)
            {
              const Tensor<1, dim> g = values.shape_grad(a, q);
              for (unsigned int c = 0; c < dim; ++c)
                {
                  scratch.gradients(c * n + a, q)          = g[c];
                  scratch.weighted_gradients(c * n + a, q) = JxW * g[c];
                }
            }
        }
      scratch.products.noalias() =
        scratch.weighted_gradients * scratch.gradients.transpose();
      const Eigen::MatrixXd &A = scratch.products;

      std::vector<unsigned int> local(dim * n);
      for (unsigned int a = 0; a < n; ++a)
        for (unsigned int c = 0; c < dim; ++c)
          local[dim * a + c] = values.local_dof(a, c);
      for (unsigned int b = 0; b < n; ++b)
        for (unsigned int a = 0; a < n; ++a)
          {
            double trace = 0.;
            for (unsigned int e = 0; e < dim; ++e)
              trace += A(e * n + a, e * n + b);
            for (unsigned int c = 0; c < dim; ++c)
              for (unsigned int d = 0; d < dim; ++d)
                matrix(local[dim * a + c], local[dim * b + d]) +=
                  lambda * A(c * n + a, d * n + b) +
                  mu * (A(d * n + a, c * n + b) + (c == d ? trace : 0.));
          }
    }



    /**
     * @brief Adds the load int v . f dx of the body force @p f (N/m^3).
     */
    template <int dim, typename Values>
    void
    add_body_force(const Values         &values,
                   const Tensor<1, dim> &f,
                   Vector<double>       &rhs)
    {
      for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
        for (unsigned int l = 0; l < values.n_basis(); ++l)
          for (unsigned int c = 0; c < dim; ++c)
            rhs[values.local_dof(l, c)] +=
              values.shape_value(l, q) * f[c] * values.JxW(q);
    }



    /**
     * @brief Adds the load int v . f(x) dx of the body force field @p f
     * (the values need update_quadrature_points).
     */
    template <int dim, typename Values>
    void
    add_body_force(const Values &values,
                   const std::function<Tensor<1, dim>(const Point<dim> &)> &f,
                   Vector<double>                                          &rhs)
    {
      for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
        {
          const Tensor<1, dim> fq = f(values.quadrature_point(q));
          for (unsigned int l = 0; l < values.n_basis(); ++l)
            for (unsigned int c = 0; c < dim; ++c)
              rhs[values.local_dof(l, c)] +=
                values.shape_value(l, q) * fq[c] * values.JxW(q);
        }
    }



    /**
     * @brief Adds the load int v . t(x, n) dGamma on the face @p face_values
     * was reinitialised on; points with a zero surface measure (a collapsed
     * NURBS edge) are skipped.
     */
    template <int dim, typename FaceValues, typename TractionFunction>
    void
    add_traction(const FaceValues       &face_values,
                 const TractionFunction &traction,
                 Vector<double>         &rhs)
    {
      for (unsigned int q = 0; q < face_values.n_quadrature_points(); ++q)
        {
          const double dA = face_values.JxW(q);
          if (dA == 0.)
            continue;
          const Tensor<1, dim> t = traction(face_values.quadrature_point(q),
                                            face_values.normal_vector(q));
          for (unsigned int l = 0; l < face_values.n_basis(); ++l)
            for (unsigned int c = 0; c < dim; ++c)
              rhs[face_values.local_dof(l, c)] +=
                face_values.shape_value(l, q) * t[c] * dA;
        }
    }



    /**
     * @brief Assembles the stiffness and the loads (body force, tractions)
     * at load factor 1 over the cells [@p begin, @p end) on all cores
     * (blocks of cells computed in parallel, added in the cells' order).
     *
     * @param cell_values Prototype of the cell evaluator (values,
     *   gradients, JxW); copied per thread.
     * @param face_values Prototype of the face evaluator (values, points,
     *   normals, JxW).
     * @param tractions A range of objects with `boundary_id` and
     *   `traction(x, n)`.
     * @param matrix Receives K (its sparsity must hold the cell couplings).
     * @param rhs Receives the loads.
     * @param assembles_cell Which cells to assemble (empty: all of them):
     *   under MPI each rank of a body's group assembles its share.
     */
    template <int dim,
              typename Iterator,
              typename CellValues,
              typename FaceValues,
              typename Tractions>
    void
    assemble_system(
      const Iterator                         &begin,
      const std::enable_if_t<true, Iterator> &end,
      const CellValues                       &cell_values,
      const FaceValues                       &face_values,
      const IsotropicMaterial<dim>           &material,
      const BodyForce<dim>                   &body_force,
      const Tractions                        &tractions,
      SparseMatrix<double>                   &matrix,
      Vector<double>                         &rhs,
      const std::enable_if_t<true, std::function<bool(const Iterator &)>>
        &assembles_cell = {})
    {
      // An empty matrix asks for the loads only (the tractions of another
      // load history): no stiffness is computed.
      const bool with_matrix = !matrix.empty();
      // Named copies, not a structured binding: the assembly lambda below
      // captures them (C++17 allows no capture of a binding).
      const auto   lame           = lame_parameters(material);
      const double lambda         = lame.first;
      const double mu             = lame.second;
      const bool   has_body_force = !body_force.zero();

      struct Scratch
      {
        CellValues           cell;
        FaceValues           face;
        CellStiffnessScratch stiffness;
      };
      struct Copy
      {
        FullMatrix<double>                   matrix;
        Vector<double>                       rhs;
        std::vector<types::global_dof_index> dofs;
      };

      auto worker = [&](const Iterator &cell, Scratch &scratch, Copy &copy) {
        if (assembles_cell && !assembles_cell(cell))
          {
            copy.dofs.clear();
            copy.rhs.reinit(0);
            return;
          }
        if (!with_matrix && !has_body_force)
          {
            // Loads of tractions only: cells without a loaded face add
            // nothing.
            bool loaded = false;
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary())
                for (const auto &neumann : tractions)
                  loaded = loaded ||
                           neumann.boundary_id == cell->face(f)->boundary_id();
            if (!loaded)
              {
                copy.dofs.clear();
                copy.rhs.reinit(0);
                return;
              }
          }
        scratch.cell.reinit(cell);
        const unsigned int n_dofs = scratch.cell.dofs_per_cell();
        copy.rhs.reinit(n_dofs);
        scratch.cell.get_dof_indices(copy.dofs);
        if (with_matrix)
          {
            copy.matrix.reinit(n_dofs, n_dofs);
            add_cell_stiffness<dim>(scratch.cell,
                                    lambda,
                                    mu,
                                    copy.matrix,
                                    scratch.stiffness);
          }
        if (has_body_force && body_force.field)
          add_body_force<dim>(scratch.cell, body_force.field, copy.rhs);
        else if (has_body_force)
          add_body_force<dim>(scratch.cell, body_force.constant, copy.rhs);
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            for (const auto &neumann : tractions)
              if (neumann.boundary_id == cell->face(f)->boundary_id())
                {
                  scratch.face.reinit(cell, f);
                  add_traction<dim>(scratch.face, neumann.traction, copy.rhs);
                }
      };

      auto copier = [&](const Copy &copy) {
        if (with_matrix && !copy.dofs.empty())
          matrix.add(copy.dofs, copy.matrix);
        for (unsigned int i = 0; i < copy.dofs.size(); ++i)
          rhs[copy.dofs[i]] += copy.rhs[i];
      };

      // Blocks of cells: the cell matrices of a block in parallel (each
      // thread with its own scratch), then added in the cells' order, so
      // that K is the same to the last bit whatever the threads did.
      // WorkStream's pipeline ran the cells on one of the two threads
      // here (oneTBB 2021.8: the calling thread waited in the pipeline
      // without taking cells; B2 at 16x64x16, 16 384 cells per beam:
      // 16 376 on one thread).
      std::vector<Iterator> cells;
      for (Iterator cell = begin; cell != end; ++cell)
        cells.push_back(cell);
      const unsigned int block = 256;
      std::vector<Copy>  copies(std::min<std::size_t>(block, cells.size()));
      Threads::ThreadLocalStorage<std::unique_ptr<Scratch>> scratch;
      for (std::size_t first = 0; first < cells.size(); first += block)
        {
          const std::size_t last = std::min(cells.size(), first + block);
          parallel::apply_to_subranges(
            first,
            last,
            [&](const std::size_t from, const std::size_t to) {
              std::unique_ptr<Scratch> &mine = scratch.get();
              if (!mine)
                mine = std::make_unique<Scratch>(
                  Scratch{cell_values, face_values, {}});
              for (std::size_t c = from; c < to; ++c)
                worker(cells[c], *mine, copies[c - first]);
            },
            8);
          for (std::size_t c = first; c < last; ++c)
            copier(copies[c - first]);
        }
    }



    /**
     * @brief Relative L2 error of the displacement and relative energy
     * error sqrt(int (s - s_h) : C^-1 : (s - s_h) / int s : C^-1 : s) over
     * the cells [@p begin, @p end), with the quadrature of @p values;
     * energy_relative is NaN when @p exact has no stress.
     */
    template <int dim, typename Iterator, typename CellValues>
    ErrorNorms
    compute_error_norms(const Iterator                         &begin,
                        const std::enable_if_t<true, Iterator> &end,
                        CellValues                             &values,
                        const Vector<double>                   &u,
                        const IsotropicMaterial<dim>           &material,
                        const ExactSolution<dim>               &exact)
    {
      AssertThrow(static_cast<bool>(exact.displacement),
                  ExcMessage("compute_errors: the exact solution has no "
                             "displacement function."));
      const SymmetricTensor<4, dim> C = material.stiffness();
      const SymmetricTensor<4, dim> S = invert(C);
      const bool with_stress          = static_cast<bool>(exact.stress);

      double              e_l2 = 0., u_l2 = 0., e_en = 0., u_en = 0., vol = 0.;
      std::vector<double> local_u;
      for (Iterator cell = begin; cell != end; ++cell)
        {
          values.reinit(cell);
          get_local_values(values, u, local_u);
          for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
            {
              const double         JxW = values.JxW(q);
              const Point<dim>    &x   = values.quadrature_point(q);
              const Tensor<1, dim> uh  = displacement<dim>(values, local_u, q);
              const Tensor<1, dim> ue  = exact.displacement(x);
              e_l2 += (ue - uh).norm_square() * JxW;
              u_l2 += ue.norm_square() * JxW;
              vol += JxW;
              if (with_stress)
                {
                  const SymmetricTensor<2, dim> se = exact.stress(x);
                  const SymmetricTensor<2, dim> ds =
                    se - C * strain<dim>(values, local_u, q);
                  e_en += (ds * (S * ds)) * JxW;
                  u_en += (se * (S * se)) * JxW;
                }
            }
        }
      ErrorNorms result;
      result.l2_relative          = std::sqrt(e_l2 / std::max(u_l2, 1e-300));
      result.energy_relative      = with_stress ?
                                      std::sqrt(e_en / std::max(u_en, 1e-300)) :
                                      std::numeric_limits<double>::quiet_NaN();
      result.measure              = vol;
      result.l2_error_squared     = e_l2;
      result.l2_norm_squared      = u_l2;
      result.energy_error_squared = e_en;
      result.energy_norm_squared  = u_en;
      return result;
    }



    /**
     * @brief Area (2D) or volume (3D) of the cells [@p begin, @p end) by the
     * quadrature of @p values (JxW only).
     */
    template <typename Iterator, typename CellValues>
    double
    integrate_measure(const Iterator                         &begin,
                      const std::enable_if_t<true, Iterator> &end,
                      CellValues                             &values)
    {
      double result = 0.;
      for (Iterator cell = begin; cell != end; ++cell)
        {
          values.reinit(cell);
          for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
            result += values.JxW(q);
        }
      return result;
    }

    /**
     * @brief The largest principal strain (in magnitude) of @p u at the
     * quadrature points of the cells [@p begin, @p end) of @p values
     * (gradients and quadrature points), and where it is.
     */
    template <int dim, typename Iterator, typename CellValues>
    std::pair<double, Point<dim>>
    largest_strain(const Iterator                         &begin,
                   const std::enable_if_t<true, Iterator> &end,
                   CellValues                             &values,
                   const Vector<double>                   &u)
    {
      std::pair<double, Point<dim>> result(0., Point<dim>());
      std::vector<double>           local_u;
      for (Iterator cell = begin; cell != end; ++cell)
        {
          values.reinit(cell);
          get_local_values(values, u, local_u);
          for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
            for (const double e : eigenvalues(strain<dim>(values, local_u, q)))
              if (std::abs(e) > result.first)
                result = {std::abs(e), values.quadrature_point(q)};
        }
      return result;
    }
  } // namespace elasticity
} // namespace igabde

#endif
