#ifndef igabde_postprocess_exact_solutions_h
#define igabde_postprocess_exact_solutions_h

#include <igabde/elasticity/error_norms.h>
#include <igabde/elasticity/material.h>

namespace igabde
{
  namespace postprocess
  {
    using namespace dealii;

    /**
     * @brief Kirsch's solution: infinite plate with a circular hole of radius
     * @p a centred at the origin under remote tension @p T along x (2D;
     * plane strain or plane stress from @p material).
     */
    elasticity::ExactSolution<2>
    kirsch_solution(const double                            T,
                    const double                            a,
                    const elasticity::IsotropicMaterial<2> &material);

    /**
     * @brief Lame's solution: thick cylinder a <= r <= b about the z axis
     * under internal pressure @p p: in 2D plane strain or plane stress as
     * @p material's plane model says, in 3D with the ends held (w = 0,
     * plane strain).
     */
    template <int dim>
    elasticity::ExactSolution<dim>
    lame_solution(const double                              a,
                  const double                              b,
                  const double                              p,
                  const elasticity::IsotropicMaterial<dim> &material);
  } // namespace postprocess
} // namespace igabde

#endif
