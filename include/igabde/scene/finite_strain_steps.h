#ifndef igabde_scene_finite_strain_steps_h
#define igabde_scene_finite_strain_steps_h

#include <igabde/discretization/body.h>
#include <igabde/discretization/finite_strain_solver.h>

#include <igabde/elasticity/hyperelastic.h>

#include <deal.II/lac/vector.h>

#include <ostream>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {
    using namespace dealii;

    /** @brief What a finite-strain load increment took. */
    struct FiniteStrainOutcome
    {
      /// False when the increment could not be finished even after
      /// max_cuts halvings; the displacement is then the start's.
      bool success = false;
      /// Newton iterations of every solve, failed ones included.
      unsigned int iterations = 0;
      /// Newton solves (1 + 2 per halving that succeeded, and the failed).
      unsigned int solves = 0;
      /// Halvings done.
      unsigned int cuts = 0;
      /// The relative residual before each iteration and at the end of the
      /// last solve.
      std::vector<double> residuals;
      /// The smallest det F at the end.
      double min_J = 0.;
      /// Why the last solve failed (empty on success).
      std::string diagnosis;
    };

    /**
     * @brief Takes a body at finite strain through the load increment from
     * the history factors @p f0 to @p f1 (load factor, displacement factor,
     * named histories): Newton's method (solve_finite_strain()) from the
     * displacement @p u at @p f0 to the equilibrium at @p f1. When a solve
     * does not converge (a diverging or stalled Newton, or an element that
     * inverts) the increment is halved, the factors interpolated linearly,
     * and both halves are solved, at most @p max_cuts halvings deep; each
     * cut is logged to @p log (nullptr: silent) with its reason. On
     * success @p u is the equilibrium at @p f1; otherwise it is left at
     * the start.
     */
    template <int dim>
    FiniteStrainOutcome
    advance_finite_strain(const discretization::Body<dim>             &body,
                          const elasticity::HyperelasticMaterial<dim> &law,
                          const std::vector<double>                   &f0,
                          const std::vector<double>                   &f1,
                          const discretization::NewtonSettings        &settings,
                          const unsigned int                           max_cuts,
                          Vector<double>                              &u,
                          std::ostream                                *log);
  } // namespace scene
} // namespace igabde

#endif
