#ifndef igabde_contact_condensation_h
#define igabde_contact_condensation_h

#include <igabde/base/choice_names.h>

#include <igabde/discretization/body.h>

#include <igabde/contact/contact_problem.h>
#include <igabde/contact/pairing.h>

#include <Eigen/Dense>

#include <ostream>
#include <utility>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief Contact/Condensation: how the condensed path forms W with the
     * direct solver: from the Schur complement on the pairs' unknowns
     * (schur), or by one solve per pair direction (columns).
     */
    enum class Condensation
    {
      schur,
      columns
    };

    /** @brief The names of Condensation as the scene writes them. */
    inline constexpr base::ChoiceNames<Condensation, 2> condensation_names = {
      {{Condensation::schur, "schur"}, {Condensation::columns, "columns"}}};

    /** @brief The name of @p condensation as the scene writes it. */
    inline std::string
    to_string(const Condensation condensation)
    {
      return base::name_of(condensation_names, condensation);
    }

    /**
     * @brief The contact problem condensed onto the pairs: the flexibility
     * F^L in the pairs' local frames, the rigid-mode columns G of floating
     * bodies and what is needed to set q and b per load step.
     */
    template <int dim>
    struct CondensedContact
    {
      /// W = F^L, G, mu; q and b are set per load step.
      ContactProblem problem;
      /// The pairs kept (those held by supports on both sides are left
      /// out).
      std::vector<ContactPair<dim>> pairs;
      /// (body, mode) of every free rigid mode.
      std::vector<std::pair<unsigned int, unsigned int>> alpha_modes;
      /// The free rigid modes' amplitudes per column of G (see
      /// RigidModeColumns::basis).
      Eigen::MatrixXd alpha_basis;
      /// r_k . f_ext of every column at load factor 1.
      Eigen::VectorXd rigid_mode_loads;
      /// r_k . f_h of every column (rows) and load history h (columns), at
      /// factor 1 (Body::history_load_vector()).
      Eigen::MatrixXd rigid_mode_history_loads;
      /// Pairs left out (both points held by supports).
      unsigned int n_dropped = 0;
      /// |W - W^T| / |W| before symmetrisation.
      double asymmetry = 0.;
    };

    /**
     * @brief The rigid modes the supports leave free, as columns of the
     * contact problem: G(m i + s, a) = +-frame_s . r_a(x_i) (Body 1 +,
     * Body 2 -), with the mode loads r_a . f_ext at factor 1. Both the
     * condensed and the full path close floating bodies with them.
     */
    struct RigidModeColumns
    {
      /// n_components * n_pairs x n_alpha.
      Eigen::MatrixXd G;
      /// (body, mode) of every free rigid mode.
      std::vector<std::pair<unsigned int, unsigned int>> alpha_modes;
      /// Amplitudes of the free rigid modes (rows, as alpha_modes) per
      /// column of G: the identity, unless a combination of modes moves no
      /// pair along a force-carrying direction and carries no load; that
      /// combination is held at zero and the columns span the others.
      Eigen::MatrixXd basis;
      /// r_a . f_ext of every column at load factor 1.
      Eigen::VectorXd loads;
      /// r_k . f_h per column (rows) and load history h (columns).
      Eigen::MatrixXd history_loads;
    };

    template <int dim>
    RigidModeColumns
    rigid_mode_columns(
      const std::vector<ContactPair<dim>>                  &pairs,
      const std::vector<const discretization::Body<dim> *> &bodies,
      const unsigned int                                    n_components,
      const std::string                                    &context,
      std::ostream                                         &log);

    /**
     * @brief The contact problem of the pairs @p keep of @p pairs (the
     * others carry no information), for either path: the kept pairs, their
     * rows of @p modes' columns as G, the modes' bookkeeping, zero q and b,
     * each pair's friction coefficient; W is the condensed path's to
     * set. Refused (bad input) when @p keep is empty: every pair is held by
     * supports on both sides.
     */
    template <int dim>
    CondensedContact<dim>
    kept_pairs_contact(const std::vector<ContactPair<dim>> &pairs,
                       const std::vector<unsigned int>     &keep,
                       const RigidModeColumns              &modes,
                       const unsigned int                   n_components,
                       const std::string                   &context);

    /**
     * @brief Condenses the bodies onto @p pairs: unit force pairs along the
     * @p n_components local directions that carry unknowns (+T_j[s] on the
     * slave body at x1_j, -T_j[s] on the master body at x2_j) give
     * F^L = T^T F^G T directly; each body gives its share on the pairs
     * that touch it through Body::flexibility() (its Schur complement on
     * its contact faces, or one solve per column), with the sign of its
     * side, so that a body that is master of one interaction and slave of
     * another couples the two. Free rigid modes become the columns of G
     * with the contact equilibrium G^T p = b. @p bodies holds the
     * deformable bodies the pairs' indices name. @p log gets one line per
     * condensed body when @p progress is set, and the rigid-mode and pair
     * counts.
     */
    template <int dim>
    CondensedContact<dim>
    condense(const std::vector<ContactPair<dim>>                  &pairs,
             const std::vector<const discretization::Body<dim> *> &bodies,
             const unsigned int                                    n_components,
             const std::string                                    &context,
             std::ostream                                         &log,
             const bool                                            progress);
  } // namespace contact
} // namespace igabde

#endif
