#include <igabde/discretization/settings.h>

namespace igabde
{
  namespace discretization
  {
    std::string
    to_string(const Type type)
    {
      return type == Type::nurbs ? "nurbs" : "lagrange";
    }



    std::string
    to_string(const LinearSolver solver)
    {
      switch (solver)
        {
          case LinearSolver::direct:
            return "direct";
          case LinearSolver::umfpack:
            return "umfpack";
          case LinearSolver::cg_amg:
            return "cg-amg";
        }
      return "unknown";
    }



    std::string
    to_string(const PairPlacement placement)
    {
      switch (placement)
        {
          case PairPlacement::greville:
            return "greville";
          case PairPlacement::knots:
            return "knots";
          case PairPlacement::gauss:
            return "gauss";
        }
      return "unknown";
    }
  } // namespace discretization
} // namespace igabde
