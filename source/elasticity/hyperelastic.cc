#include <igabde/base/utilities.h>

#include <igabde/elasticity/assembly.h>
#include <igabde/elasticity/hyperelastic.h>

#include <cmath>

namespace igabde
{
  namespace elasticity
  {
    template <int dim>
    HyperelasticMaterial<dim>::HyperelasticMaterial(
      const MaterialModel           model,
      const IsotropicMaterial<dim> &material)
      : law(model)
      , plane_stress(dim == 2 &&
                     material.plane_model == PlaneModel::plane_stress)
    {
      AssertThrow(model != MaterialModel::linear,
                  ExcMessage("HyperelasticMaterial: the linear law has no "
                             "finite-strain form."));
      AssertThrow(dim == 3 ||
                    material.plane_model == PlaneModel::plane_strain ||
                    supports_plane_stress(model),
                  ExcMessage("HyperelasticMaterial: the " + to_string(model) +
                             " law has no plane-stress form here."));
      std::tie(lame_lambda, lame_mu) = lame_parameters(material);
    }



    template <int dim>
    bool
    HyperelasticMaterial<dim>::supports_plane_stress(const MaterialModel model)
    {
      return model == MaterialModel::saint_venant_kirchhoff;
    }



    template <int dim>
    MaterialModel
    HyperelasticMaterial<dim>::model() const
    {
      return law;
    }



    template <int dim>
    double
    HyperelasticMaterial<dim>::lambda() const
    {
      return lame_lambda;
    }



    template <int dim>
    double
    HyperelasticMaterial<dim>::mu() const
    {
      return lame_mu;
    }



    template <int dim>
    double
    HyperelasticMaterial<dim>::energy(const SymmetricTensor<2, dim> &C) const
    {
      if (law == MaterialModel::saint_venant_kirchhoff)
        {
          const SymmetricTensor<2, dim> E =
            0.5 * (C - unit_symmetric_tensor<dim>());
          return 0.5 * lame_lambda * trace(E) * trace(E) + lame_mu * (E * E);
        }
      // In 2D the out-of-plane stretch is 1: tr C - 3 = tr C_2D - 2.
      const double ln_J = 0.5 * std::log(determinant(C));
      return 0.5 * lame_mu * (trace(C) - dim) - lame_mu * ln_J +
             0.5 * lame_lambda * ln_J * ln_J;
    }



    template <int dim>
    SymmetricTensor<2, dim>
    HyperelasticMaterial<dim>::second_piola_kirchhoff(
      const SymmetricTensor<2, dim> &C) const
    {
      const SymmetricTensor<2, dim> I = unit_symmetric_tensor<dim>();
      if (law == MaterialModel::saint_venant_kirchhoff)
        {
          const SymmetricTensor<2, dim> E = 0.5 * (C - I);
          return lame_lambda * trace(E) * I + 2. * lame_mu * E;
        }
      const SymmetricTensor<2, dim> C_inv = invert(C);
      const double                  ln_J  = 0.5 * std::log(determinant(C));
      return lame_mu * (I - C_inv) + lame_lambda * ln_J * C_inv;
    }



    template <int dim>
    SymmetricTensor<4, dim>
    HyperelasticMaterial<dim>::tangent(const SymmetricTensor<2, dim> &C) const
    {
      if (law == MaterialModel::saint_venant_kirchhoff)
        return lame_lambda * outer_product(unit_symmetric_tensor<dim>(),
                                           unit_symmetric_tensor<dim>()) +
               2. * lame_mu * identity_tensor<dim>();
      const SymmetricTensor<2, dim> C_inv = invert(C);
      const double                  ln_J  = 0.5 * std::log(determinant(C));
      SymmetricTensor<4, dim>       D;
      const double                  a = 2. * (lame_mu - lame_lambda * ln_J);
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int l = k; l < dim; ++l)
              D[i][j][k][l] =
                lame_lambda * C_inv[i][j] * C_inv[k][l] +
                a * 0.5 *
                  (C_inv[i][k] * C_inv[j][l] + C_inv[i][l] * C_inv[j][k]);
      return D;
    }



    template <int dim>
    double
    HyperelasticMaterial<dim>::out_of_plane_second_piola(
      const SymmetricTensor<2, dim> &C) const
    {
      if (dim == 3 || plane_stress)
        return 0.;
      if (law == MaterialModel::saint_venant_kirchhoff)
        return lame_lambda * 0.5 * (trace(C) - dim);
      return lame_lambda * 0.5 * std::log(determinant(C));
    }



    template class HyperelasticMaterial<2>;
    template class HyperelasticMaterial<3>;
  } // namespace elasticity
} // namespace igabde
