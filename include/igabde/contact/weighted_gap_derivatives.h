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
       * The dual basis of one slave element, biorthogonal to its face
       * basis: psi_j = sum_k A_jk N_k with A = D M^{-1}, M_jk = int_e N_j
       * N_k, D = diag(int_e N_j), so that int_e psi_j N_k = delta_jk D_jj;
       * on the whole element with its Gauss rule. Functions of the cell
       * that vanish on the face (FE_Q) have no share: an identity row
       * keeps M regular and D = 0 drops them.
       */
      template <int dim>
      struct ElementDualBasis
      {
        /// Numbers the functions that do not vanish on the element, by
        /// their keys (first components' unknowns).
        std::map<types::global_dof_index, unsigned int> local;
        /// A = D M^{-1}, and M^{-1}.
        Eigen::MatrixXd A, M_inverse;
        /// The functions without a share on the face.
        std::vector<bool> no_share;
        /// The rule's points and their weights in face coordinates.
        std::vector<discretization::FacePoint<dim>> points;
        std::vector<double>                         weights;
      };

      /// The dual basis of the slave element [@p lo, @p hi] of
      /// @p slave_face, integrated with @p rule in each face direction.
      template <int dim>
      ElementDualBasis<dim>
      element_dual_basis(const discretization::Body<dim> &slave_body,
                         const types::boundary_id         slave_face,
                         const Point<dim - 1>            &lo,
                         const Point<dim - 1>            &hi,
                         const QGauss<1>                 &rule);

      /**
       * Adds the derivatives of the integrals that the samples @p samples
       * of a slave element give each basis function living there, to
       * @p derivatives (by the function's key), with the weights of
       * WeightedGapPairing: N_j, or where @p dual is given the element's
       * dual basis psi_j. The basis derivatives are the face points' own
       * (FacePoint::gradients, Body::face_second_derivatives()); an
       * obstacle's closest point's derivatives by the slave point are
       * central differences.
       */
      template <int dim>
      void
      add_element_derivatives(const MasterSide<dim>                 &master,
                              const std::vector<ElementSample<dim>> &samples,
                              const ElementDualBasis<dim>           *dual,
                              std::map<types::global_dof_index,
                                       IntegralDerivatives<dim>> &derivatives);

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
