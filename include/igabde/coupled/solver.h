#ifndef igabde_coupled_solver_h
#define igabde_coupled_solver_h

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

    /** @brief The name of @p solver as the scene writes it. */
    inline std::string
    to_string(const Solver solver)
    {
      return solver == Solver::mumps ? "mumps" :
             solver == Solver::klu   ? "klu" :
                                       "gmres-amg";
    }
  } // namespace coupled
} // namespace igabde

#endif
