#ifndef igabde_coupled_mumps_pivot_order_h
#define igabde_coupled_mumps_pivot_order_h

#include <vector>

class Amesos_BaseSolver;

namespace igabde
{
  namespace coupled
  {
    namespace internal
    {
      /**
       * @brief Gives @p solver, if it is Amesos' MUMPS solver and before its
       * symbolic factorisation, the pivot order @p order (MUMPS' PERM_IN,
       * 1-based positions), which must stay alive while the solver may
       * read it. Returns whether it was given (false for another solver
       * or an empty order: the solver then orders itself).
       */
      bool
      give_mumps_pivot_order(Amesos_BaseSolver &solver,
                             std::vector<int>  &order);

      /**
       * @brief The floating-point operations of the last numeric
       * factorisation of @p solver if it is Amesos' MUMPS solver (MUMPS'
       * RINFOG(3)), else 0.
       */
      double
      mumps_factorization_flops(Amesos_BaseSolver &solver);

      /**
       * @brief Bytes of the factor on this rank after the last numeric
       * factorisation of @p solver if it is Amesos' MUMPS solver (its
       * reals and integers, INFO(9) and INFO(10)), else 0.
       */
      double
      mumps_local_bytes(Amesos_BaseSolver &solver);

      /**
       * @brief MUMPS' error code INFOG(1) after the last phase of @p solver
       * if it is Amesos' MUMPS solver (0: no error), else 0.
       */
      int
      mumps_error(Amesos_BaseSolver &solver);

      /**
       * @brief Sets MUMPS' workspace relaxation ICNTL(14) (per cent above
       * the analysis' estimate) of @p solver, before its symbolic
       * factorisation, if it is Amesos' MUMPS solver.
       */
      void
      set_mumps_workspace_relaxation(Amesos_BaseSolver &solver,
                                     const int          percent);
    } // namespace internal
  }   // namespace coupled
} // namespace igabde

#endif
