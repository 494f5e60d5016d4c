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
     * from (l0, d0) to (l1, d1) (load and displacement factors). When the
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
        std::function<std::vector<Vector<double>>(double, double)>;

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
       * displacement at (l1, d1). A solution that violates a contact
       * condition is not cut: it is an error.
       */
      Outcome
      advance(const unsigned int           step,
              const double                 l0,
              const double                 d0,
              const double                 l1,
              const double                 d1,
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
