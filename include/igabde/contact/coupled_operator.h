#ifndef igabde_contact_coupled_operator_h
#define igabde_contact_coupled_operator_h

#include <igabde/contact/contact_operator.h>

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief The full path: the uncondensed contact system. The unknowns
     * are the displacement w of both bodies (the contact correction of
     * their displacements), the pair forces p and the rigid-mode
     * amplitudes alpha of floating bodies, coupled by the pair operator C
     * (relative displacement of every pair in its local frame, normal
     * first) and the rigid-mode columns G:
     * @code
     *   K w - C^T p             = 0     (held unknowns: w_i = 0)
     *   u = C w + G alpha + q           (pair relative displacements)
     *   G^T p                   = b
     * @endcode
     * Each Newton iteration solves
     * @code
     *   [ K     -C^T   0   ] [dw    ]   [r_w    ]
     *   [ A C    B     A G ] [dp    ] = [r_p    ]
     *   [ 0      G^T   0   ] [dalpha]   [r_alpha]
     * @endcode
     * with a sparse direct solver, or with preconditioned GMRES to a
     * tolerance the Newton chooses per iteration. This class turns the
     * primitives below into the ContactOperator interface; the
     * implementation (coupled/coupled_system.h) holds K and the block
     * matrix, which keeps the contact layer free of the body classes and
     * of the linear-algebra library. This is the seam where distributed
     * matrices enter: an implementation over MPI-distributed K and w
     * implements the same primitives.
     */
    class CoupledOperator : public ContactOperator
    {
    public:
      std::string
      path_name() const override;

      Eigen::VectorXd
      displacement(const Eigen::VectorXd &p,
                   const Eigen::VectorXd &w) const override;

      void
      displacement_adjoint(const Eigen::VectorXd &y,
                           Eigen::VectorXd       &y_p,
                           Eigen::VectorXd       &y_w) const override;

      Eigen::VectorXd
      equilibrium_residual(const Eigen::VectorXd &p,
                           const Eigen::VectorXd &w) const override;

      void
      equilibrium_adjoint(const Eigen::VectorXd &h,
                          Eigen::VectorXd       &h_p,
                          Eigen::VectorXd       &h_w) const override;

      double
      equilibrium_scale(const Eigen::VectorXd &p,
                        const Eigen::VectorXd &w) const override;

      PairWeights
      weights(const ContactData &data, const double factor) const override;

      Eigen::VectorXd
      pair_stiffness() const override;

      double
      flexibility_scale() const override;

      void
      set_proximal_shift(const double eps) override;

      bool
      newton_step(const ContactData    &data,
                  const NewtonBlocks   &blocks,
                  const ContactIterate &F,
                  ContactIterate       &dx,
                  StepReport           &report,
                  const double          lm_relative,
                  const bool            try_lu,
                  const double          linear_tolerance) override;

      bool
      bilateral_start(const ContactData       &data,
                      const std::vector<bool> &closed,
                      ContactIterate          &x) override;

      /** @brief False when a body is at finite strain (finite_strain()). */
      bool
      equilibrium_is_linear() const override;

      /** @brief linearize_bodies() at x.w, then linearize_geometry(x). */
      void
      linearize(const ContactIterate &x) override;

      /** @brief apply_C_derivative(v_w) + eps v_p. */
      Eigen::VectorXd
      displacement_derivative(const Eigen::VectorXd &v_p,
                              const Eigen::VectorXd &v_w) const override;

      /** @brief tangent_equations(v_w, v_p). */
      Eigen::VectorXd
      equilibrium_derivative(const Eigen::VectorXd &v_p,
                             const Eigen::VectorXd &v_w) const override;

      // --- The primitives an implementation provides.

      /** @brief C w: the pairs' relative displacements caused by w. */
      virtual Eigen::VectorXd
      apply_C(const Eigen::VectorXd &w) const = 0;

      /**
       * @brief K w - C^T p, with the rows of held unknowns set to w_i
       * (force units except there): zero when w is the bodies' response
       * to the pair forces p.
       */
      virtual Eigen::VectorXd
      displacement_equations(const Eigen::VectorXd &w,
                             const Eigen::VectorXd &p) const = 0;

      /**
       * @brief The size of the terms of displacement_equations():
       * || |K| |w| + |C|^T |p| || (absolute values entry by entry, the
       * Oettli-Prager denominator).
       */
      virtual double
      displacement_equations_scale(const Eigen::VectorXd &w,
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
       * @p why) when the linear solver fails. An iterative solver stops
       * when the residual is at most @p relative_tolerance times the norm
       * of the right-hand side; a direct solver ignores it.
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
       * @brief Whether a body of the system is at finite strain: its rows of
       * displacement_equations() are then f_int(u_ref + w) - f_ext - C^T p,
       * with u_ref the reference displacement of set_reference() (w is the
       * correction from it; held unknowns keep their values there, w_i = 0),
       * and the Newton matrix holds its tangent at the last
       * linearize_bodies(). The rows of a body at small strain stay
       * K w - C^T p.
       */
      virtual bool
      finite_strain() const
      {
        return false;
      }

      /**
       * @brief The displacement @p u (all unknowns, in the system's order)
       * the corrections w of the next solve start from, and the load
       * histories' factors @p factors of the loads f_ext; linearises at
       * w = 0. Nothing at small strain, where w is the contact part of the
       * displacement.
       */
      virtual void
      set_reference(const Eigen::VectorXd     &u,
                    const std::vector<double> &factors)
      {
        (void)u;
        (void)factors;
      }

      /**
       * @brief Assembles the tangent of the bodies at finite strain at the
       * correction @p w (nothing when it is the last one, or at small
       * strain).
       */
      virtual void
      linearize_bodies(const Eigen::VectorXd &w)
      {
        (void)w;
      }

      /**
       * @brief Finite sliding: the derivatives of the pairs' gaps, slips
       * and force directions by the configuration at the iterate @p x
       * (its forces x.p), which the next factorize(), apply_C_derivative()
       * and tangent_equations() take until the pairs are formed again.
       * Nothing by default (C does not depend on w).
       */
      virtual void
      linearize_geometry(const ContactIterate &x)
      {
        (void)x;
      }

      /**
       * @brief The derivative of C w by w along @p v: C v unless
       * linearize_geometry() holds the pairs' derivatives.
       */
      virtual Eigen::VectorXd
      apply_C_derivative(const Eigen::VectorXd &v) const
      {
        return apply_C(v);
      }

      /**
       * @brief The linearised displacement equations K_T v_w - C^T v_p (held
       * unknowns: v_w,i), K_T the bodies' tangent at the last
       * linearize_bodies() (K at small strain: displacement_equations()
       * itself).
       */
      virtual Eigen::VectorXd
      tangent_equations(const Eigen::VectorXd &v_w,
                        const Eigen::VectorXd &v_p) const
      {
        return displacement_equations(v_w, v_p);
      }

      /**
       * @brief K_T^T h over the unknowns not held, h_i on the held ones (K
       * symmetric at small strain: displacement_equations(h, 0)).
       */
      virtual Eigen::VectorXd
      tangent_transpose(const Eigen::VectorXd &h) const
      {
        return displacement_equations(h, Eigen::VectorXd::Zero(n_rows()));
      }

      /** @brief Iterations of the last solve() (0 for a direct one). */
      virtual unsigned int
      linear_iterations() const
      {
        return 0;
      }

      /**
       * @brief A stiffness (force per length) per pair from the underlying
       * elements: k_i = E_i A_i / h_i with E_i the series modulus of the
       * two bodies (Body 1's against a rigid obstacle), A_i the pair's
       * tributary area (length in 2D, unit thickness) and h_i the mean
       * element size (body measure / number of elements)^(1/dim) of the
       * two bodies (the larger).
       */
      virtual const Eigen::VectorXd &
      element_pair_stiffness() const = 0;

      /** @brief Number of nonzero entries of the last Newton matrix. */
      virtual double
      n_nonzeros() const = 0;

    private:
      /// The proximal shift eps.
      double eps = 0.;
    };
  } // namespace contact
} // namespace igabde

#endif
