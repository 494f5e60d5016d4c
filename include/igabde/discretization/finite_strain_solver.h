#ifndef igabde_discretization_finite_strain_solver_h
#define igabde_discretization_finite_strain_solver_h

#include <igabde/discretization/body.h>

#include <igabde/elasticity/hyperelastic.h>

#include <deal.II/lac/vector.h>

#include <ostream>
#include <string>
#include <vector>

namespace igabde
{
  namespace discretization
  {
    using namespace dealii;

    /** @brief When a finite-strain Newton solve stops. */
    struct NewtonSettings
    {
      /// ||R|| over the free unknowns, relative to the largest external
      /// load or internal force (reactions included) of the solve, at which
      /// the iteration has converged.
      double tolerance = 1e-10;
      /// Iterations before the solve gives up.
      unsigned int max_iterations = 25;
      /// Halvings of the step the line search may take.
      unsigned int max_halvings = 10;
      /// Whether a step that does not decrease ||R|| is halved (a
      /// backtracking line search on the residual norm); without it only a
      /// step that inverts an element is.
      bool line_search = false;
    };

    /** @brief What a finite-strain Newton solve did. */
    struct NewtonResult
    {
      bool converged = false;
      /// Newton iterations (tangent solves).
      unsigned int iterations = 0;
      /// The relative residual before each iteration and at the end.
      std::vector<double> residuals;
      /// The smallest det F of the last iterate.
      double min_J = 0.;
      /// Why it stopped without converging (empty when it converged).
      std::string diagnosis;
    };

    /**
     * @brief Equilibrium of @p body at finite strain with the law
     * @p material: the displacement @p u (in: the start, e.g. the previous
     * step's; out: the solution) with f_int(u) = f_ext(@p factors) on the
     * unknowns the supports leave free and u = the supports' values at
     * @p factors on the others.
     *
     * Newton's method on the residual R = f_int(u) - f_ext, each step
     * K_T du = -R solved on the unknowns the supports leave free with
     * du = g - u on the held ones (the first step moves the supports to
     * their values g and predicts the inside with them; a sparse LU,
     * UMFPACK). A step is halved while it inverts an element (det F <= 0)
     * and, with NewtonSettings::line_search once the supports are at g,
     * while it does not decrease ||R|| (backtracking line search). Each
     * iteration's relative residual and the observed rate log(r_k / r_k-1) /
     * log(r_k-1 / r_k-2) go to @p log (nullptr: silent). A body with free rigid
     * modes has a singular tangent and is refused. @p additional_load
     * (nullptr: none) joins f_ext (the contact forces of the last step,
     * held fixed in the contact solve's predictor).
     */
    template <int dim>
    NewtonResult
    solve_finite_strain(const Body<dim>                             &body,
                        const elasticity::HyperelasticMaterial<dim> &material,
                        const std::vector<double>                   &factors,
                        const NewtonSettings                        &settings,
                        Vector<double>                              &u,
                        std::ostream                                *log,
                        const Vector<double> *additional_load = nullptr);
  } // namespace discretization
} // namespace igabde

#endif
