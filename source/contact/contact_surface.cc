#include <igabde/contact/contact_surface.h>
#include <igabde/contact/obstacle.h>

namespace igabde
{
  namespace contact
  {
    template <int dim>
    BodyFace<dim>::BodyFace(const discretization::Body<dim> &body,
                            const types::boundary_id         face)
      : body(body)
      , face(face)
      , samples(body.surface_points(face))
    {}



    template <int dim>
    bool
    BodyFace<dim>::deformable() const
    {
      return true;
    }



    template <int dim>
    std::string
    BodyFace<dim>::description() const
    {
      return body.name() + "'s face " + std::to_string(face);
    }



    template <int dim>
    const std::vector<discretization::SurfacePoint<dim>> &
    BodyFace<dim>::sample_points() const
    {
      return samples;
    }



    template <int dim>
    discretization::SurfacePoint<dim>
    BodyFace<dim>::closest_point(
      const Point<dim>                        &location,
      const discretization::SurfacePoint<dim> *nearest) const
    {
      Assert(nearest != nullptr, ExcInternalError());
      return body.closest_surface_point(face, location, *nearest);
    }



    template <int dim>
    discretization::FaceGrid<dim>
    ContactSurface<dim>::face_grid() const
    {
      AssertThrow(false,
                  ExcMessage(description() + " has no face coordinates."));
      return {};
    }



    template <int dim>
    discretization::FacePoint<dim>
    ContactSurface<dim>::face_point(const Point<dim - 1> &) const
    {
      AssertThrow(false,
                  ExcMessage(description() + " has no face coordinates."));
      return {};
    }



    template <int dim>
    discretization::FaceGrid<dim>
    BodyFace<dim>::face_grid() const
    {
      return body.face_grid(face);
    }



    template <int dim>
    discretization::FacePoint<dim>
    BodyFace<dim>::face_point(const Point<dim - 1> &eta) const
    {
      return body.face_point(face, eta);
    }



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



    template class ContactSurface<2>;
    template class ContactSurface<3>;
    template class BodyFace<2>;
    template class BodyFace<3>;
    template class Obstacle<2>;
    template class Obstacle<3>;
    template class RigidPlane<2>;
    template class RigidPlane<3>;
  } // namespace contact
} // namespace igabde
