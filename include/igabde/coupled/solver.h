#ifndef igabde_coupled_solver_h
#define igabde_coupled_solver_h

#include <igabde/base/choice_names.h>

#include <string>

namespace igabde
{
  namespace coupled
  {
    /** @brief Contact/Full system solver: the coupled system's solver. */
    enum class Solver
    {
      /// Amesos' MUMPS (direct).
      mumps,
      /// Amesos' KLU (direct).
      klu,
      /// GMRES preconditioned by ML algebraic multigrid.
      gmres_amg
    };

    /** @brief The names of Solver as the scene writes them. */
    inline constexpr base::ChoiceNames<Solver, 3> solver_names = {
      {{Solver::mumps, "mumps"},
       {Solver::klu, "klu"},
       {Solver::gmres_amg, "gmres-amg"}}};

    /** @brief The name of @p solver as the scene writes it. */
    inline std::string
    to_string(const Solver solver)
    {
      return base::name_of(solver_names, solver);
    }
  } // namespace coupled
} // namespace igabde

#endif
