#include <igabde/base/utilities.h>

#include <igabde/scene/load_controller.h>

#include <tuple>

namespace igabde
{
  namespace scene
  {
    template <int dim>
    LoadController<dim>::LoadController(contact::ContactStage<dim> &stage,
                                        const ExternalSolution     &external,
                                        const unsigned int          max_cuts,
                                        const std::string          &context,
                                        std::ostream               &log)
      : stage(stage)
      , external(external)
      , max_cuts(max_cuts)
      , context(context)
      , log(log)
    {}



    template <int dim>
    typename LoadController<dim>::Outcome
    LoadController<dim>::advance(const unsigned int           step,
                                 const double                 l0,
                                 const double                 d0,
                                 const double                 l1,
                                 const double                 d1,
                                 std::vector<Vector<double>> &u,
                                 TimerOutput                 &timer)
    {
      Outcome outcome;
      // Targets still to reach, the next one last, with their depth: a
      // failed target at depth k is replaced by the midpoint and itself,
      // both at depth k + 1.
      std::vector<std::tuple<double, double, unsigned int>> targets = {
        {l1, d1, 0}};
      double l = l0, d = d0;
      while (!targets.empty())
        {
          const auto [lt, dt, depth] = targets.back();
          const auto state           = stage.save_state();
          u                          = external(lt, dt);
          outcome.last               = stage.solve_step(lt, u, timer);
          outcome.iterations += outcome.last.iterations;
          ++outcome.contact_solves;
          if (outcome.last.converged)
            {
              AssertThrow(outcome.last.conditions_passed,
                          base::ExcInput(
                            context + ": load step " + std::to_string(step) +
                            ": the contact solution violates a contact "
                            "condition: " +
                            outcome.last.first_violation));
              targets.pop_back();
              l = lt;
              d = dt;
              continue;
            }
          stage.restore_state(state);
          if (depth >= max_cuts)
            return outcome;
          log << "  contact solve did not converge: halving the increment "
                 "(cut "
              << depth + 1 << " of at most " << max_cuts << ")" << std::endl;
          ++outcome.cuts;
          std::get<2>(targets.back()) = depth + 1;
          targets.emplace_back(0.5 * (l + lt), 0.5 * (d + dt), depth + 1);
        }
      outcome.success = true;
      return outcome;
    }



    template class LoadController<2>;
    template class LoadController<3>;
  } // namespace scene
} // namespace igabde
