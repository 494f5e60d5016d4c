#ifndef igabde_elasticity_fe_values_evaluator_h
#define igabde_elasticity_fe_values_evaluator_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_values.h>

#include <type_traits>
#include <utility>
#include <vector>

namespace igabde
{
  namespace elasticity
  {
    using namespace dealii;

    /**
     * @brief The evaluator interface of elasticity/assembly.h on deal.II's
     * FEValues (or FEFaceValues) of a vector element FESystem(FE, dim) with
     * one scalar base element: basis function l is the scalar base shape
     * function l, and (l, c) is the system shape function of component c.
     */
    template <int dim, typename FEValuesType = FEValues<dim>>
    class FEValuesEvaluator
    {
    public:
      /// The quadrature type of @p FEValuesType (cell or face rule).
      using QuadratureType = std::decay_t<
        decltype(std::declval<const FEValuesType &>().get_quadrature())>;

      /**
       * @brief FEValuesType(mapping, fe, quadrature, flags).
       */
      FEValuesEvaluator(const Mapping<dim>       &mapping,
                        const FiniteElement<dim> &fe,
                        const QuadratureType     &quadrature,
                        const UpdateFlags         flags)
        : fe_values(mapping, fe, quadrature, flags)
      {
        const unsigned int n_basis = fe.base_element(0).n_dofs_per_cell();
        Assert(fe.n_base_elements() == 1 &&
                 fe.element_multiplicity(0) == static_cast<unsigned int>(dim),
               ExcMessage("FEValuesEvaluator needs FESystem(FE, dim)."));
        system_index.resize(dim * n_basis);
        for (unsigned int l = 0; l < n_basis; ++l)
          for (unsigned int c = 0; c < dim; ++c)
            system_index[dim * l + c] = fe.component_to_system_index(c, l);
      }

      /// A new FEValuesType with the same mapping, element, rule and flags.
      FEValuesEvaluator(const FEValuesEvaluator &other)
        : fe_values(other.fe_values.get_mapping(),
                    other.fe_values.get_fe(),
                    other.fe_values.get_quadrature(),
                    other.fe_values.get_update_flags())
        , system_index(other.system_index)
      {}

      /// Reinitialises on @p cell (and a face number for FEFaceValues).
      template <typename... FaceNumber>
      void
      reinit(const typename DoFHandler<dim>::active_cell_iterator &cell,
             const FaceNumber... face)
      {
        fe_values.reinit(cell, face...);
        dof_cell = cell;
      }

      /// Quadrature points.
      unsigned int
      n_quadrature_points() const
      {
        return fe_values.n_quadrature_points;
      }

      /// Scalar basis functions per cell.
      unsigned int
      n_basis() const
      {
        return system_index.size() / dim;
      }

      /// Vector unknowns per cell.
      unsigned int
      dofs_per_cell() const
      {
        return system_index.size();
      }

      /// Cell-local index of basis function @p l times e_c.
      unsigned int
      local_dof(const unsigned int l, const unsigned int c) const
      {
        return system_index[dim * l + c];
      }

      /// Global unknowns in cell-local order.
      void
      get_dof_indices(std::vector<types::global_dof_index> &dofs) const
      {
        dofs.resize(system_index.size());
        dof_cell->get_dof_indices(dofs);
      }

      /// N_l(x_q).
      double
      shape_value(const unsigned int l, const unsigned int q) const
      {
        return fe_values.shape_value(system_index[dim * l], q);
      }

      /// grad N_l(x_q) (physical).
      const Tensor<1, dim> &
      shape_grad(const unsigned int l, const unsigned int q) const
      {
        return fe_values.shape_grad(system_index[dim * l], q);
      }

      /// Quadrature weight times the volume (surface) element.
      double
      JxW(const unsigned int q) const
      {
        return fe_values.JxW(q);
      }

      /// Physical quadrature point.
      const Point<dim> &
      quadrature_point(const unsigned int q) const
      {
        return fe_values.quadrature_point(q);
      }

      /// Outward unit normal (faces only).
      const Tensor<1, dim> &
      normal_vector(const unsigned int q) const
      {
        return fe_values.normal_vector(q);
      }

      /// The wrapped deal.II object.
      const FEValuesType &
      get_fe_values() const
      {
        return fe_values;
      }

    private:
      FEValuesType                                   fe_values;
      std::vector<unsigned int>                      system_index;
      typename DoFHandler<dim>::active_cell_iterator dof_cell;
    };
  } // namespace elasticity
} // namespace igabde

#endif
