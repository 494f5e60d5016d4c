#ifndef igabde_elasticity_finite_output_h
#define igabde_elasticity_finite_output_h

#include <igabde/elasticity/hyperelastic.h>

#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace igabde
{
  namespace elasticity
  {
    using namespace dealii;

    /**
     * @brief The fields a body at finite strain writes at a point, after
     * its displacement: the Green-Lagrange strain E = (C - I)/2 as
     * strain_ij, the Cauchy stress sigma = F S F^T / det F as stress_ij
     * (the components i <= j of each), the von Mises stress of sigma,
     * det F and the largest principal stretch.
     */
    template <int dim>
    std::vector<std::string>
    finite_strain_field_names();

    /**
     * @brief The values of finite_strain_field_names() at the displacement
     * gradient @p grad_u of a body of the law @p law, written to
     * @p values (finite_strain_field_names().size() of them).
     *
     * In 2D (plane strain, F_33 = 1) the von Mises stress takes sigma_33 =
     * S_33 / det F (HyperelasticMaterial::out_of_plane_second_piola()) and
     * the principal stretches include the out-of-plane one, 1. Where
     * det F <= 0 (an inverted element; such a step is cut) the stresses are
     * not defined and are written as zero.
     */
    template <int dim>
    void
    finite_strain_fields(const Tensor<2, dim>            &grad_u,
                         const HyperelasticMaterial<dim> &law,
                         double                          *values);

    /**
     * @brief The largest principal stretch sqrt(lambda_max(C)) of the
     * deformation gradient @p F (in 2D with the out-of-plane stretch 1).
     */
    template <int dim>
    double
    largest_stretch(const Tensor<2, dim> &F);
  } // namespace elasticity
} // namespace igabde

#endif
