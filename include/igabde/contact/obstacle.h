#ifndef igabde_contact_obstacle_h
#define igabde_contact_obstacle_h

#include <igabde/discretization/exact_surface.h>

#include <igabde/contact/contact_surface.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    using namespace dealii;

    /**
     * @brief One term of an obstacle's prescribed rigid motion: a
     * translation and a small (linearised) rotation about the obstacle's
     * pivot, both scaled by one history's factor.
     */
    template <int dim>
    struct RigidMotion
    {
      /// The index of the history in the step's factors.
      unsigned int history = 1;
      /// The translation (m).
      Tensor<1, dim> translation;
      /// The rotation (rad): about z in 2D (component 2 only), the
      /// rotation vector in 3D.
      Tensor<1, 3> rotation;
    };

    /**
     * @brief A rigid obstacle: a contact surface without unknowns, fixed or
     * moved rigidly. Its points carry no operator; pairs against it couple
     * Body 1 only.
     *
     * A motion moves every point x of the obstacle by
     * u(x) = sum_k f_k (d_k + r_k x (x - c)), c the pivot, f_k the step's
     * factor of term k's history: the small-deformation model, whose pairs
     * keep their reference normals, sees the motion as a shift of each
     * pair's gap and slip.
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

      /// Whether the surface is flat (an infinite curvature_radius()):
      /// sliding along it leaves a pair's gap and normal exact.
      bool
      flat() const;

      /// The radius of curvature of the surface (the smallest, where it
      /// has two): infinite for a plane. Small sliding keeps each pair's
      /// reference normal, which a slide s along the surface turns by
      /// s / radius.
      virtual double
      curvature_radius() const;

      /// The point rotations turn about: a plane's point, a cylinder's or
      /// sphere's centre.
      virtual Point<dim>
      pivot() const = 0;

      /// Sets the prescribed motion (empty: fixed).
      void
      set_motion(const std::vector<RigidMotion<dim>> &terms);

      /// Whether a motion is prescribed.
      bool
      moves() const;

      /// The displacement of the obstacle's point @p x at the history
      /// factors @p factors (a history past their end has factor 0).
      Tensor<1, dim>
      displacement(const Point<dim>          &x,
                   const std::vector<double> &factors) const;

      /**
       * @brief The motion at @p factors as a finite rigid motion, of which
       * displacement() is the linearisation: the point @p x goes to
       * c + d + R (x - c), c the pivot, d the summed translation and R the
       * rotation by the summed rotation vector (about z in 2D, Rodrigues'
       * formula in 3D). Finite sliding places the obstacle by it.
       */
      Point<dim>
      placed(const Point<dim> &x, const std::vector<double> &factors) const;

      /// The rotation R of placed().
      Tensor<2, dim>
      rotation(const std::vector<double> &factors) const;

      /// The translation d of placed().
      Tensor<1, dim>
      translation(const std::vector<double> &factors) const;

    private:
      const std::vector<discretization::SurfacePoint<dim>> no_samples{};
      std::vector<RigidMotion<dim>>                        motion;
    };



    /**
     * @brief An obstacle where its finite rigid motion puts it at given
     * history factors (Obstacle::placed()): closest points are those of
     * the obstacle at rest to the point moved back, moved forward again
     * with their normals turned. What finite sliding pairs a moving
     * obstacle as.
     */
    template <int dim>
    class PlacedObstacle : public ContactSurface<dim>
    {
    public:
      /// @p obstacle (kept by reference) at @p factors.
      PlacedObstacle(const Obstacle<dim>       &obstacle,
                     const std::vector<double> &factors);

      bool
      deformable() const override;

      std::string
      description() const override;

      const std::vector<discretization::SurfacePoint<dim>> &
      sample_points() const override;

      discretization::SurfacePoint<dim>
      closest_point(
        const Point<dim>                        &location,
        const discretization::SurfacePoint<dim> *nearest) const override;

    private:
      const Obstacle<dim> &obstacle;
      const Point<dim>     pivot;
      const Tensor<2, dim> R;
      const Tensor<1, dim> d;
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

      Point<dim>
      pivot() const override;

      /// The orthogonal projection of @p location on the plane.
      discretization::SurfacePoint<dim>
      closest_point(
        const Point<dim>                        &location,
        const discretization::SurfacePoint<dim> *nearest) const override;

    private:
      const Point<dim> point;
      Tensor<1, dim>   normal;
    };



    /**
     * @brief A rigid circular cylinder that Body 1 touches from outside:
     * in 2D the circle of a radius about a centre, in 3D the infinite
     * cylinder of a radius about the axis through the centre along a
     * direction. Its outward normal points away from the axis.
     */
    template <int dim>
    class RigidCylinder : public Obstacle<dim>
    {
    public:
      /// @p axis (3D) need not be unit; it must not be zero (ignored in
      /// 2D). @p radius > 0.
      RigidCylinder(const Point<dim>     &centre,
                    const double          radius,
                    const Tensor<1, dim> &axis);

      std::string
      description() const override;

      std::string
      kind() const override;

      double
      curvature_radius() const override;

      Point<dim>
      pivot() const override;

      /// The point of the cylinder on the ray from the axis through
      /// @p location; a location on the axis has no closest point and is
      /// refused with an input error.
      discretization::SurfacePoint<dim>
      closest_point(
        const Point<dim>                        &location,
        const discretization::SurfacePoint<dim> *nearest) const override;

    private:
      const Point<dim> centre;
      const double     radius;
      Tensor<1, dim>   axis;
    };



    /**
     * @brief A rigid sphere (3D) that Body 1 touches from outside; its
     * outward normal points away from the centre.
     */
    template <int dim>
    class RigidSphere : public Obstacle<dim>
    {
    public:
      /// @p radius > 0.
      RigidSphere(const Point<dim> &centre, const double radius);

      std::string
      description() const override;

      std::string
      kind() const override;

      double
      curvature_radius() const override;

      Point<dim>
      pivot() const override;

      /// The point of the sphere on the ray from the centre through
      /// @p location; the centre itself is refused with an input error.
      discretization::SurfacePoint<dim>
      closest_point(
        const Point<dim>                        &location,
        const discretization::SurfacePoint<dim> *nearest) const override;

    private:
      const Point<dim> centre;
      const double     radius;
    };



    /**
     * @brief A rigid surface of exact geometry: faces of the patches of a
     * body's geometry (a built-in shape or a G+Smo file), touched from
     * outside, e.g. a punch with rounded corners. Its geometry is a
     * discretization::ExactSurface (make_nurbs_surface()): the closest
     * point and normal its projection gives, rotations about its faces'
     * centroid, its smallest radius of curvature.
     */
    template <int dim>
    class RigidSurface : public Obstacle<dim>
    {
    public:
      /// The surface @p surface; @p name says where the geometry comes
      /// from, for messages ("the rigid surface of punch.xml").
      RigidSurface(std::unique_ptr<discretization::ExactSurface<dim>> surface,
                   const std::string                                 &name);

      std::string
      description() const override;

      std::string
      kind() const override;

      /// ExactSurface::smallest_curvature_radius().
      double
      curvature_radius() const override;

      /// ExactSurface::centroid().
      Point<dim>
      pivot() const override;

      /// ExactSurface::closest_point().
      discretization::SurfacePoint<dim>
      closest_point(
        const Point<dim>                        &location,
        const discretization::SurfacePoint<dim> *nearest) const override;

    private:
      std::unique_ptr<discretization::ExactSurface<dim>> surface;
      std::string                                        name;
    };
  } // namespace contact
} // namespace igabde

#endif
