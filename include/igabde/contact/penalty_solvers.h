#ifndef igabde_contact_penalty_solvers_h
#define igabde_contact_penalty_solvers_h

#include <igabde/contact/contact_solver.h>
#include <igabde/contact/newton_driver.h>

#include <string>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief Node-to-node penalty contact as ANSYS applies it: per pair the
     * normal stiffness k_n = FKN k_i (k_i the operator's pair stiffness,
     * from the underlying elements on the full path), the stick stiffness
     * k_t = FKT k_n and Coulomb return mapping: the PenaltyLaw in the one
     * Newton driver, with the pair states updated every iteration.
     * Converged when the residuals are below the tolerance; the
     * penetration (about p / k_n) is part of the answer. Without
     * Contact/Penalty line search, full Newton steps as ANSYS takes them by
     * default, so a stiff penalty may chatter between states and not
     * converge: that is reported, not hidden.
     */
    class PenaltySolver : public ContactSolver
    {
    public:
      explicit PenaltySolver(const ContactSolverSettings &settings);

      std::string
      name() const override;

      bool
      exact() const override;

      ContactSolverResult
      solve(const ContactData     &data,
            ContactOperator       &op,
            const ContactIterate  &start,
            const Eigen::VectorXd &p_previous = {}) const override;

    private:
      const ContactSolverSettings settings;
    };

    /**
     * @brief Augmented Lagrangian (the method of multipliers with penalty
     * increase) as an outer loop around the penalty solve: the multipliers
     * lambda (normal and tangential) are the base forces of the
     * PenaltyLaw; after each penalty solve lambda <- p, until the
     * natural-map residual and the equilibrium of floating bodies meet
     * the tolerance of the B-differentiable equations. Its converged
     * answer is the BDE answer.
     */
    class AugmentedLagrangeSolver : public ContactSolver
    {
    public:
      explicit AugmentedLagrangeSolver(const ContactSolverSettings &settings);

      std::string
      name() const override;

      ContactSolverResult
      solve(const ContactData     &data,
            ContactOperator       &op,
            const ContactIterate  &start,
            const Eigen::VectorXd &p_previous = {}) const override;

    private:
      const ContactSolverSettings settings;
    };
  } // namespace contact
} // namespace igabde

#endif
