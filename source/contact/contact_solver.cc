#include <igabde/base/utilities.h>

#include <igabde/contact/bnewton.h>
#include <igabde/contact/contact_solver.h>
#include <igabde/contact/penalty_solvers.h>

#include <iomanip>
#include <ostream>
#include <sstream>

namespace igabde
{
  namespace contact
  {
    void
    ContactIterationRecord::print(std::ostream &out) const
    {
      std::ios::fmtflags f(out.flags());
      out << std::setw(5) << iteration << ' ' << std::setw(9) << phase
          << std::scientific << std::setprecision(4) << std::setw(12) << h_norm
          << std::setw(12) << residual << std::setw(12) << balanced_residual
          << std::setw(12) << step << std::setw(6) << n_open << std::setw(6)
          << n_stick << std::setw(6) << n_slip << std::setw(7) << n_closed
          << std::setw(6) << n_reduced << ' ' << note
          << (linear_iterations > 0 ?
                std::string(note.empty() ? "" : " ") + "gmres " +
                  std::to_string(linear_iterations) :
                std::string())
          << '\n';
      out.flags(f);
    }



    void
    ContactSolverResult::print_history(std::ostream &out) const
    {
      std::ios::fmtflags f(out.flags());
      out << "   it     phase        |H|    residual    balanced        step"
             "  open stick  slip closed   red note\n";
      for (const ContactIterationRecord &rec : history)
        rec.print(out);
      out << summary() << '\n';
      out.flags(f);
    }



    std::string
    ContactSolverResult::summary() const
    {
      std::ostringstream s;
      s << (converged ? "converged" : "NOT converged") << " after "
        << iterations << " iterations";
      if (sweeps > 0)
        s << " and " << sweeps << " Gauss-Seidel sweeps";
      s << ", relative natural-map residual " << std::scientific
        << std::setprecision(4) << residual << " (balanced "
        << balanced_residual << ")";
      if (alpha.size() > 0)
        s << ", equilibrium residual " << equilibrium_residual;
      s << ", open/stick/slip/closed " << n_open << '/' << n_stick << '/'
        << n_slip << '/' << n_closed << ": " << diagnosis;
      std::string krylov;
      for (const ContactIterationRecord &rec : history)
        if (rec.linear_iterations > 0)
          krylov +=
            (krylov.empty() ? "" : " ") + std::to_string(rec.linear_iterations);
      if (!krylov.empty())
        s << "; GMRES iterations per Newton step: " << krylov;
      return s.str();
    }



    std::unique_ptr<ContactSolver>
    create_contact_solver(const ContactSolverSettings &settings)
    {
      switch (settings.algorithm)
        {
          case Algorithm::bde:
            return std::make_unique<BNewtonSolver>(settings.bnewton);
          case Algorithm::penalty:
            return std::make_unique<PenaltySolver>(settings);
          case Algorithm::augmented_lagrange:
            return std::make_unique<AugmentedLagrangeSolver>(settings);
        }
      return nullptr;
    }
  } // namespace contact
} // namespace igabde
