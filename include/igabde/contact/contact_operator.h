#ifndef igabde_contact_contact_operator_h
#define igabde_contact_contact_operator_h

#include <igabde/base/memory_record.h>

#include <igabde/contact/contact_law.h>
#include <igabde/contact/contact_problem.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <memory>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief The unknowns of a contact solve: the pair forces p (n_rows()),
     * the rigid-mode amplitudes alpha of floating bodies (n_alpha()) and,
     * on the full path, the bodies' contact displacement w
     * (ContactOperator::n_dofs(); empty on the condensed path).
     */
    struct ContactIterate
    {
      Eigen::VectorXd p, alpha, w;
    };

    /**
     * @brief The per-pair blocks of one Newton matrix: for every pair the
     * piece of the law, whose d x d blocks A = dH/du and B = dH/dp
     * (top-left of each 3 x 3 matrix) enter the Newton matrix.
     */
    using NewtonBlocks = std::vector<PairPiece>;

    /**
     * @brief How the pair displacements depend on the unknowns of a contact
     * solve: the path. The law's data (q, mu, G, b) are ContactData; the
     * operator adds the part that depends on the forces and, on the full
     * path, on the bodies' displacement:
     * @code
     *   u = M(p, w) + G alpha + q,
     *   M(p, w) = W p + eps p            (CondensedOperator: the dense
     *                                     flexibility from the bodies'
     *                                     Schur complements)
     *           = C w + eps p            (CoupledOperator: the pair
     *                                     operator on the bodies'
     *                                     displacement w, with the
     *                                     displacement equations
     *                                     E(p, w) = K w - C^T p = 0)
     * @endcode
     * eps >= 0 is the proximal shift (set_proximal_shift(); 0 outside the
     * proximal phase of the B-Newton). The one semismooth Newton driver
     * (newton_driver.h) sees a path only through this interface: the
     * products with M and E and their adjoints for the merit function and
     * its gradient, the weights of the law, and the Newton solve for the
     * per-pair blocks of the law's pieces.
     */
    class ContactOperator
    {
    public:
      virtual ~ContactOperator() = default;

      /** @brief The path's name for logs: "condensed" or "full". */
      virtual std::string
      path_name() const = 0;

      /**
       * @brief What this rank holds for the operator beyond the contact
       * problem's data (base::MemoryItem; empty where nothing is counted).
       */
      virtual std::vector<base::MemoryItem>
      memory_record() const
      {
        return {};
      }

      /** @brief Rows of u and p: pairs times components per pair. */
      virtual unsigned int
      n_rows() const = 0;

      /** @brief Displacement unknowns w (0 on the condensed path). */
      virtual unsigned int
      n_dofs() const
      {
        return 0;
      }

      /** @brief M(p, w) (see the class documentation), n_rows(). */
      virtual Eigen::VectorXd
      displacement(const Eigen::VectorXd &p,
                   const Eigen::VectorXd &w) const = 0;

      /**
       * @brief The derivative of M along the direction (@p v_p, @p v_w):
       * M(v_p, v_w) where M is linear (the default); with finite sliding
       * and the full sliding tangent, the derivative of the pairs' gaps
       * and slips by the configuration at the last linearize().
       */
      virtual Eigen::VectorXd
      displacement_derivative(const Eigen::VectorXd &v_p,
                              const Eigen::VectorXd &v_w) const
      {
        return displacement(v_p, v_w);
      }

      /**
       * @brief Finite sliding (Contact/Sliding = finite): re-forms the
       * pairs on the configuration the iterate @p x reaches (their
       * operators, frames and gaps there) before its residual is
       * evaluated, so that displacement() is the pairs' linearisation at
       * @p x and displacement_offset() the change of the gaps that the
       * data's q does not hold: the pair displacements at @p x are then
       * displacement(x) + q + displacement_offset(), exact at @p x.
       * Nothing by default (pairs formed once, small sliding).
       */
      virtual void
      update_geometry(const ContactIterate &x)
      {
        (void)x;
      }

      /**
       * @brief The configuration that update_geometry()'s iterates are
       * corrections from has changed (a new step): the next update forms
       * the pairs whatever the iterate.
       */
      virtual void
      forget_geometry()
      {}

      /**
       * @brief After update_geometry(): the pair displacements' offset
       * from displacement() + q at the configuration of the last update;
       * nullptr without finite sliding.
       */
      virtual const Eigen::VectorXd *
      displacement_offset() const
      {
        return nullptr;
      }

      /**
       * @brief The adjoint of displacement(): M_p^T y into @p y_p
       * (n_rows()) and M_w^T y into @p y_w (n_dofs()).
       */
      virtual void
      displacement_adjoint(const Eigen::VectorXd &y,
                           Eigen::VectorXd       &y_p,
                           Eigen::VectorXd       &y_w) const = 0;

      /**
       * @brief The displacement equations E(p, w) = K w - C^T p (held
       * unknowns: w_i), n_dofs(); empty on the condensed path.
       */
      virtual Eigen::VectorXd
      equilibrium_residual(const Eigen::VectorXd &p,
                           const Eigen::VectorXd &w) const
      {
        (void)p;
        (void)w;
        return Eigen::VectorXd();
      }

      /**
       * @brief The adjoint of equilibrium_residual(): E_p^T h into @p h_p,
       * E_w^T h into @p h_w (zero on the condensed path).
       */
      virtual void
      equilibrium_adjoint(const Eigen::VectorXd &h,
                          Eigen::VectorXd       &h_p,
                          Eigen::VectorXd       &h_w) const
      {
        (void)h;
        h_p.setZero(n_rows());
        h_w.resize(0);
      }

      /**
       * @brief Whether equilibrium_residual() is linear in (p, w): true on
       * the condensed path and on the full path at small strain; false
       * when a body of the full path is at finite strain (E = f_int(w) -
       * f_ext - C^T p), whose Newton iterations then linearise() first and
       * whose line search evaluates E at every trial point.
       */
      virtual bool
      equilibrium_is_linear() const
      {
        return true;
      }

      /**
       * @brief Linearises the displacement equations at @p x (the tangent
       * of the bodies at finite strain, which newton_step(),
       * equilibrium_derivative() and equilibrium_adjoint() then use);
       * nothing where they are linear.
       */
      virtual void
      linearize(const ContactIterate &x)
      {
        (void)x;
      }

      /**
       * @brief Whether the Newton iteration asks the next linearize() for
       * the most exact tangent the operator can give, where a cheaper one
       * is its choice otherwise (Contact/Sliding tangent = auto: the
       * sliding derivatives once the residual contracts slowly). Nothing
       * by default.
       */
      virtual void
      want_exact_tangent(const bool wanted)
      {
        (void)wanted;
      }

      /**
       * @brief The derivative of equilibrium_residual() at the point of the
       * last linearize() along (@p v_p, @p v_w); where E is linear, E itself
       * at (v_p, v_w).
       */
      virtual Eigen::VectorXd
      equilibrium_derivative(const Eigen::VectorXd &v_p,
                             const Eigen::VectorXd &v_w) const
      {
        return equilibrium_residual(v_p, v_w);
      }

      /**
       * @brief The size of the terms of equilibrium_residual():
       * || |K| |w| + |C|^T |p| || (the Oettli-Prager denominator of its
       * componentwise backward error); 0 on the condensed path.
       */
      virtual double
      equilibrium_scale(const Eigen::VectorXd &p,
                        const Eigen::VectorXd &w) const
      {
        (void)p;
        (void)w;
        return 0.;
      }

      /**
       * @brief The weights r_n, r_t of the B-differentiable equations at
       * factor @p factor (pair_weights()): c / W_nn on the condensed path
       * (of W + eps I in the proximal phase), c times the pair stiffness of
       * the underlying elements on the full path.
       */
      virtual PairWeights
      weights(const ContactData &data, const double factor) const = 0;

      /**
       * @brief A stiffness per pair (force per length): the scale of the
       * penalty methods' k_n = FKN k_i. The full path takes it from the
       * underlying elements (CoupledOperator::pair_stiffness()); the
       * condensed one from the pair's own flexibility, 1 / W_nn.
       */
      virtual Eigen::VectorXd
      pair_stiffness() const = 0;

      /**
       * @brief A flexibility scale for the proximal phase (eps starts
       * there): the largest W_ii, or the largest 1 / k_i.
       */
      virtual double
      flexibility_scale() const = 0;

      /** @brief Sets the proximal shift eps (see the class documentation). */
      virtual void
      set_proximal_shift(const double eps) = 0;

      /**
       * @brief Whether a Newton matrix found singular at the first
       * iteration is better met by the proximal phase than by
       * Levenberg-Marquardt steps. False unless the path says so
       * (CondensedOperator on a sparse W).
       */
      virtual bool
      proximal_for_singular_start() const
      {
        return false;
      }

      /**
       * @brief Whether direction @p row of the pairs is held by supports
       * on both sides: no displacement moves it (an empty row of C on the
       * full path, a zero row of W on the condensed path) and its force
       * enters no body's equations. Pairs held in every direction are left
       * out when the path is prepared; a pair on a symmetry plane keeps
       * its other directions. False unless the path says so.
       */
      virtual bool
      pair_row_is_held(const unsigned int row) const
      {
        (void)row;
        return false;
      }

      /**
       * @brief The dense flexibility W of the condensed path, unshifted;
       * nullptr on a path that forms none (the nonsmooth Gauss-Seidel
       * phase sweeps over its columns).
       */
      virtual const Eigen::MatrixXd *
      dense_flexibility() const
      {
        return nullptr;
      }

      /**
       * @brief W in compressed rows, unshifted, where the operator keeps W
       * sparse for @p data's components (mostly zero: a condensed W of
       * rigid bodies, each contact coupled to the few that share its
       * bodies); nullptr otherwise. A nonsmooth Gauss-Seidel sweep over
       * it costs one pass over W's non-zero entries.
       */
      virtual const Eigen::SparseMatrix<double, Eigen::RowMajor> *
      sparse_flexibility(const ContactData &data) const
      {
        (void)data;
        return nullptr;
      }

      /**
       * @brief What one Newton step reports besides the increment.
       */
      struct StepReport
      {
        /// Remarks for the iteration table ("lm " for a
        /// Levenberg-Marquardt step).
        std::string note;
        /// Size of the linear system solved.
        unsigned int n_reduced = 0;
        /// Iterations of an iterative linear solve (0 for a direct one).
        unsigned int linear_iterations = 0;
        /// Why the step failed, if it did.
        std::string why;
      };

      /**
       * @brief The Newton increment dx for the residual F = (H, G^T p - b,
       * E) at the blocks @p blocks of the law, J dx = -F, with
       * @code
       *   J = [ B + A M_p   A G   A M_w ]
       *       [ G^T          0     0    ]
       *       [ E_p          0     E_w  ]
       * @endcode
       * @param data The law's data (G for the rigid-mode columns).
       * @param lm_relative Levenberg-Marquardt regularisation, relative to
       * the largest diagonal entry of J^T J, for a (nearly) singular
       * reduced matrix (where the operator supports it).
       * @param try_lu Whether to try the LU at all (false after repeated
       * singular matrices).
       * @param linear_tolerance Relative accuracy of an iterative solve.
       * @return false when no increment could be computed (@p report .why
       * says why): the driver then takes a steepest-descent step.
       */
      virtual bool
      newton_step(const ContactData    &data,
                  const NewtonBlocks   &blocks,
                  const ContactIterate &F,
                  ContactIterate       &dx,
                  StepReport           &report,
                  const double          lm_relative,
                  const bool            try_lu,
                  const double          linear_tolerance) = 0;

      /**
       * @brief The bilateral start: the pairs @p closed glued (their
       * relative displacement zero; directions held by supports on both
       * sides left free of force) and the others free of force, with the
       * equilibrium rows of floating bodies. Returns false if there is
       * nothing to glue or the solve fails.
       */
      virtual bool
      bilateral_start(const ContactData       &data,
                      const std::vector<bool> &closed,
                      ContactIterate          &x) = 0;
    };



    /**
     * @brief The condensed path: u = W p + eps p + G alpha + q with the
     * dense flexibility W of a ContactProblem (from the bodies' Schur
     * complements, or read from an FCLIB file). Newton matrix: the rows with
     * A = 0 and B = identity (open normals, free tangents) give d_i = -H_i
     * and drop out; the rest is factorised by Cholesky when every remaining
     * row is a positive multiple of a row of a symmetric W (closed normals,
     * stick), by LU otherwise, densely (LAPACK) or sparsely (Eigen) when W
     * is sparse; a (nearly) singular matrix is replaced by a
     * Levenberg-Marquardt step.
     */
    class CondensedOperator : public ContactOperator
    {
    public:
      /** @brief How the Newton matrix is stored and factorised. */
      enum class LinearAlgebra
      {
        /// Sparse when W's fill is at most sparse_fill (and W has at least
        /// min_sparse_rows rows).
        automatic,
        /// Dense LAPACK factorisations (Cholesky or LU).
        dense,
        /// Eigen sparse factorisations (SimplicialLDLT or SparseLU).
        sparse
      };

      /**
       * @brief Below this many rows W is always stored dense: a sparse
       * factorisation's set-up costs more than LAPACK's on so small a
       * matrix, whatever the fill.
       */
      static constexpr unsigned int min_sparse_rows = 48;

      /**
       * @brief Keeps a reference to @p W (n x n, symmetric or not).
       * @param use_symmetry Factorise by Cholesky where the pieces allow.
       */
      CondensedOperator(
        const Eigen::MatrixXd &W,
        const LinearAlgebra    linear_algebra = LinearAlgebra::automatic,
        const double           sparse_fill    = 0.1,
        const bool             use_symmetry   = true);

      ~CondensedOperator() override;

      std::string
      path_name() const override;

      unsigned int
      n_rows() const override;

      Eigen::VectorXd
      displacement(const Eigen::VectorXd &p,
                   const Eigen::VectorXd &w) const override;

      void
      displacement_adjoint(const Eigen::VectorXd &y,
                           Eigen::VectorXd       &y_p,
                           Eigen::VectorXd       &y_w) const override;

      PairWeights
      weights(const ContactData &data, const double factor) const override;

      Eigen::VectorXd
      pair_stiffness() const override;

      double
      flexibility_scale() const override;

      const Eigen::MatrixXd *
      dense_flexibility() const override;

      const Eigen::SparseMatrix<double, Eigen::RowMajor> *
      sparse_flexibility(const ContactData &data) const override;

      /// A diagonal entry of W at most 1e-8 of the largest: the direction
      /// moves (next to) nothing, held by supports on both sides.
      bool
      pair_row_is_held(const unsigned int row) const override;

      void
      set_proximal_shift(const double eps) override;

      /**
       * True where W is kept sparse and is symmetric: there a
       * Levenberg-Marquardt step factorises J^T J, whose fill far exceeds
       * J's, at every iteration, while the proximal subproblems' Newton
       * matrices (of W + eps I) are regular, and on sticking and closed
       * pairs symmetric positive definite (a sparse Cholesky
       * factorisation). On KaplasTower (FCLIB: a hyperstatic tower of
       * rigid bodies, 570 contacts, W 4 % full and of about half rank) the
       * proximal phase from the start takes 11 iterations against
       * Levenberg-Marquardt's 14, and less time. The Capsules problems
       * (W 1.6 % full, not symmetric) stay with Levenberg-Marquardt: there
       * the proximal phase from the start took longer
       * (doc/contact-solver.md).
       */
      bool
      proximal_for_singular_start() const override;

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

    private:
      class Storage;
      /// W, its shifted copy in the proximal phase, its structure.
      std::unique_ptr<Storage> storage;
    };
  } // namespace contact
} // namespace igabde

#endif
