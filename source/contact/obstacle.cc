#include <igabde/base/rotation.h>
#include <igabde/base/utilities.h>

#include <igabde/contact/obstacle.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace igabde
{
  namespace contact
  {
    template <int dim>
    bool
    Obstacle<dim>::deformable() const
    {
      return false;
    }



    template <int dim>
    const std::vector<discretization::SurfacePoint<dim>> &
    Obstacle<dim>::sample_points() const
    {
      return no_samples;
    }



    template <int dim>
    bool
    Obstacle<dim>::flat() const
    {
      return !std::isfinite(curvature_radius());
    }



    template <int dim>
    double
    Obstacle<dim>::curvature_radius() const
    {
      return std::numeric_limits<double>::infinity();
    }



    template <int dim>
    void
    Obstacle<dim>::set_motion(const std::vector<RigidMotion<dim>> &terms)
    {
      motion = terms;
    }



    template <int dim>
    bool
    Obstacle<dim>::moves() const
    {
      return !motion.empty();
    }



    template <int dim>
    Tensor<1, dim>
    Obstacle<dim>::displacement(const Point<dim>          &x,
                                const std::vector<double> &factors) const
    {
      const Tensor<1, dim> arm = x - pivot();
      Tensor<1, 3>         arm3;
      for (unsigned int d = 0; d < dim; ++d)
        arm3[d] = arm[d];
      Tensor<1, dim> u;
      for (const RigidMotion<dim> &term : motion)
        {
          const double f =
            term.history < factors.size() ? factors[term.history] : 0.;
          if (f == 0.)
            continue;
          const Tensor<1, 3> turned = cross_product_3d(term.rotation, arm3);
          for (unsigned int d = 0; d < dim; ++d)
            u[d] += f * (term.translation[d] + turned[d]);
        }
      return u;
    }



    template <int dim>
    Tensor<1, dim>
    Obstacle<dim>::translation(const std::vector<double> &factors) const
    {
      Tensor<1, dim> d;
      for (const RigidMotion<dim> &term : motion)
        if (term.history < factors.size())
          d += factors[term.history] * term.translation;
      return d;
    }



    template <int dim>
    Tensor<2, dim>
    Obstacle<dim>::rotation(const std::vector<double> &factors) const
    {
      Tensor<1, 3> theta;
      for (const RigidMotion<dim> &term : motion)
        if (term.history < factors.size())
          theta += factors[term.history] * term.rotation;
      return base::exact_rotation<dim>(theta);
    }



    template <int dim>
    Point<dim>
    Obstacle<dim>::placed(const Point<dim>          &x,
                          const std::vector<double> &factors) const
    {
      const Point<dim> c = pivot();
      return c + translation(factors) + rotation(factors) * (x - c);
    }



    template <int dim>
    PlacedObstacle<dim>::PlacedObstacle(const Obstacle<dim>       &obstacle,
                                        const std::vector<double> &factors)
      : obstacle(obstacle)
      , pivot(obstacle.pivot())
      , R(obstacle.rotation(factors))
      , d(obstacle.translation(factors))
    {}



    template <int dim>
    bool
    PlacedObstacle<dim>::deformable() const
    {
      return false;
    }



    template <int dim>
    std::string
    PlacedObstacle<dim>::description() const
    {
      return obstacle.description();
    }



    template <int dim>
    const std::vector<discretization::SurfacePoint<dim>> &
    PlacedObstacle<dim>::sample_points() const
    {
      return obstacle.sample_points();
    }



    template <int dim>
    discretization::SurfacePoint<dim>
    PlacedObstacle<dim>::closest_point(
      const Point<dim>                        &location,
      const discretization::SurfacePoint<dim> *nearest) const
    {
      (void)nearest;
      // R is orthogonal: R^T moves back.
      const Point<dim> back = pivot + transpose(R) * (location - pivot - d);
      discretization::SurfacePoint<dim> point =
        obstacle.closest_point(back, nullptr);
      point.location = pivot + d + R * (point.location - pivot);
      point.normal   = R * point.normal;
      return point;
    }



    template <int dim>
    RigidPlane<dim>::RigidPlane(const Point<dim>     &point,
                                const Tensor<1, dim> &normal_in)
      : point(point)
      , normal(normal_in)
    {
      AssertThrow(normal.norm() > 0.,
                  ExcMessage("RigidPlane: the normal must not be zero."));
      normal /= normal.norm();
    }



    template <int dim>
    std::string
    RigidPlane<dim>::description() const
    {
      return "the rigid plane";
    }



    template <int dim>
    std::string
    RigidPlane<dim>::kind() const
    {
      return "rigid plane";
    }



    template <int dim>
    Point<dim>
    RigidPlane<dim>::pivot() const
    {
      return point;
    }



    template <int dim>
    discretization::SurfacePoint<dim>
    RigidPlane<dim>::closest_point(
      const Point<dim> &location,
      const discretization::SurfacePoint<dim> *) const
    {
      discretization::SurfacePoint<dim> result;
      result.location = location - ((location - point) * normal) * normal;
      result.normal   = normal;
      return result;
    }



    namespace
    {
      /// The point at distance @p radius from the centre along the
      /// direction @p radial of @p location from the centre (or axis), and
      /// that direction as the normal; a location on the centre (axis),
      /// within 1e-12 of the radius, is refused.
      template <int dim>
      discretization::SurfacePoint<dim>
      on_round_surface(const Point<dim>  &location,
                       const Point<dim>  &foot,
                       const double       radius,
                       const std::string &description,
                       const std::string &where)
      {
        const Tensor<1, dim> radial   = location - foot;
        const double         distance = radial.norm();
        AssertThrow(distance > 1e-12 * radius,
                    base::ExcInput(
                      "the contact point (" + base::to_string(location) +
                      ") of Body 1 lies on " + description + "'s " + where +
                      ", where no closest point and no normal exist: Body 1 "
                      "is deep inside the obstacle; place the obstacle "
                      "outside Body 1 (its Centre and Radius)."));
        discretization::SurfacePoint<dim> result;
        result.normal   = radial / distance;
        result.location = foot + radius * result.normal;
        return result;
      }
    } // namespace



    template <int dim>
    RigidCylinder<dim>::RigidCylinder(const Point<dim>     &centre,
                                      const double          radius,
                                      const Tensor<1, dim> &axis_in)
      : centre(centre)
      , radius(radius)
      , axis(axis_in)
    {
      AssertThrow(radius > 0.,
                  ExcMessage("RigidCylinder: the radius must be positive."));
      if (dim == 3)
        {
          AssertThrow(axis.norm() > 0.,
                      ExcMessage("RigidCylinder: the axis must not be zero."));
          axis /= axis.norm();
        }
    }



    template <int dim>
    std::string
    RigidCylinder<dim>::description() const
    {
      return dim == 2 ? "the rigid circle" : "the rigid cylinder";
    }



    template <int dim>
    std::string
    RigidCylinder<dim>::kind() const
    {
      return dim == 2 ? "rigid circle" : "rigid cylinder";
    }



    template <int dim>
    double
    RigidCylinder<dim>::curvature_radius() const
    {
      return radius;
    }



    template <int dim>
    Point<dim>
    RigidCylinder<dim>::pivot() const
    {
      return centre;
    }



    template <int dim>
    discretization::SurfacePoint<dim>
    RigidCylinder<dim>::closest_point(
      const Point<dim> &location,
      const discretization::SurfacePoint<dim> *) const
    {
      Point<dim> foot = centre;
      if (dim == 3)
        foot += ((location - centre) * axis) * axis;
      return on_round_surface(location,
                              foot,
                              radius,
                              description(),
                              dim == 2 ? "centre" : "axis");
    }



    template <int dim>
    RigidSphere<dim>::RigidSphere(const Point<dim> &centre, const double radius)
      : centre(centre)
      , radius(radius)
    {
      AssertThrow(radius > 0.,
                  ExcMessage("RigidSphere: the radius must be positive."));
    }



    template <int dim>
    std::string
    RigidSphere<dim>::description() const
    {
      return "the rigid sphere";
    }



    template <int dim>
    std::string
    RigidSphere<dim>::kind() const
    {
      return "rigid sphere";
    }



    template <int dim>
    double
    RigidSphere<dim>::curvature_radius() const
    {
      return radius;
    }



    template <int dim>
    Point<dim>
    RigidSphere<dim>::pivot() const
    {
      return centre;
    }



    template <int dim>
    discretization::SurfacePoint<dim>
    RigidSphere<dim>::closest_point(
      const Point<dim> &location,
      const discretization::SurfacePoint<dim> *) const
    {
      return on_round_surface(location,
                              centre,
                              radius,
                              description(),
                              "centre");
    }



    template <int dim>
    RigidSurface<dim>::RigidSurface(
      std::unique_ptr<discretization::ExactSurface<dim>> surface,
      const std::string                                 &name)
      : surface(std::move(surface))
      , name(name)
    {
      Assert(this->surface, ExcInternalError());
    }



    template <int dim>
    std::string
    RigidSurface<dim>::description() const
    {
      return "the rigid surface of " + name;
    }



    template <int dim>
    std::string
    RigidSurface<dim>::kind() const
    {
      return "rigid surface";
    }



    template <int dim>
    double
    RigidSurface<dim>::curvature_radius() const
    {
      return surface->smallest_curvature_radius();
    }



    template <int dim>
    Point<dim>
    RigidSurface<dim>::pivot() const
    {
      return surface->centroid();
    }



    template <int dim>
    discretization::SurfacePoint<dim>
    RigidSurface<dim>::closest_point(
      const Point<dim> &location,
      const discretization::SurfacePoint<dim> *) const
    {
      return surface->closest_point(location);
    }



    template class Obstacle<2>;
    template class Obstacle<3>;
    template class PlacedObstacle<2>;
    template class PlacedObstacle<3>;
    template class RigidPlane<2>;
    template class RigidPlane<3>;
    template class RigidCylinder<2>;
    template class RigidCylinder<3>;
    template class RigidSphere<2>;
    template class RigidSphere<3>;
    template class RigidSurface<2>;
    template class RigidSurface<3>;
  } // namespace contact
} // namespace igabde
