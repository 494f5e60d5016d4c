#ifndef igabde_elasticity_material_h
#define igabde_elasticity_material_h

#include <igabde/base/choice_names.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <string>

namespace igabde
{
  namespace elasticity
  {
    using namespace dealii;

    /**
     * @brief The 2D kinematic assumption; ignored in 3D.
     */
    enum class PlaneModel
    {
      plane_strain,
      plane_stress
    };

    /** @brief The names of PlaneModel as the scene writes them. */
    inline constexpr base::ChoiceNames<PlaneModel, 2> plane_model_names = {
      {{PlaneModel::plane_strain, "plane strain"},
       {PlaneModel::plane_stress, "plane stress"}}};

    /** @brief "plane strain" or "plane stress", as the scene writes it. */
    inline std::string
    to_string(const PlaneModel model)
    {
      return base::name_of(plane_model_names, model);
    }

    /**
     * @brief Isotropic linear elastic material.
     */
    template <int dim>
    struct IsotropicMaterial
    {
      /// Young's modulus (Pa).
      double youngs_modulus = 1.0;
      /// Poisson's ratio (-), -1 < nu < 0.5.
      double poisson_ratio = 0.3;
      /// Plane strain or plane stress (2D only).
      PlaneModel plane_model = PlaneModel::plane_strain;

      /**
       * @brief Throws a user-facing error naming @p where when the constants
       * are not physical (E <= 0, nu outside (-1, 0.5)).
       */
      void
      validate(const std::string &where) const;

      /**
       * @brief The fourth-order stiffness C with sigma = C : eps.
       */
      SymmetricTensor<4, dim>
      stiffness() const;

      /**
       * @brief The compliance C^-1 with eps = C^-1 : sigma (in-plane part).
       */
      SymmetricTensor<4, dim>
      compliance() const;
    };
  } // namespace elasticity
} // namespace igabde

#endif
