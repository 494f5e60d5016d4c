#ifndef igabde_elasticity_stress_measures_h
#define igabde_elasticity_stress_measures_h

#include <igabde/elasticity/material.h>

#include <deal.II/base/symmetric_tensor.h>

namespace igabde
{
  namespace elasticity
  {
    using namespace dealii;

    /**
     * @brief The out-of-plane normal stress sigma_zz that goes with the
     * in-plane stress @p sigma: nu (sigma_xx + sigma_yy) in plane strain
     * (eps_zz = 0), 0 in plane stress and in 3D (where sigma holds it).
     *
     * @param sigma Cauchy stress (Pa), in-plane part in 2D.
     * @param material Its Poisson ratio and plane model are used.
     */
    template <int dim>
    double
    out_of_plane_stress(const SymmetricTensor<2, dim> &sigma,
                        const IsotropicMaterial<dim>  &material);

    /**
     * @brief Von Mises equivalent stress sqrt(3/2 s : s), s the deviator of
     * the full 3x3 stress: in 2D the in-plane @p sigma completed by
     * out_of_plane_stress() (plane strain: nu (sigma_xx + sigma_yy), plane
     * stress: 0).
     *
     * @param sigma Cauchy stress (Pa).
     * @param material Its Poisson ratio and plane model are used in 2D.
     * @return The von Mises stress (Pa).
     */
    template <int dim>
    double
    von_mises(const SymmetricTensor<2, dim> &sigma,
              const IsotropicMaterial<dim>  &material);

    /**
     * @brief sigma = C : eps for the isotropic @p material.
     */
    template <int dim>
    SymmetricTensor<2, dim>
    stress(const SymmetricTensor<2, dim> &strain,
           const IsotropicMaterial<dim>  &material);
  } // namespace elasticity
} // namespace igabde

#endif
