#ifndef igabde_contact_full_system_solvers_h
#define igabde_contact_full_system_solvers_h

#include <igabde/contact/contact_solver.h>

#include <string>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief The B-differentiable equations on the uncondensed system
     * (Contact/Path = full): displacements, pair forces and rigid-mode
     * amplitudes are the unknowns together, and each Newton iteration sets
     * per pair the equations of its piece (pair_law(): open p = 0, stick
     * u_t = 0, slip p_t on the cone, closed u_n = 0) in the sparse system
     * of ContactProblem::coupled. The same per-pair law, tie rules and
     * stopping test as the condensed BNewtonSolver, with an Armijo line
     * search on theta = |H|^2/2 + |K w - C^T p|^2/2 + |G^T p - b|^2/2; the
     * weights r come from the underlying elements (pair_weights()).
     */
    class FullBNewtonSolver : public ContactSolver
    {
    public:
      explicit FullBNewtonSolver(const BNewtonSettings &settings);

      std::string
      name() const override;

      /**
       * @brief Solve; @p problem must carry a CoupledOperator, and its w0
       * the displacement consistent with @p p0 (or be empty with p0 = 0).
       */
      ContactSolverResult
      solve(const ContactProblem  &problem,
            const Eigen::VectorXd &p0,
            const Eigen::VectorXd &alpha0) const override;

    private:
      const BNewtonSettings settings;
    };

    /**
     * @brief Node-to-node penalty contact as ANSYS applies it: per pair the
     * normal stiffness k_n = FKN k_i (k_i the pair stiffness of the
     * CoupledOperator, from the underlying elements), the stick stiffness
     * k_t = FKT k_n and Coulomb return mapping (penalty_law()); full
     * Newton steps on the coupled system, with the pair states updated
     * every iteration. Converged when no pair changes state and the
     * residuals are below the tolerance; the penetration (about p / k_n)
     * is part of the answer. Like ANSYS it takes no line search, so a
     * stiff penalty may chatter between states and not converge: that is
     * reported, not hidden.
     */
    class PenaltySolver : public ContactSolver
    {
    public:
      explicit PenaltySolver(const ContactSolverSettings &settings);

      std::string
      name() const override;

      ContactSolverResult
      solve(const ContactProblem  &problem,
            const Eigen::VectorXd &p0,
            const Eigen::VectorXd &alpha0) const override;

    private:
      const ContactSolverSettings settings;
    };

    /**
     * @brief Augmented Lagrangian (Uzawa) around the penalty solve: the
     * multipliers lambda (normal and tangential) enter penalty_law(), the
     * penalty problem is solved by PenaltySolver's Newton, then lambda <-
     * p, until the natural-map residual and the equilibrium of floating
     * bodies meet the tolerance of the B-differentiable equations. Its
     * converged answer is the BDE answer.
     */
    class AugmentedLagrangeSolver : public ContactSolver
    {
    public:
      explicit AugmentedLagrangeSolver(const ContactSolverSettings &settings);

      std::string
      name() const override;

      ContactSolverResult
      solve(const ContactProblem  &problem,
            const Eigen::VectorXd &p0,
            const Eigen::VectorXd &alpha0) const override;

    private:
      const ContactSolverSettings settings;
    };
  } // namespace contact
} // namespace igabde

#endif
