#ifndef igabde_contact_obstacle_h
#define igabde_contact_obstacle_h

#include <igabde/contact/contact_surface.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    using namespace dealii;

    /**
     * @brief A rigid, fixed obstacle: a contact surface without unknowns.
     * Its points carry no operator; pairs against it couple Body 1 only.
     */
    template <int dim>
    class Obstacle : public ContactSurface<dim>
    {
    public:
      bool
      deformable() const override;

      /// What the obstacle is, for the log: "rigid plane".
      virtual std::string
      kind() const = 0;

      /// No samples: an obstacle is always paired by closest point.
      const std::vector<discretization::SurfacePoint<dim>> &
      sample_points() const override;

    private:
      const std::vector<discretization::SurfacePoint<dim>> no_samples{};
    };



    /**
     * @brief The rigid plane through a point with a unit normal pointing
     * towards Body 1 (the plane's outward normal).
     */
    template <int dim>
    class RigidPlane : public Obstacle<dim>
    {
    public:
      /// @p normal need not be unit; it must not be zero.
      RigidPlane(const Point<dim> &point, const Tensor<1, dim> &normal);

      std::string
      description() const override;

      std::string
      kind() const override;

      /// The orthogonal projection of @p location on the plane.
      discretization::SurfacePoint<dim>
      closest_point(
        const Point<dim>                        &location,
        const discretization::SurfacePoint<dim> *nearest) const override;

    private:
      const Point<dim> point;
      Tensor<1, dim>   normal;
    };
  } // namespace contact
} // namespace igabde

#endif
