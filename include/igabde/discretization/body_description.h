#ifndef igabde_discretization_body_description_h
#define igabde_discretization_body_description_h

#include <igabde/base/rotation.h>

#include <igabde/nurbs/geometry_file.h>
#include <igabde/nurbs/nurbs_patch.h>

#include <igabde/discretization/settings.h>

#include <igabde/elasticity/hyperelastic.h>
#include <igabde/elasticity/material.h>

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace igabde
{
  namespace discretization
  {
    using namespace dealii;

    /**
     * @brief The faces of a body: face f of patch p is p * 2 dim + f (the
     * scene's 'p.f'); a single-patch body's faces are 0..2 dim - 1.
     */
    template <int dim>
    constexpr unsigned int
    face_id(const unsigned int patch, const unsigned int face)
    {
      return patch * 2 * dim + face;
    }

    /// The patch of the face @p id.
    template <int dim>
    constexpr unsigned int
    patch_of_face(const unsigned int id)
    {
      return id / (2 * dim);
    }

    /// The face number 0..2 dim - 1 within its patch of the face @p id.
    template <int dim>
    constexpr unsigned int
    local_face(const unsigned int id)
    {
      return id % (2 * dim);
    }



    /**
     * @brief Prescribed displacement on a patch face: the selected components
     * take the value @p value times the step's displacement factor.
     */
    template <int dim>
    struct DirichletCondition
    {
      /// Patch face (deal.II colorized boundary id 0..2dim-1).
      types::boundary_id boundary_id = 0;
      /// Which displacement components are prescribed.
      std::array<bool, dim> components{};
      /// Prescribed value per component (m), constant on the face.
      Tensor<1, dim> value;
      /// Where set, the prescribed value of that component as a function
      /// of the point (m) instead of value[c].
      std::array<std::function<double(const Point<dim> &)>, dim> field;
      /// Load history scaling the value (1: the displacement factors).
      unsigned int history = 1;
    };

    /// Traction t(x, n) in Pa, given the point and the outward unit normal.
    template <int dim>
    using TractionFunction =
      std::function<Tensor<1, dim>(const Point<dim> &, const Tensor<1, dim> &)>;

    /**
     * @brief Traction on a patch face, scaled by the step's load factor.
     */
    template <int dim>
    struct NeumannCondition
    {
      /// Patch face (deal.II colorized boundary id 0..2dim-1).
      types::boundary_id boundary_id = 0;
      /// Traction as a function of the physical point and outward normal.
      TractionFunction<dim> traction;
      /// Load history scaling the traction (0: the load factors).
      unsigned int history = 0;
      /// The pressure p (Pa) of a 'pressure p' entry (traction -p n): on a
      /// body at finite strain a follower load on the current surface
      /// (Body::add_follower_pressure()) instead of @p traction.
      std::optional<double> pressure;
    };

    /**
     * @brief A point force at a physical point, scaled by the load factor.
     */
    template <int dim>
    struct PointLoad
    {
      /// Where the force acts (m); must lie in the body.
      Point<dim> location;
      /// Force (N, or N/m in 2D).
      Tensor<1, dim> force;
      /// Load history scaling the force (0: the load factors).
      unsigned int history = 0;
    };

    /**
     * @brief Components prescribed at one node of the body (a patch corner
     * for NURBS, a mesh node for FE_Q).
     */
    template <int dim>
    struct PointSupport
    {
      /// Where (m).
      Point<dim> location;
      /// Which displacement components are held.
      std::array<bool, dim> components{};
      /// Their values (m) at factor 1 (zero: held in place).
      Tensor<1, dim> value;
      /// Load history scaling the values (1: the displacement factors).
      unsigned int history = 1;
    };

    /**
     * @brief A moment on a patch face about its centroid, spread as a
     * distributing coupling spreads it (Body::face_rotation_loads()),
     * scaled by the load factor.
     */
    struct FaceMoment
    {
      /// Patch face (deal.II colorized boundary id 0..2dim-1).
      types::boundary_id boundary_id = 0;
      /// Components about the axes (z only in 2D; x, y, z in 3D), N m.
      std::vector<double> moment;
      /// Load history scaling the moment (0: the load factors).
      unsigned int history = 0;
    };

    /**
     * @brief A patch face moved rigidly, as a kinematic coupling moves it
     * (Body n/Face motions): u = d + r x (x - c) on the face. The motion
     * itself is the support dirichlet[condition] of the body (its
     * components as functions of the point, exact in the discrete space
     * because a linear field is); this record keeps what its reaction
     * needs (Body::face_motion_reaction()).
     */
    template <int dim>
    struct FaceMotion
    {
      /// Patch face (deal.II colorized boundary id 0..2dim-1).
      types::boundary_id boundary_id = 0;
      /// The face's centroid c: the reference point of the motion and of
      /// the reaction's moment.
      Point<dim> centre;
      /// Index of the motion's support in BodyDescription::dirichlet.
      unsigned int condition = 0;
      /// The centroid's displacement d (m) and the rotation vector r (rad;
      /// one component, about z, in 2D) at factor 1. At finite strain the
      /// face moves by u = f d + (R(f r) - I)(x - c) at the factor f of
      /// its history, R the exact rotation (Body::prescribed_values()).
      Tensor<1, dim>      displacement;
      std::vector<double> rotation;

      /**
       * @brief The rotation by the rotation vector @p f r, exactly: in 3D
       * by Rodrigues' formula R = I + sin(a) K + (1 - cos(a)) K^2, K the
       * cross product with the unit axis, a the angle f |r|.
       */
      Tensor<2, dim>
      exact_rotation(const double f) const
      {
        Tensor<1, 3> theta;
        if constexpr (dim == 2)
          theta[2] = f * rotation.at(0);
        else
          for (unsigned int d = 0; d < 3; ++d)
            theta[d] = f * rotation.at(d);
        return base::exact_rotation<dim>(theta);
      }
    };

    /**
     * @brief Everything the scene says about one deformable body,
     * independent of how it is discretised.
     */
    template <int dim>
    struct BodyDescription
    {
      /// Name used in output files and messages.
      std::string name = "body";
      /// What was read differently from how the geometry file states it
      /// (nurbs::MultiPatchGeometry::notes), for the log.
      std::vector<std::string> notes;
      /// Exact geometry as a NURBS patch (coarsest description); of a
      /// multi-patch body, patch 0.
      nurbs::NurbsPatch<dim> geometry;
      /// Patches 1, 2, ... of a multi-patch body (empty: one patch).
      std::vector<nurbs::NurbsPatch<dim>> more_patches;
      /// The interfaces where the patches are glued (patch indices as
      /// above, faces 0..2 dim - 1).
      std::vector<nurbs::PatchInterface> interfaces;

      /// Number of patches.
      unsigned int
      n_patches() const
      {
        return 1 + more_patches.size();
      }

      /// Patch @p p.
      const nurbs::NurbsPatch<dim> &
      patch(const unsigned int p) const
      {
        return p == 0 ? geometry : more_patches.at(p - 1);
      }
      /// Material constants (and the plane model).
      elasticity::IsotropicMaterial<dim> material;
      /// Small strain (Hooke's law on the linear path) or finite strain
      /// (total Lagrangian, the law @p model, Newton's method).
      elasticity::Kinematics kinematics = elasticity::Kinematics::small;
      /// The finite-strain law (linear at small strain).
      elasticity::MaterialModel model = elasticity::MaterialModel::linear;
      /// Supports.
      std::vector<DirichletCondition<dim>> dirichlet;
      /// Point supports.
      std::vector<PointSupport<dim>> point_supports;
      /// The patch face whose mean rotation is held at zero (a
      /// distributing coupling's rotation constraint; -1: none).
      int hold_rotation_face = -1;
      /// Tractions.
      std::vector<NeumannCondition<dim>> tractions;
      /// Point loads.
      std::vector<PointLoad<dim>> point_loads;
      /// Moments on faces.
      std::vector<FaceMoment> moments;
      /// Faces moved rigidly (their motions are among the supports).
      std::vector<FaceMotion<dim>> face_motions;
      /// Body force per unit volume (N/m^3), on history 0.
      Tensor<1, dim> body_force;
      /// A body force that varies in space (N/m^3), on history 0; when set
      /// it replaces body_force.
      std::function<Tensor<1, dim>(const Point<dim> &)> body_force_field;

      /// Number of load histories the loads refer to: 2 (load and
      /// displacement factors) or more.
      unsigned int
      n_histories() const
      {
        unsigned int n = 2;
        for (const auto &d : dirichlet)
          n = std::max(n, d.history + 1);
        for (const auto &t : tractions)
          n = std::max(n, t.history + 1);
        for (const auto &p : point_loads)
          n = std::max(n, p.history + 1);
        for (const auto &m : moments)
          n = std::max(n, m.history + 1);
        for (const auto &p : point_supports)
          n = std::max(n, p.history + 1);
        return n;
      }

      /// Whether load history @p h loads or moves the body: a traction,
      /// point load or moment of it, a prescribed displacement of it that
      /// is not zero, or (history 0) a body force.
      bool
      acts_in_history(const unsigned int h) const
      {
        const auto moves = [](const auto &components, const auto &value) {
          for (unsigned int c = 0; c < dim; ++c)
            if (components[c] && value[c] != 0.)
              return true;
          return false;
        };
        for (const auto &d : dirichlet)
          if (d.history == h)
            for (unsigned int c = 0; c < dim; ++c)
              if (d.components[c] && (d.value[c] != 0. || d.field[c]))
                return true;
        for (const auto &p : point_supports)
          if (p.history == h && moves(p.components, p.value))
            return true;
        for (const auto &t : tractions)
          if (t.history == h)
            return true;
        for (const auto &p : point_loads)
          if (p.history == h)
            return true;
        for (const auto &m : moments)
          if (m.history == h)
            return true;
        return h == 0 &&
               (body_force.norm() > 0. || static_cast<bool>(body_force_field));
      }
    };
  } // namespace discretization
} // namespace igabde

#endif
