#include <igabde/elasticity/material.h>

#include <deal.II/base/exceptions.h>

namespace igabde
{
  namespace elasticity
  {
    template <int dim>
    void
    IsotropicMaterial<dim>::validate(const std::string &where) const
    {
      AssertThrow(youngs_modulus > 0.,
                  ExcMessage(where +
                             ": Young's modulus must be positive, got " +
                             std::to_string(youngs_modulus) +
                             "; set it to a value > 0."));
      AssertThrow(poisson_ratio > -1. && poisson_ratio < 0.5,
                  ExcMessage(where +
                             ": Poisson's ratio must lie in (-1, 0.5), got " +
                             std::to_string(poisson_ratio) +
                             "; nearly incompressible materials need "
                             "nu < 0.5 (e.g. 0.49)."));
    }



    template <int dim>
    SymmetricTensor<4, dim>
    IsotropicMaterial<dim>::stiffness() const
    {
      const double E      = youngs_modulus;
      const double nu     = poisson_ratio;
      double       lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
      const double mu     = E / (2. * (1. + nu));
      // Plane stress in 2D: the out-of-plane stress vanishes, which replaces
      // lambda by 2 mu lambda / (lambda + 2 mu).
      if (dim == 2 && plane_model == PlaneModel::plane_stress)
        lambda = 2. * mu * lambda / (lambda + 2. * mu);

      SymmetricTensor<4, dim> C;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int l = 0; l < dim; ++l)
              C[i][j][k][l] = lambda * (i == j) * (k == l) +
                              mu * ((i == k) * (j == l) + (i == l) * (j == k));
      return C;
    }



    template <int dim>
    SymmetricTensor<4, dim>
    IsotropicMaterial<dim>::compliance() const
    {
      return invert(stiffness());
    }



    template struct IsotropicMaterial<2>;
    template struct IsotropicMaterial<3>;
  } // namespace elasticity
} // namespace igabde
