// The names of the contact layer's enums (algorithm, path, pairing,
// condensation) as the scene writes them, apart from the code that uses
// them: the scene reader parses its selections with them without linking
// any solver (the fuzz target of contrib/fuzz).

#include <igabde/contact/condensation.h>
#include <igabde/contact/contact_solver.h>
#include <igabde/contact/pairing.h>
#include <igabde/contact/path_cost.h>

#include <string>

namespace igabde
{
  namespace contact
  {
    std::string
    to_string(const Algorithm algorithm)
    {
      switch (algorithm)
        {
          case Algorithm::bde:
            return "bde";
          case Algorithm::penalty:
            return "penalty";
          case Algorithm::augmented_lagrange:
            return "augmented-lagrange";
        }
      return "";
    }



    std::string
    to_string(const Path path)
    {
      switch (path)
        {
          case Path::condensed:
            return "condensed";
          case Path::full:
            return "full";
          case Path::automatic:
            return "auto";
        }
      return "";
    }



    std::string
    to_string(const Condensation condensation)
    {
      return condensation == Condensation::schur ? "schur" : "columns";
    }



    std::string
    to_string(const Pairing pairing)
    {
      switch (pairing)
        {
          case Pairing::node_to_surface:
            return "node-to-surface";
          case Pairing::node_to_node:
            return "node-to-node";
          case Pairing::weighted_gap:
            return "weighted-gap";
          case Pairing::weighted_gap_standard:
            return "weighted-gap-standard";
        }
      return "";
    }
  } // namespace contact
} // namespace igabde
