#include <igabde/scene/finite_strain_steps.h>

#include <algorithm>
#include <iomanip>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /// One increment f0 -> f1, halved up to @p depth times more.
      template <int dim>
      bool
      advance(const discretization::Body<dim>             &body,
              const elasticity::HyperelasticMaterial<dim> &law,
              const std::vector<double>                   &f0,
              const std::vector<double>                   &f1,
              const discretization::NewtonSettings        &settings,
              const unsigned int                           depth,
              Vector<double>                              &u,
              std::ostream                                *log,
              FiniteStrainOutcome                         &outcome)
      {
        const Vector<double>               start = u;
        const discretization::NewtonResult result =
          discretization::solve_finite_strain(body, law, f1, settings, u, log);
        ++outcome.solves;
        outcome.iterations += result.iterations;
        outcome.residuals = result.residuals;
        outcome.min_J     = result.min_J;
        if (result.converged)
          return true;
        outcome.diagnosis = result.diagnosis;
        u                 = start;
        if (depth == 0)
          return false;
        ++outcome.cuts;
        std::vector<double> middle(f0.size());
        for (unsigned int h = 0; h < f0.size(); ++h)
          middle[h] = 0.5 * (f0[h] + f1[h]);
        if (log != nullptr)
          *log << "    step cut: " << result.diagnosis
               << "; the increment is halved (load factor "
               << std::setprecision(6) << f0[0] << " -> " << middle[0] << " -> "
               << f1[0] << ")" << std::endl;
        return advance(body,
                       law,
                       f0,
                       middle,
                       settings,
                       depth - 1,
                       u,
                       log,
                       outcome) &&
               advance(body,
                       law,
                       middle,
                       f1,
                       settings,
                       depth - 1,
                       u,
                       log,
                       outcome);
      }
    } // namespace



    template <int dim>
    FiniteStrainOutcome
    advance_finite_strain(const discretization::Body<dim>             &body,
                          const elasticity::HyperelasticMaterial<dim> &law,
                          const std::vector<double>                   &f0,
                          const std::vector<double>                   &f1,
                          const discretization::NewtonSettings        &settings,
                          const unsigned int                           max_cuts,
                          Vector<double>                              &u,
                          std::ostream                                *log)
    {
      FiniteStrainOutcome  outcome;
      const Vector<double> start = u;
      outcome.success =
        advance(body, law, f0, f1, settings, max_cuts, u, log, outcome);
      if (outcome.success)
        outcome.diagnosis.clear();
      else
        u = start;
      return outcome;
    }



    template FiniteStrainOutcome
    advance_finite_strain(const discretization::Body<2> &,
                          const elasticity::HyperelasticMaterial<2> &,
                          const std::vector<double> &,
                          const std::vector<double> &,
                          const discretization::NewtonSettings &,
                          const unsigned int,
                          Vector<double> &,
                          std::ostream *);
    template FiniteStrainOutcome
    advance_finite_strain(const discretization::Body<3> &,
                          const elasticity::HyperelasticMaterial<3> &,
                          const std::vector<double> &,
                          const std::vector<double> &,
                          const discretization::NewtonSettings &,
                          const unsigned int,
                          Vector<double> &,
                          std::ostream *);
  } // namespace scene
} // namespace igabde
