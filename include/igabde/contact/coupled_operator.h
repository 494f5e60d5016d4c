#ifndef igabde_contact_coupled_operator_h
#define igabde_contact_coupled_operator_h

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief The uncondensed contact system, as the full-system contact
     * solvers see it: the displacement unknowns w of both bodies (the
     * contact correction of their displacements), the pair forces p and the
     * rigid-mode amplitudes alpha of floating bodies, coupled by the pair
     * operator C (relative displacement of every pair in its local frame,
     * normal first) and the rigid-mode columns G of the ContactProblem:
     * @code
     *   K w - C^T p             = 0     (held unknowns: w_i = 0)
     *   u = C w + G alpha + q           (pair relative displacements)
     *   G^T p                   = b
     * @endcode
     * Each Newton iteration of a full-system solver linearises the per-pair
     * law as A_i du_i + B_i dp_i = r_i (contact_law.h) and solves
     * @code
     *   [ K     -C^T   0   ] [dw    ]   [r_w    ]
     *   [ A C    B     A G ] [dp    ] = [r_p    ]
     *   [ 0      G^T   0   ] [dalpha]   [r_alpha]
     * @endcode
     * with a sparse direct solver, or with preconditioned GMRES to a
     * tolerance the Newton chooses per iteration. This interface keeps the
     * contact layer free of the body classes and of the linear-algebra library
     * that holds K; the implementation (coupled/coupled_system.h) assembles the
     * block matrix. Vectors are Eigen vectors of the sizes n_dofs(), n_rows()
     * (the problem's) and n_alpha().
     */
    class CoupledOperator
    {
    public:
      virtual ~CoupledOperator() = default;

      /** @brief Number of displacement unknowns w (all bodies). */
      virtual unsigned int
      n_dofs() const = 0;

      /** @brief Rows of C: pairs times components per pair. */
      virtual unsigned int
      n_rows() const = 0;

      /** @brief C w: the pairs' relative displacements caused by w. */
      virtual Eigen::VectorXd
      apply_C(const Eigen::VectorXd &w) const = 0;

      /**
       * @brief K w - C^T p, with the rows of held unknowns set to w_i
       * (force units except there): zero when w is the bodies' response
       * to the pair forces p.
       */
      virtual Eigen::VectorXd
      equilibrium_residual(const Eigen::VectorXd &w,
                           const Eigen::VectorXd &p) const = 0;

      /**
       * @brief The size of the terms of equilibrium_residual():
       * || |K| |w| + |C|^T |p| || (absolute values entry by entry, the
       * Oettli-Prager denominator). The residual divided by it is the
       * componentwise backward error of the displacement equations, which
       * rounding keeps near the machine epsilon whatever the scaling.
       */
      virtual double
      equilibrium_scale(const Eigen::VectorXd &w,
                        const Eigen::VectorXd &p) const = 0;

      /**
       * @brief Assembles and factorises the Newton matrix for the per-pair
       * blocks @p A and @p B (d x d blocks, top-left of each 3 x 3 matrix,
       * d the components per pair).
       */
      virtual void
      factorize(const std::vector<Eigen::Matrix3d> &A,
                const std::vector<Eigen::Matrix3d> &B) = 0;

      /**
       * @brief Solves the Newton system factorised last for the right-hand
       * sides @p r_w, @p r_p, @p r_alpha; returns false (with a reason in
       * @p why) when the linear solver fails (singular matrix, no
       * convergence). An iterative solver stops when the residual of the
       * Newton system is at most @p relative_tolerance times the norm of
       * the right-hand side (all rows in force units); a direct solver
       * ignores it.
       */
      virtual bool
      solve(const Eigen::VectorXd &r_w,
            const Eigen::VectorXd &r_p,
            const Eigen::VectorXd &r_alpha,
            Eigen::VectorXd       &dw,
            Eigen::VectorXd       &dp,
            Eigen::VectorXd       &dalpha,
            std::string           &why,
            const double           relative_tolerance = 1e-12) const = 0;

      /**
       * @brief Iterations of the last solve() of an iterative solver (0 for
       * a direct one).
       */
      virtual unsigned int
      linear_iterations() const
      {
        return 0;
      }

      /** @brief Whether solve() is iterative (its accuracy is chosen per
       * call). */
      virtual bool
      iterative() const
      {
        return false;
      }

      /**
       * @brief A stiffness (force per length) per pair from the underlying
       * elements: k_i = E_i A_i / h_i with E_i the series modulus of the
       * two bodies (Body 1's against a rigid obstacle), A_i the pair's
       * tributary area (length in 2D, unit thickness) and h_i the mean
       * element size (body measure / number of elements)^(1/dim) of the
       * two bodies (the larger). It scales the penalty stiffness and the
       * weights r of the B-differentiable equations on the full path.
       */
      virtual const Eigen::VectorXd &
      pair_stiffness() const = 0;

      /** @brief Number of nonzero entries of the last Newton matrix. */
      virtual double
      n_nonzeros() const = 0;

      /**
       * @brief Whether row @p row of C (pair row / d, component row % d)
       * is empty: that direction of the pair is held by supports on both
       * sides, so no displacement moves it and its force enters no body's
       * equations (the supports take it).
       */
      virtual bool
      pair_row_is_held(const unsigned int row) const = 0;
    };
  } // namespace contact
} // namespace igabde

#endif
