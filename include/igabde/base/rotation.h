#ifndef igabde_base_rotation_h
#define igabde_base_rotation_h

#include <deal.II/base/tensor.h>

#include <cmath>

namespace igabde
{
  namespace base
  {
    using namespace dealii;

    /**
     * @brief The rotation by the rotation vector @p theta, exactly: in 2D
     * by the angle theta[2] about z, in 3D by Rodrigues' formula
     * R = I + sin(a) K + (1 - cos(a)) K^2, K the cross product with the
     * unit axis, a = |theta|.
     */
    template <int dim>
    Tensor<2, dim>
    exact_rotation(const Tensor<1, 3> &theta)
    {
      Tensor<2, dim> R;
      if constexpr (dim == 2)
        {
          const double angle = theta[2];
          R[0][0]            = std::cos(angle);
          R[0][1]            = -std::sin(angle);
          R[1][0]            = std::sin(angle);
          R[1][1]            = std::cos(angle);
        }
      else
        {
          Tensor<1, 3> axis  = theta;
          const double angle = axis.norm();
          for (unsigned int d = 0; d < 3; ++d)
            R[d][d] = 1.;
          if (angle > 0.)
            {
              axis /= angle;
              Tensor<2, 3> K;
              K[0][1] = -axis[2];
              K[0][2] = axis[1];
              K[1][0] = axis[2];
              K[1][2] = -axis[0];
              K[2][0] = -axis[1];
              K[2][1] = axis[0];
              R += std::sin(angle) * K + (1. - std::cos(angle)) * K * K;
            }
        }
      return R;
    }
  } // namespace base
} // namespace igabde

#endif
