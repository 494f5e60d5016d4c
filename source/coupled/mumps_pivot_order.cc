// Hands a pivot order to Amesos' MUMPS solver and reads its flop count. Its own
// file (and outside the unity batches: CMakeLists.txt) because Amesos_Mumps.h
// opens namespace Teuchos at global scope, whose Utilities and ArrayView would
// collide with deal.II's in any file that includes both.

#include <igabde/coupled/mumps_pivot_order.h>

#include <Amesos_Mumps.h>

namespace igabde
{
  namespace coupled
  {
    namespace internal
    {
      bool
      give_mumps_pivot_order(Amesos_BaseSolver &solver, std::vector<int> &order)
      {
        auto *mumps = dynamic_cast<Amesos_Mumps *>(&solver);
        if (mumps == nullptr || order.empty())
          return false;
        // ICNTL(7) = 1: the order given in PERM_IN.
        mumps->SetICNTL(7, 1);
        mumps->SetOrdering(order.data());
        return true;
      }



      double
      mumps_factorization_flops(Amesos_BaseSolver &solver)
      {
        auto *mumps = dynamic_cast<Amesos_Mumps *>(&solver);
        // RINFOG(3): the floating-point operations of the elimination.
        return mumps != nullptr ? mumps->GetRINFOG()[2] : 0.;
      }



      double
      mumps_local_bytes(Amesos_BaseSolver &solver)
      {
        auto *mumps = dynamic_cast<Amesos_Mumps *>(&solver);
        if (mumps == nullptr)
          return 0.;
        // INFO(9), INFO(10): the factor's reals and integers on this rank
        // (negative: millions).
        const auto count = [](const int n) {
          return n >= 0 ? double(n) : -1e6 * double(n);
        };
        const int *info = mumps->GetINFO();
        return count(info[8]) * sizeof(double) + count(info[9]) * sizeof(int);
      }



      int
      mumps_error(Amesos_BaseSolver &solver)
      {
        auto *mumps = dynamic_cast<Amesos_Mumps *>(&solver);
        return mumps != nullptr ? mumps->GetINFOG()[0] : 0;
      }



      void
      set_mumps_workspace_relaxation(Amesos_BaseSolver &solver,
                                     const int          percent)
      {
        if (auto *mumps = dynamic_cast<Amesos_Mumps *>(&solver))
          mumps->SetICNTL(14, percent);
      }
    } // namespace internal
  }   // namespace coupled
} // namespace igabde
