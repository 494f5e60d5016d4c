#ifndef igabde_elasticity_body_force_h
#define igabde_elasticity_body_force_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <functional>

namespace igabde
{
  namespace elasticity
  {
    using namespace dealii;

    /**
     * @brief A body force per unit volume (N/m^3): the constant vector, or
     * where @p field is set, that function of the physical point.
     */
    template <int dim>
    struct BodyForce
    {
      Tensor<1, dim>                                    constant;
      std::function<Tensor<1, dim>(const Point<dim> &)> field;

      /// Whether there is no body force at all.
      bool
      zero() const
      {
        return !field && constant.norm() == 0.;
      }
    };
  } // namespace elasticity
} // namespace igabde

#endif
