#ifndef igabde_elasticity_error_norms_h
#define igabde_elasticity_error_norms_h

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

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
      /// The integrals the ratios come from: ||u - u_h||^2, ||u||^2 (L2)
      /// and the energy error and norm squared (zero without stress), so
      /// that the norms of several patches add (add()).
      double l2_error_squared = 0., l2_norm_squared = 0.,
             energy_error_squared = 0., energy_norm_squared = 0.;

      /// Adds the integrals of another part of the body and updates the
      /// ratios; @p with_stress: whether the energy ratio exists.
      void
      add(const ErrorNorms &part, const bool with_stress)
      {
        l2_error_squared += part.l2_error_squared;
        l2_norm_squared += part.l2_norm_squared;
        energy_error_squared += part.energy_error_squared;
        energy_norm_squared += part.energy_norm_squared;
        measure += part.measure;
        l2_relative =
          std::sqrt(l2_error_squared / std::max(l2_norm_squared, 1e-300));
        energy_relative = with_stress ?
                            std::sqrt(energy_error_squared /
                                      std::max(energy_norm_squared, 1e-300)) :
                            std::numeric_limits<double>::quiet_NaN();
      }
    };
  } // namespace elasticity
} // namespace igabde

#endif
