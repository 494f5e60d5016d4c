#include <igabde/elasticity/stress_measures.h>

#include <cmath>

namespace igabde
{
  namespace elasticity
  {
    template <int dim>
    double
    out_of_plane_stress(const SymmetricTensor<2, dim> &sigma,
                        const IsotropicMaterial<dim>  &material)
    {
      if (dim == 2 && material.plane_model == PlaneModel::plane_strain)
        return material.poisson_ratio * (sigma[0][0] + sigma[1][1]);
      return 0.;
    }



    template <int dim>
    double
    von_mises(const SymmetricTensor<2, dim> &sigma,
              const IsotropicMaterial<dim>  &material)
    {
      // The full 3x3 stress: in 2D the in-plane block and sigma_zz (the
      // shear stresses out of the plane vanish in both plane models).
      SymmetricTensor<2, 3> s;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          s[i][j] = sigma[i][j];
      if (dim == 2)
        s[2][2] = out_of_plane_stress(sigma, material);
      const SymmetricTensor<2, 3> d = deviator(s);
      return std::sqrt(1.5 * (d * d));
    }



    template <int dim>
    SymmetricTensor<2, dim>
    stress(const SymmetricTensor<2, dim> &strain,
           const IsotropicMaterial<dim>  &material)
    {
      return material.stiffness() * strain;
    }



    template double
    out_of_plane_stress(const SymmetricTensor<2, 2> &,
                        const IsotropicMaterial<2> &);
    template double
    out_of_plane_stress(const SymmetricTensor<2, 3> &,
                        const IsotropicMaterial<3> &);
    template double
    von_mises(const SymmetricTensor<2, 2> &, const IsotropicMaterial<2> &);
    template double
    von_mises(const SymmetricTensor<2, 3> &, const IsotropicMaterial<3> &);
    template SymmetricTensor<2, 2>
    stress(const SymmetricTensor<2, 2> &, const IsotropicMaterial<2> &);
    template SymmetricTensor<2, 3>
    stress(const SymmetricTensor<2, 3> &, const IsotropicMaterial<3> &);
  } // namespace elasticity
} // namespace igabde
