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
                                 const std::vector<double>   &f0,
                                 const std::vector<double>   &f1,
                                 std::vector<Vector<double>> &u,
                                 TimerOutput                 &timer)
    {
      Outcome outcome;
      // Targets still to reach, the next one last, with their depth: a
      // failed target at depth k is replaced by the midpoint and itself,
      // both at depth k + 1. A target is the factor of every load history.
      std::vector<std::pair<std::vector<double>, unsigned int>> targets = {
        {f1, 0}};
      std::vector<double> f = f0;
      f.resize(f1.size(), 0.);
      // A load no contact can balance: no step cut helps (the loads contact
      // can balance form a convex cone; with the last step's load and f1's
      // in it, every load between is).
      const std::string unbalanced = stage.unbalanceable_load(f1);
      AssertThrow(unbalanced.empty(),
                  base::ExcInput(context + ": load step " +
                                 std::to_string(step) + ": " + unbalanced));
      while (!targets.empty())
        {
          const auto [ft, depth] = targets.back();
          const auto state       = stage.save_state();
          u                      = external(ft);
          outcome.last           = stage.solve_step(ft, u, timer);
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
              f = ft;
              continue;
            }
          stage.restore_state(state);
          if (depth >= max_cuts || !outcome.last.advice.empty())
            return outcome;
          log << "  contact solve did not converge: halving the increment "
                 "(cut "
              << depth + 1 << " of at most " << max_cuts << ")" << std::endl;
          ++outcome.cuts;
          targets.back().second = depth + 1;
          std::vector<double> middle(ft.size());
          for (unsigned int h = 0; h < ft.size(); ++h)
            middle[h] = 0.5 * (f[h] + ft[h]);
          targets.emplace_back(middle, depth + 1);
        }
      outcome.success = true;
      return outcome;
    }



    template class LoadController<2>;
    template class LoadController<3>;
  } // namespace scene
} // namespace igabde
