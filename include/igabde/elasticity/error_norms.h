#ifndef igabde_elasticity_error_norms_h
#define igabde_elasticity_error_norms_h

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <functional>

namespace igabde
{
  namespace elasticity
  {
    using namespace dealii;

    /**
     * @brief Exact solution of a verification scene, for error norms.
     */
    template <int dim>
    struct ExactSolution
    {
      /// Displacement (m) at a physical point.
      std::function<Tensor<1, dim>(const Point<dim> &)> displacement;
      /// Cauchy stress (Pa) at a physical point; may be empty.
      std::function<SymmetricTensor<2, dim>(const Point<dim> &)> stress;
    };

    /**
     * @brief Error norms against an exact solution, relative to the exact
     * solution's norms.
     */
    struct ErrorNorms
    {
      /// ||u - u_h||_L2 / ||u||_L2.
      double l2_relative = 0.;
      /// Energy-norm error / energy norm of the exact solution (NaN when
      /// the exact solution has no stress).
      double energy_relative = 0.;
      /// Measure (area/volume) of the body by the quadrature of the norms.
      double measure = 0.;
    };
  } // namespace elasticity
} // namespace igabde

#endif
