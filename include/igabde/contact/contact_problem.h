#ifndef igabde_contact_contact_problem_h
#define igabde_contact_contact_problem_h

#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief The data of the contact law that every path shares: per pair
     * the gap (in q), the friction coefficient and, with floating bodies,
     * the rigid-mode columns G with the equilibrium rows G^T p = b. How the
     * pair displacements u depend on the forces is not here: that is the
     * ContactOperator (the dense flexibility W of the condensed path, or the
     * coupled system of the full path).
     *
     * Ordering: the unknowns of contact i occupy the rows
     * [i*n_components, (i+1)*n_components) of p, u and q, the normal
     * component first:
     *  - n_components = 1: frictionless, normal only;
     *  - n_components = 2: 2D friction, [n, t];
     *  - n_components = 3: 3D friction, [n, a, b].
     *
     * Sign conventions (method.md §3): u_n is the total relative normal
     * displacement, gap included, u_n >= 0 means open; the tangential
     * components of u are the slip increments of the load step; p_n > 0 is
     * compression; at slip p_t opposes u_t. With floating bodies
     * (method.md "Bodies held only through contact") u also carries
     * G alpha, and the rows G^T p = b join the equations; G and b are
     * empty (size 0) when every body is held.
     *
     * Units: q and u are displacements, p and b forces, alpha has the units
     * of the rigid modes in G.
     */
    struct ContactData
    {
      /** @brief Number of contact pairs. */
      unsigned int n_contacts = 0;

      /** @brief Components per pair: 1 (frictionless), 2 (2D) or 3 (3D). */
      unsigned int n_components = 3;

      /** @brief Relative displacement with zero contact force, n_rows(). */
      Eigen::VectorXd q;

      /** @brief Friction coefficient per pair (ignored if frictionless). */
      std::vector<double> mu;

      /** @brief Rigid-mode matrix of floating bodies, n_rows() x n_alpha. */
      Eigen::MatrixXd G;

      /** @brief Right-hand side of the equilibrium rows G^T p = b. */
      Eigen::VectorXd b;

      /**
       * @brief A floor of ||q|| in the measures relative to the size of the
       * displacements (the relative natural map, the condition check), or
       * 0. At finite strain q holds the pairs' displacement from the last
       * step's state, which may be small where the bodies have moved far
       * (every pair closed and held): the contact layer then sets it from
       * the displacements of the pairs' points.
       */
      double displacement_scale = 0.;

      /** @brief Optional name (e.g. the file it was read from), for logs. */
      std::string name;

      /** @brief Number of rows of q, p and u: n_contacts * n_components. */
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
       * inconsistent: wrong vector sizes, n_components not in {1,2,3}, mu
       * negative or not finite, non-finite entries, G and b of mismatching
       * sizes.
       */
      void
      check_consistency() const;
    };



    /**
     * @brief The condensed ("local", in FCLIB's words) point-pair contact
     * problem u = W p + q + G alpha: the law's data and the dense
     * flexibility W (n_rows() x n_rows(), in local frames, displacement per
     * force). This is what the condensed path solves, what the FCLIB
     * readers return, and what CondensedOperator wraps.
     */
    struct ContactProblem : public ContactData
    {
      /** @brief Flexibility matrix, n_rows() x n_rows(), in local frames. */
      Eigen::MatrixXd W;

      /** @brief ContactData::check_consistency() and the size of W. */
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
     * Moves alpha from zero along -b (the direction in which the load b
     * drives the rigid modes into the supports: moving along -b changes
     * the normal gaps by -G_n b, whose
     * p-weighted sum is -|b|^2 < 0 at any solution) until the first normal
     * gap u_n = q_n + G_n alpha among the pairs that close along this
     * direction reaches zero. If a pair already penetrates, the step is
     * negative and moves the bodies back until no closing pair penetrates.
     * With every pair open the alpha columns of the Newton matrix vanish
     * (Newton would stall); with this start the touching pair is taken as
     * closed by the solver (see BNewtonSolver, "floating-body tie rule").
     *
     * @param problem The problem (must have n_alpha() > 0).
     * @return alpha with min over closing pairs of u_n(p = 0) equal to 0;
     * zero when b is zero (no load on the rigid modes) or no pair closes
     * along -b.
     */
    Eigen::VectorXd
    touching_alpha(const ContactData &problem);



    /**
     * @brief Floating-body start: where the rigid bodies come to rest.
     *
     * The rigid limit of the contact problem: with the contact forces p
     * on the normal rows only, the linear program
     * @code
     *   minimise b^T alpha  subject to  u_n(alpha) = q_n + G_n alpha >= l_n
     * @endcode
     * (the potential energy of the loads b on the rigid modes, the pairs
     * kept out of the obstacle; l_n = min(0, u_n(0)), so that pairs
     * penetrating at the start do not make it infeasible), whose dual is
     * G_n^T p = b, p >= 0: the rigid bodies' equilibrium. Solved by a
     * primal active-set method (one constraint enters or leaves per
     * iteration, at most n_alpha() active; each iteration O(n_rows()
     * n_alpha())). Unlike touching_alpha(), the answer does not depend on
     * how the rigid modes are parametrised, and the pairs it leaves active
     * span the load with compressive forces (a half disc comes to rest on
     * the pairs either side of its lowest point, not on two pairs beside
     * it about which it would roll).
     *
     * @param problem The problem (must have n_alpha() > 0).
     * @param alpha On success the resting alpha; unchanged otherwise.
     * @param active On success the pairs that hold the rest position.
     * @return false if the normal rows cannot hold the load (the program is
     * unbounded: a load held only by friction, or not at all), if b is
     * zero, or if the iteration limit is reached (degenerate ties).
     */
    bool
    resting_alpha(const ContactData         &problem,
                  Eigen::VectorXd           &alpha,
                  std::vector<unsigned int> &active);


  } // namespace contact
} // namespace igabde

#endif
