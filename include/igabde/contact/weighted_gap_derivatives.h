#ifndef igabde_contact_weighted_gap_derivatives_h
#define igabde_contact_weighted_gap_derivatives_h

#include <igabde/contact/master_side.h>
#include <igabde/contact/pairing.h>

#include <deal.II/base/quadrature_lib.h>

#include <Eigen/Dense>

#include <map>
#include <vector>

// The weighted-gap pairing's derivatives by the bodies' unknowns in closed
// form (WeightedGapPairing::make_pairs_with_derivatives()): those of the
// integrands at the quadrature points of each slave element, with the
// closest point's motion on the master from its orthogonality condition.

namespace igabde
{
  namespace contact
  {
    namespace internal
    {
      /**
       * One quadrature point of a slave element and the master point it
       * faces.
       */
      template <int dim>
      struct ElementSample
      {
        discretization::FacePoint<dim> s, m;
        /// Quadrature weight in face coordinates.
        double weight = 0.;
        /// The slave point's face coordinates.
        Point<dim - 1> eta;
        /// Against a deformable master: the master face (MasterSide::parts)
        /// and the master point's face coordinates on it.
        unsigned int   part = 0;
        Point<dim - 1> xi;
      };

      /**
       * The derivatives of the integrals of one slave basis function N_j
       * (area, gap, normal and the op1 and op2 rows, by their keys) by the
       * unknowns of the two bodies (PairDerivatives::Unknown).
       */
      template <int dim>
      struct IntegralDerivatives
      {
        using Unknown = typename PairDerivatives<dim>::Unknown;
        using Map     = std::map<Unknown, double>;
        Map                                    area, gap;
        std::array<Map, dim>                   normal;
        std::map<types::global_dof_index, Map> op1, op2;

        /// Adds @p other's (a merged function's integrals).
        void
        add(const IntegralDerivatives &other);
      };

      /**
       * Adds the derivatives of the integrals that the samples @p samples
       * of the slave element [@p lo, @p hi] of @p slave_face give each
       * basis function living there, to @p derivatives (by the function's
       * key), with the weights of WeightedGapPairing: N_j, or where
       * @p dual is not empty the element's dual basis psi_j = sum_k
       * dual_jk N_k, @p local numbering the functions, integrated on the
       * whole element with @p rule. The slave point's basis derivatives
       * and the master's second derivatives are central differences in
       * face coordinates (a millionth of the element), an obstacle's
       * closest point's derivatives by the slave point central
       * differences too.
       */
      template <int dim>
      void
      add_element_derivatives(
        const discretization::Body<dim>                       &slave_body,
        const types::boundary_id                               slave_face,
        const MasterSide<dim>                                 &master,
        const Point<dim - 1>                                  &lo,
        const Point<dim - 1>                                  &hi,
        const std::vector<ElementSample<dim>>                 &samples,
        const QGauss<1>                                       &rule,
        const std::map<types::global_dof_index, unsigned int> &local,
        const Eigen::MatrixXd                                 &dual,
        std::map<types::global_dof_index, IntegralDerivatives<dim>>
          &derivatives);

      /**
       * The pair's derivatives from those of its integrals: the gap
       * @p gap / @p area, the unit normal @p normal / |@p normal| and the
       * operators' weights @p op1 / @p area, @p op2 / @p area (the entries
       * that make_operator() keeps, in their order).
       */
      template <int dim>
      PairDerivatives<dim>
      pair_derivatives(const double                                     area,
                       const double                                     gap,
                       const Tensor<1, dim>                            &normal,
                       const std::map<types::global_dof_index, double> &op1,
                       const std::map<types::global_dof_index, double> &op2,
                       const IntegralDerivatives<dim> &derivatives);
    } // namespace internal
  }   // namespace contact
} // namespace igabde

#endif
