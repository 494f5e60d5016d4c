#ifndef igabde_elasticity_hyperelastic_h
#define igabde_elasticity_hyperelastic_h

#include <igabde/base/choice_names.h>

#include <igabde/elasticity/material.h>

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <string>

namespace igabde
{
  namespace elasticity
  {
    using namespace dealii;

    /** @brief How a body's strain is measured. */
    enum class Kinematics
    {
      /// Small strain and rotation: linear elasticity.
      small,
      /// Finite strain and rotation, total Lagrangian.
      finite
    };

    /** @brief The material law of a body at finite strain. */
    enum class MaterialModel
    {
      /// Hooke's law (small kinematics only).
      linear,
      /// W = lambda/2 (tr E)^2 + mu E : E, E = (C - I)/2.
      saint_venant_kirchhoff,
      /// W = mu/2 (I_1 - 3) - mu ln J + lambda/2 (ln J)^2.
      neo_hookean
    };

    /** @brief The names of each enum's values as the scene writes them. */
    inline constexpr base::ChoiceNames<Kinematics, 2> kinematics_names = {
      {{Kinematics::small, "small"}, {Kinematics::finite, "finite"}}};
    /** @copydoc kinematics_names */
    inline constexpr base::ChoiceNames<MaterialModel, 3> material_model_names =
      {{{MaterialModel::linear, "linear"},
        {MaterialModel::saint_venant_kirchhoff, "saint venant-kirchhoff"},
        {MaterialModel::neo_hookean, "neo-hookean"}}};

    /** @brief The name of each value as the scene writes it. */
    inline std::string
    to_string(const Kinematics kinematics)
    {
      return base::name_of(kinematics_names, kinematics);
    }
    /** @copydoc to_string(const Kinematics) */
    inline std::string
    to_string(const MaterialModel model)
    {
      return base::name_of(material_model_names, model);
    }

    /**
     * @brief A hyperelastic material in the reference configuration: the
     * strain energy per reference volume W(C) of the right Cauchy-Green
     * tensor C = F^T F, the second Piola-Kirchhoff stress S = 2 dW/dC and
     * its tangent dS/dE = 4 d^2W/dC^2 (E = (C - I)/2), with Lamé's lambda
     * and mu from Young's modulus and Poisson's ratio.
     *
     * - Saint Venant-Kirchhoff: W = lambda/2 (tr E)^2 + mu E : E,
     *   S = lambda tr(E) I + 2 mu E, dS/dE = lambda I x I + 2 mu II.
     * - Compressible neo-Hookean: W = mu/2 (tr C - 3) - mu ln J
     *   + lambda/2 (ln J)^2 with J = det F = sqrt(det C),
     *   S = mu (I - C^-1) + lambda ln J C^-1,
     *   dS/dE = lambda C^-1 x C^-1 + 2 (mu - lambda ln J) II_{C^-1},
     *   II_{C^-1, ijkl} = (C^-1_ik C^-1_jl + C^-1_il C^-1_jk) / 2.
     *
     * Both reduce to Hooke's law with the same lambda and mu at small
     * strain. In 2D the plane-strain forms are the 3D ones with E_33 = 0
     * (C_33 = 1: tr C - 3 becomes tr C - 2 for the in-plane C); plane
     * stress has S_33 = 0, which the Saint Venant-Kirchhoff law meets with
     * the reduced lambda* = 2 lambda mu / (lambda + 2 mu) exactly (its S is
     * linear in E); the neo-Hookean law would need C_33 solved at each point
     * and is not offered in plane stress (supports_plane_stress()).
     */
    template <int dim>
    class HyperelasticMaterial
    {
    public:
      /**
       * @brief The law @p model (not linear) with the constants of
       * @p material (its plane model in 2D).
       */
      HyperelasticMaterial(const MaterialModel           model,
                           const IsotropicMaterial<dim> &material);

      /// Whether @p model has a plane-stress form here.
      static bool
      supports_plane_stress(const MaterialModel model);

      /// The law.
      MaterialModel
      model() const;

      /// Lamé's lambda (the reduced one in plane stress) and mu.
      double
      lambda() const;
      double
      mu() const;

      /// W(C), per reference volume. C must have det C > 0.
      double
      energy(const SymmetricTensor<2, dim> &C) const;

      /// S(C) = 2 dW/dC.
      SymmetricTensor<2, dim>
      second_piola_kirchhoff(const SymmetricTensor<2, dim> &C) const;

      /// dS/dE (C) = 2 dS/dC, with the minor and major symmetries.
      SymmetricTensor<4, dim>
      tangent(const SymmetricTensor<2, dim> &C) const;

      /**
       * @brief In 2D, the out-of-plane S_33 that goes with the in-plane C:
       * in plane strain (C_33 = 1) lambda tr E for Saint Venant-Kirchhoff
       * and lambda ln J for neo-Hookean, 0 in plane stress; 0 in 3D (where
       * S holds it).
       */
      double
      out_of_plane_second_piola(const SymmetricTensor<2, dim> &C) const;

    private:
      MaterialModel law;
      double        lame_lambda;
      double        lame_mu;
      bool          plane_stress;
    };

    /// F = I + grad u.
    template <int dim>
    Tensor<2, dim>
    deformation_gradient(const Tensor<2, dim> &grad_u)
    {
      Tensor<2, dim> F = grad_u;
      for (unsigned int d = 0; d < dim; ++d)
        F[d][d] += 1.;
      return F;
    }

    /// C = F^T F.
    template <int dim>
    SymmetricTensor<2, dim>
    right_cauchy_green(const Tensor<2, dim> &F)
    {
      return symmetrize(transpose(F) * F);
    }

    /// The Cauchy stress sigma = F S F^T / det F.
    template <int dim>
    SymmetricTensor<2, dim>
    cauchy_stress(const Tensor<2, dim> &F, const SymmetricTensor<2, dim> &S)
    {
      return symmetrize(F * Tensor<2, dim>(S) * transpose(F)) / determinant(F);
    }
  } // namespace elasticity
} // namespace igabde

#endif
