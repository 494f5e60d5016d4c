#ifndef igabde_nurbs_nurbs_values_h
#define igabde_nurbs_nurbs_values_h

#include <igabde/nurbs/nurbs_patch.h>

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/full_matrix.h>

#include <deal.II/grid/tria.h>

#include <deal.II/fe/fe_update_flags.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace igabde
{
  namespace nurbs
  {
    using namespace dealii;

    /**
     * @brief FEValues for a NURBS patch on one knot span (one cell of the
     * parametric Triangulation): the rational basis R_A and its physical
     * gradients, the exact map x(xi), its Jacobian, JxW, and the
     * control-point unknowns dim A + c, at a fixed set of reference points.
     *
     * The span is found once in reinit(cell); the Bernstein values at the
     * reference points are computed once in the constructor, so that a cell
     * costs the Bézier extraction, the NURBS quotient rule and one Jacobian
     * inversion per point. This is the evaluator of elasticity/assembly.h for
     * IGA; the patch must outlive it.
     *
     * Cells: reference points in [0, 1]^dim, JxW = |det J| h_1..h_dim w_q.
     * Faces (the face constructor, reinit(cell, face)): points on the cell
     * face, JxW = |cof(J) e_d| prod_{e != d} h_e w_q, outward unit normals
     * (zero where the face degenerates to a point).
     */
    template <int dim>
    class NurbsValues
    {
    public:
      /// Cells of the parametric mesh.
      using cell_iterator = typename Triangulation<dim>::active_cell_iterator;

      /**
       * @brief Evaluates on cells at the points of @p quadrature (on
       * [0, 1]^dim). @p flags: update_values, update_gradients (physical,
       * needs an invertible J: at singular points the gradients are zero
       * and regular() is false), update_quadrature_points,
       * update_JxW_values, update_jacobians.
       */
      NurbsValues(const NurbsPatch<dim> &patch,
                  const Quadrature<dim> &quadrature,
                  const UpdateFlags      flags);

      /**
       * @brief Evaluates on cell faces at the points of @p face_quadrature
       * (on [0, 1]^(dim-1)); reinit(cell, face).
       */
      NurbsValues(const NurbsPatch<dim>     &patch,
                  const Quadrature<dim - 1> &face_quadrature,
                  const UpdateFlags          flags);

      /**
       * @brief Throws, naming @p owner, when reinit(cell) meets a Jacobian
       * whose sign is not the patch's orientation (a folded map).
       */
      void
      check_orientation(const std::string &owner);

      /**
       * @brief Numbers the unknowns by @p control_point_numbers (the glued
       * index of each control point of a multi-patch body, which must
       * outlive this object): get_dof_indices() gives dim n[A] + c instead
       * of dim A + c. control_points() stays the patch's own numbering.
       */
      void
      number_unknowns_by(
        const std::vector<unsigned int> &control_point_numbers);

      /// Evaluates on the knot span of @p cell.
      void
      reinit(const cell_iterator &cell);

      /// Evaluates on face @p face of the knot span of @p cell.
      void
      reinit(const cell_iterator &cell, const unsigned int face);

      /// Evaluates on the knot span @p span (face rule: on @p face).
      void
      reinit(const std::array<unsigned int, dim> &span,
             const unsigned int face = numbers::invalid_unsigned_int);

      /// Quadrature (reference) points.
      unsigned int
      n_quadrature_points() const
      {
        return n_q;
      }

      /// Basis functions with support on the span: prod (p_d + 1).
      unsigned int
      n_basis() const
      {
        return n_local;
      }

      /// Vector unknowns per cell.
      unsigned int
      dofs_per_cell() const
      {
        return dim * n_local;
      }

      /// Cell-local index of basis function @p l times e_c.
      unsigned int
      local_dof(const unsigned int l, const unsigned int c) const
      {
        return dim * l + c;
      }

      /// Global unknowns dim A + c in cell-local order.
      void
      get_dof_indices(std::vector<types::global_dof_index> &dofs) const;

      /// Control point of each local basis function (lexicographic,
      /// direction 0 fastest).
      const std::vector<unsigned int> &
      control_points() const
      {
        return local_control_points;
      }

      /// R_l(xi_q).
      double
      shape_value(const unsigned int l, const unsigned int q) const
      {
        return values[q * n_local + l];
      }

      /// grad_x R_l(xi_q) = J^-T grad_xi R_l.
      const Tensor<1, dim> &
      shape_grad(const unsigned int l, const unsigned int q) const
      {
        return gradients[q * n_local + l];
      }

      /// grad_xi R_l(xi_q).
      const Tensor<1, dim> &
      parametric_shape_grad(const unsigned int l, const unsigned int q) const
      {
        return parametric_gradients[q * n_local + l];
      }

      /// Weight times volume (cells) or surface (faces) element.
      double
      JxW(const unsigned int q) const
      {
        return jxw[q];
      }

      /// x(xi_q).
      const Point<dim> &
      quadrature_point(const unsigned int q) const
      {
        return points[q];
      }

      /// xi_q.
      const Point<dim> &
      parametric_point(const unsigned int q) const
      {
        return parametric_points[q];
      }

      /// dx/dxi at xi_q.
      const Tensor<2, dim> &
      jacobian(const unsigned int q) const
      {
        return jacobians[q];
      }

      /// Whether J is invertible at xi_q (gradients defined).
      bool
      regular(const unsigned int q) const
      {
        return is_regular[q] != 0;
      }

      /// Outward unit normal (faces).
      const Tensor<1, dim> &
      normal_vector(const unsigned int q) const
      {
        return normals[q];
      }

      /// The knot span of the last reinit.
      const std::array<unsigned int, dim> &
      span() const
      {
        return current_span;
      }

    private:
      /// What the patch and the reference points give once.
      struct Data
      {
        std::array<std::vector<FullMatrix<double>>, dim> extraction;
        std::array<std::vector<unsigned int>, dim>       span_knot_index;
        std::array<std::vector<double>, dim>             breaks;
        /// Reference points and weights per point set (one for cells,
        /// 2 dim for faces).
        std::vector<std::vector<Point<dim>>> reference;
        std::vector<std::vector<double>>     weights;
        /// Bernstein values and derivatives: [set][q][d][j].
        std::vector<std::vector<std::array<std::vector<double>, dim>>> B, dB;
      };

      void
      initialize(const std::vector<std::vector<Point<dim>>> &sets,
                 const std::vector<double>                  &weights);

      const NurbsPatch<dim>      *patch;
      std::shared_ptr<const Data> data;
      UpdateFlags                 flags;
      bool                        face_rule;
      std::string                 orientation_owner;
      double                      orientation = 1.;

      unsigned int                  n_q     = 0;
      unsigned int                  n_local = 0;
      std::array<unsigned int, dim> n_1d;
      std::array<unsigned int, dim> current_span;
      std::vector<unsigned int>     local_control_points;
      /// The glued numbering (number_unknowns_by()); null: the patch's own.
      const std::vector<unsigned int> *numbering = nullptr;
      std::vector<double>              values;
      std::vector<Tensor<1, dim>>      parametric_gradients;
      std::vector<Tensor<1, dim>>      gradients;
      std::vector<Point<dim>>          points;
      std::vector<Point<dim>>          parametric_points;
      std::vector<Tensor<2, dim>>      jacobians;
      std::vector<double>              jxw;
      std::vector<Tensor<1, dim>>      normals;
      std::vector<char>                is_regular;
      /// Per-point scratch: 1D B-splines and derivatives per direction.
      std::array<std::vector<double>, dim> N, dN;
    };
  } // namespace nurbs
} // namespace igabde

#endif
