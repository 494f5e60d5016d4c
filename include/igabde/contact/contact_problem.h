#ifndef igabde_contact_contact_problem_h
#define igabde_contact_contact_problem_h

#include <igabde/contact/coupled_operator.h>

#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief The condensed ("local", in FCLIB's words) point-pair contact
     * problem u = W p + q + G alpha, with Coulomb friction per pair.
     *
     * Ordering: the unknowns of contact i occupy the rows
     * [i*n_components, (i+1)*n_components) of p, u, W and q, the normal
     * component first:
     *  - n_components = 1: frictionless, normal only;
     *  - n_components = 2: 2D friction, [n, t];
     *  - n_components = 3: 3D friction, [n, a, b].
     *
     * Sign conventions (method.md §3): u_n is the total relative normal
     * displacement, gap included, u_n >= 0 means open; the tangential
     * components of u are the slip increments of the load step; p_n > 0 is
     * compression; at slip p_t opposes u_t.
     *
     * Floating bodies (method.md "Bodies held only through contact"): the
     * optional G (n_rows() x n_alpha) adds the rigid-mode amplitudes alpha
     * to the unknowns, u = W p + q + G alpha, together with the equilibrium
     * rows G^T p = b. Leave G and b empty (size 0) when every body is held.
     *
     * Units: W is a flexibility (displacement per force), q and u are
     * displacements, p and b are forces, alpha has the units of the rigid
     * modes in G.
     */
    struct ContactProblem
    {
      /** @brief Number of contact pairs. */
      unsigned int n_contacts = 0;

      /** @brief Components per pair: 1 (frictionless), 2 (2D) or 3 (3D). */
      unsigned int n_components = 3;

      /** @brief Flexibility matrix, n_rows() x n_rows(), in local frames. */
      Eigen::MatrixXd W;

      /** @brief Relative displacement with zero contact force, n_rows(). */
      Eigen::VectorXd q;

      /** @brief Friction coefficient per pair (ignored if frictionless). */
      std::vector<double> mu;

      /** @brief Rigid-mode matrix of floating bodies, n_rows() x n_alpha. */
      Eigen::MatrixXd G;

      /** @brief Right-hand side of the equilibrium rows G^T p = b. */
      Eigen::VectorXd b;

      /**
       * @brief The uncondensed system (full path), or null. With it W may
       * be empty (0 x 0): the full-system solvers never form W, and u is
       * C w + G alpha + q with w the coupled displacement unknowns.
       */
      std::shared_ptr<CoupledOperator> coupled;

      /**
       * @brief Warm start of the coupled displacement unknowns w (full
       * path; size coupled->n_dofs(), or empty for zero).
       */
      Eigen::VectorXd w0;

      /**
       * @brief Pair forces at the end of the previous load step (the base
       * of the incremental friction of the penalty methods; empty for 0).
       */
      Eigen::VectorXd p_previous;

      /** @brief Optional name (e.g. the file it was read from), for logs. */
      std::string name;

      /**
       * @brief Number of rows of W, q, p and u: n_contacts * n_components.
       */
      unsigned int
      n_rows() const;

      /** @brief Number of floating-body unknowns alpha (columns of G). */
      unsigned int
      n_alpha() const;

      /** @brief True if n_components > 1 (tangential unknowns exist). */
      bool
      has_friction() const;

      /**
       * @brief Throw (AssertThrow) if sizes, signs or values are
       * inconsistent: wrong matrix/vector sizes, n_components not in
       * {1,2,3}, mu negative or not finite, non-finite entries, G and b of
       * mismatching sizes.
       */
      void
      check_consistency() const;

      /**
       * @brief Relative displacement u = W p + q + G alpha.
       * @param p Contact forces, n_rows().
       * @param alpha Rigid-mode amplitudes, n_alpha() (may be empty when
       * n_alpha() == 0).
       */
      Eigen::VectorXd
      relative_displacement(const Eigen::VectorXd &p,
                            const Eigen::VectorXd &alpha = {}) const;

      /**
       * @brief The same problem with all friction coefficients set to @p
       * new_mu (used for the mu sweeps).
       */
      ContactProblem
      with_friction(const double new_mu) const;

      /**
       * @brief The problem with W, q scaled by @p displacement_factor and
       * b, (implicitly) p scaled by @p force_factor: W -> W * d / f,
       * q -> q * d, G -> G * d (alpha unchanged), b -> b * f. The solution
       * then scales as p -> f p, u -> d u, alpha -> alpha.
       */
      ContactProblem
      scaled(const double force_factor, const double displacement_factor) const;
    };



    /**
     * @brief Floating-body start: alpha such that the closest pair just
     * touches when p = 0.
     *
     * Moves alpha from @p alpha0 along @p direction (default -b, the
     * direction in which the load b drives the rigid modes into the
     * supports: moving along -b changes the normal gaps by -G_n b, whose
     * p-weighted sum is -|b|^2 < 0 at any solution) until the first normal
     * gap u_n = q_n + G_n alpha among the pairs that close along this
     * direction reaches zero. If a pair already penetrates, the step is
     * negative and moves the bodies back until no closing pair penetrates.
     * With every pair open the alpha columns of the Newton matrix vanish
     * (Newton would stall); with this start the touching pair is taken as
     * closed by the solver (see BNewtonSolver, "floating-body tie rule").
     *
     * @param problem The problem (must have n_alpha() > 0).
     * @param alpha0 Starting alpha (size n_alpha(), or empty for zero).
     * @param direction Search direction in alpha space (empty for -b).
     * @return alpha with min over closing pairs of u_n(p = 0) equal to 0.
     */
    Eigen::VectorXd
    touching_alpha(const ContactProblem  &problem,
                   const Eigen::VectorXd &alpha0    = {},
                   const Eigen::VectorXd &direction = {});

    /**
     * @brief The tangential pair directions held by supports on both sides
     * (full path: an empty row of C, and of G with floating bodies): no
     * displacement moves them and their force enters no body's equations,
     * so they carry p = 0 and u = 0 (the supports take whatever friction
     * would carry there). Left to the contact law, a stick piece there is a
     * zero row of the Newton matrix. All false without problem.coupled.
     */
    std::vector<bool>
    held_pair_directions(const ContactProblem &problem);

  } // namespace contact
} // namespace igabde

#endif
