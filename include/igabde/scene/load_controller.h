#ifndef igabde_scene_load_controller_h
#define igabde_scene_load_controller_h

#include <igabde/contact/contact_stage.h>

#include <deal.II/base/timer.h>

#include <deal.II/lac/vector.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {
    using namespace dealii;

    /**
     * @brief Step cutting: takes a contact scene through the load increment
     * from the factors f0 to f1 (one per load history: load factor,
     * displacement factor, named histories). When the
     * contact solve of an increment does not converge, the increment is
     * halved (loads interpolated linearly) and both halves are solved, at
     * most max_cuts halvings deep.
     */
    template <int dim>
    class LoadController
    {
    public:
      /// Displacements of every body under the external loads alone at a
      /// load and displacement factor.
      using ExternalSolution =
        std::function<std::vector<Vector<double>>(const std::vector<double> &)>;

      /// What the increment took.
      struct Outcome
      {
        /// False when the increment could not be finished; @p last then
        /// holds the failed attempt.
        bool success = false;
        /// The last contact solve.
        contact::StepResult<dim> last;
        /// Iterations of all contact solves, failed ones included.
        unsigned int iterations = 0;
        /// Contact solves (1 + 2 per halving that succeeded).
        unsigned int contact_solves = 0;
        /// Halvings done.
        unsigned int cuts = 0;
      };

      /// @p context prefixes error messages (the scene file).
      LoadController(contact::ContactStage<dim> &stage,
                     const ExternalSolution     &external,
                     const unsigned int          max_cuts,
                     const std::string          &context,
                     std::ostream               &log);

      /**
       * @brief Solves the increment; on success @p u holds the total
       * displacement at the factors @p f1. A solution that violates a contact
       * condition is not cut: it is an error.
       */
      Outcome
      advance(const unsigned int           step,
              const std::vector<double>   &f0,
              const std::vector<double>   &f1,
              std::vector<Vector<double>> &u,
              TimerOutput                 &timer);

    private:
      contact::ContactStage<dim> &stage;
      const ExternalSolution      external;
      const unsigned int          max_cuts;
      const std::string           context;
      std::ostream               &log;
    };
  } // namespace scene
} // namespace igabde

#endif
