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
      const std::vector<nurbs::NurbsPatch<dim>> &patches_in,
      const std::vector<unsigned int>           &face_ids,
      const std::string                         &name)
      : name(name)
      , radius(std::numeric_limits<double>::infinity())
    {
      AssertThrow(!face_ids.empty(),
                  ExcMessage("RigidSurface: no faces given."));
      // Only the patches that carry a face are kept.
      std::vector<int> kept(patches_in.size(), -1);
      for (const unsigned int id : face_ids)
        {
          const unsigned int p = id / (2 * dim), f = id % (2 * dim);
          AssertThrow(p < patches_in.size(),
                      ExcMessage("RigidSurface: face " + std::to_string(id) +
                                 " is on a patch the geometry does not "
                                 "have."));
          if (kept[p] < 0)
            {
              kept[p] = patches.size();
              patches.push_back(patches_in[p]);
            }
          faces.emplace_back(kept[p], f);
        }

      for (const auto &[p, f] : faces)
        centroid += patches[p].face_centroid(f) / double(faces.size());

      // The radius of curvature from the normal's turn between
      // neighbouring sample points along each face direction: for a
      // circle of radius R, |n_i - n_j| / |x_i - x_j| = 1 / R exactly.
      constexpr unsigned int per_span = 8;
      for (const auto &[p, f] : faces)
        {
          const nurbs::NurbsPatch<dim>        &patch  = patches[p];
          const unsigned int                   normal = f / 2;
          std::array<std::vector<double>, dim> samples;
          for (unsigned int d = 0; d < dim; ++d)
            {
              if (d == normal)
                {
                  samples[d] = {f % 2 == 0 ? patch.parametric_lower()[d] :
                                             patch.parametric_upper()[d]};
                  continue;
                }
              const auto b = patch.breakpoints(d);
              for (unsigned int s = 0; s + 1 < b.size(); ++s)
                for (unsigned int j = 0; j < per_span; ++j)
                  samples[d].push_back(b[s] + (b[s + 1] - b[s]) * (j + 0.5) /
                                                per_span);
            }
          std::array<unsigned int, dim> count, index;
          unsigned int                  total = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              count[d] = samples[d].size();
              total *= count[d];
            }
          const auto xi_of = [&](const std::array<unsigned int, dim> &i) {
            Point<dim> xi;
            for (unsigned int d = 0; d < dim; ++d)
              xi[d] = samples[d][i[d]];
            return xi;
          };
          for (unsigned int k = 0; k < total; ++k)
            {
              unsigned int rest = k;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  index[d] = rest % count[d];
                  rest /= count[d];
                }
              const Point<dim>     xi = xi_of(index);
              const Point<dim>     x  = patch.value(xi);
              const Tensor<1, dim> n  = patch.outward_normal(f, xi);
              for (unsigned int d = 0; d < dim; ++d)
                {
                  if (d == normal || index[d] + 1 == count[d])
                    continue;
                  auto next = index;
                  ++next[d];
                  const Point<dim> xi_next = xi_of(next);
                  const double     chord   = (patch.value(xi_next) - x).norm();
                  const double     turn =
                    (patch.outward_normal(f, xi_next) - n).norm();
                  // Below round-off a turn is no curvature.
                  if (chord > 0. && turn > 1e-12)
                    radius = std::min(radius, chord / turn);
                }
            }
        }
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
      return radius;
    }



    template <int dim>
    Point<dim>
    RigidSurface<dim>::pivot() const
    {
      return centroid;
    }



    template <int dim>
    discretization::SurfacePoint<dim>
    RigidSurface<dim>::closest_point(
      const Point<dim> &location,
      const discretization::SurfacePoint<dim> *) const
    {
      discretization::SurfacePoint<dim> best;
      double distance = std::numeric_limits<double>::infinity();
      for (const auto &[p, f] : faces)
        {
          const Point<dim> xi = patches[p].closest_point_on_face(f, location);
          const Point<dim> x  = patches[p].value(xi);
          if ((x - location).norm() < distance)
            {
              distance        = (x - location).norm();
              best.location   = x;
              best.parametric = xi;
              best.normal     = patches[p].outward_normal(f, xi);
            }
        }
      return best;
    }



    template class Obstacle<2>;
    template class Obstacle<3>;
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
