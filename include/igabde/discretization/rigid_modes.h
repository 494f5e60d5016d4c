#ifndef igabde_discretization_rigid_modes_h
#define igabde_discretization_rigid_modes_h

#include <deal.II/base/point.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace discretization
  {
    using namespace dealii;

    /**
     * @brief The rigid motions a body's supports leave free, the pins that
     * remove them from a solve, and the rotations a face holds, with the
     * projectors that hold them (method.md, "Bodies held only through
     * contact").
     *
     * A value object over the unknowns of one body: their control point or
     * node locations, their components and which of them the supports
     * constrain. It knows nothing of the discretisation: the rigid modes
     * are evaluated at the locations, which is exact for NURBS and FE_Q
     * alike since both bases reproduce linear fields.
     *
     * The free modes are the null space of the pure modes (dim translations,
     * then the rotations about the centroid of the locations, scaled by the
     * largest distance from it) restricted to the constrained unknowns; they
     * are orthonormal in the pure modes' coefficients. hold() then moves the
     * free modes that constraints c_a^T u = 0 hold (a face whose rotation is
     * held) from the free to the held modes R_h, with their constraint
     * loads C_h and S = R_h^T C_h: P^T = I - C_h S^-1 R_h^T adds to a load
     * the moment reaction that balances it in the held modes (balance()),
     * P = I - R_h S^-T C_h^T adds to a displacement the held rigid motion
     * that meets the constraints (fix()).
     */
    template <int dim>
    class RigidModes
    {
    public:
      /// No unknowns, no modes.
      RigidModes() = default;

      /**
       * @brief The free rigid modes of unknowns at @p locations with
       * components @p components (unknown i sits at locations[i] and is
       * component components[i]) that @p constraints leaves free.
       */
      RigidModes(const std::vector<Point<dim>>   &locations,
                 const std::vector<unsigned int> &components,
                 const AffineConstraints<double> &constraints);

      /// The free modes as displacement vectors (zero where constrained).
      const std::vector<Vector<double>> &
      free_modes() const;

      /// Their names ("translation y", "rotation z (combined)", ...).
      const std::vector<std::string> &
      free_mode_names() const;

      /**
       * @brief Whether the translation along component @p c lies in the
       * span of the free modes: a body whose resultant along c then
       * balances its load through contact alone.
       */
      bool
      free_translation(const unsigned int c) const;

      /**
       * @brief One unknown per free mode at which the free modes are
       * independent, chosen by column-pivoted QR of the free modes with
       * unknown i's column scaled by @p weights[i] (larger: preferred).
       * Constraining them to zero removes every free mode from a solve.
       */
      std::vector<types::global_dof_index>
      pins(const std::vector<double> &weights) const;

      /**
       * @brief Holds the free modes that the constraints @p c[a]^T u = 0
       * hold (one per rotation axis of a face: 1 in 2D, 3 in 3D), @p J
       * the moments of the loads c_a about the axes (J(a, b): moment of
       * c_a about axis b). The modes that the constraints do not see stay
       * free; a rotation the supports hold already has no free part.
       */
      void
      hold(const std::vector<Vector<double>> &c, const FullMatrix<double> &J);

      /// The held modes R_h (empty before hold() or when none is held).
      const std::vector<Vector<double>> &
      held_modes() const;

      /// Their constraint loads C_h (the combinations of the c_a of hold()).
      const std::vector<Vector<double>> &
      held_loads() const;

      /// S^-1 = (R_h^T C_h)^-1.
      const FullMatrix<double> &
      held_inverse() const;

      /// The held modes' names.
      const std::vector<std::string> &
      held_mode_names() const;

      /**
       * @brief S^-1 R_h^T f: the multipliers of the loads C_h that the
       * held modes' reaction removes from @p f.
       */
      Vector<double>
      held_multipliers(const Vector<double> &f) const;

      /// f <- P^T f = f - C_h S^-1 R_h^T f: the held modes' reactions added.
      void
      balance(Vector<double> &f) const;

      /// u <- P u = u - R_h S^-T C_h^T u: the held modes' constraints met.
      void
      fix(Vector<double> &u) const;

      /**
       * @brief The moment of the reaction -C_h S^-1 R_h^T f of the held
       * modes to the load @p f (one value about z in 2D, three in 3D).
       */
      std::vector<double>
      held_moment(const Vector<double> &f) const;

      /// The centroid of the locations: the rotations' centre.
      const Point<dim> &
      centre() const;

      /// The largest distance of a location from centre(): the rotations'
      /// scale.
      double
      size() const;

    private:
      /// Value at unknown @p i of pure mode @p mode (translations, then
      /// rotations).
      double
      pure_mode_value(const unsigned int mode, const std::size_t i) const;

      /// The mode with @p coefficients on the pure modes (zero at
      /// constrained unknowns) and its name: the dominant pure mode,
      /// "(combined)" when it is not pure.
      std::pair<Vector<double>, std::string>
      mode(const std::vector<double> &coefficients) const;

      /// Rebuilds free and free_names from free_coefficients.
      void
      build_free_modes();

      std::vector<Point<dim>>   locations;
      std::vector<unsigned int> components;
      std::vector<bool>         constrained;
      Point<dim>                mode_centre;
      double                    mode_size = 1.;

      std::vector<std::vector<double>> free_coefficients;
      std::vector<Vector<double>>      free;
      std::vector<std::string>         free_names;

      std::vector<Vector<double>>      held;
      std::vector<Vector<double>>      loads;
      FullMatrix<double>               inverse;
      std::vector<std::string>         held_names;
      std::vector<std::vector<double>> moments;
    };
  } // namespace discretization
} // namespace igabde

#endif
