#ifndef igabde_discretization_factorization_request_h
#define igabde_discretization_factorization_request_h

#include <igabde/discretization/body.h>

#include <deal.II/base/timer.h>

#include <memory>
#include <mpi.h>
#include <vector>

namespace igabde
{
  namespace discretization
  {
    /**
     * @brief What a body's factorisation must provide and what must stay
     * after it: the contact path's answer for one body (the path knows
     * whether the bodies solve again after their load cases, and which
     * contact points their Schur complements serve).
     *
     * The default is a body without contact: no Schur interface, K read
     * afterwards by the support reactions only, the factor kept.
     */
    template <int dim>
    struct FactorizationRequest
    {
      /// Operators of the contact points on the body: the factorisation
      /// also forms the Schur complement of K onto the unknowns they touch.
      /// Empty: none.
      std::vector<PointOperator<dim>> interface;
      /// Whether K is read after the factorisation beyond the support
      /// reactions' rows, on every rank (the coupled system of the full
      /// path assembles from it): K is then assembled wherever
      /// setup_system() left it out, and kept whole.
      bool matrix_read_afterwards = false;
      /// Whether the body solves again after its load cases (the condensed
      /// path's flexibility and field recovery). Without, the
      /// factorisation is freed once the load cases are solved.
      bool solves_afterwards = true;
    };

    /**
     * @brief What factorize_bodies() did, per body, the largest over the
     * ranks (0 for a body at finite strain, which factorises its tangent
     * in every Newton iteration instead).
     */
    struct FactorizationReport
    {
      /// Wall seconds of the factorisation and the load cases.
      std::vector<double> seconds;
      /// Floating-point operations of the factorisation (MUMPS' estimate;
      /// 0 where the solver gives none).
      std::vector<double> flops;
    };

    /**
     * @brief Factorises every body at small strain for @p requests (one per
     * body), each group its own body at the same time, hands every rank of
     * @p world what it did not compute, and frees what no later solve
     * reads. Timed in @p timer's sections "assembly" (K where a request
     * reads it afterwards and setup_system() left it out) and
     * "factorization". Collective on @p world.
     */
    template <int dim>
    FactorizationReport
    factorize_bodies(const std::vector<std::unique_ptr<Body<dim>>> &bodies,
                     const std::vector<FactorizationRequest<dim>>  &requests,
                     TimerOutput                                   &timer,
                     MPI_Comm                                       world);
  } // namespace discretization
} // namespace igabde

#endif
