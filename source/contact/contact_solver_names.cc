// The names create_contact_solver() knows, apart from the solvers
// themselves: the scene reader checks Contact/Algorithm against them
// without linking any solver (the fuzz target of contrib/fuzz).

#include <igabde/contact/contact_solver.h>

#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    std::vector<std::string>
    available_contact_solvers()
    {
      return {"bde", "penalty", "augmented-lagrange"};
    }
  } // namespace contact
} // namespace igabde
