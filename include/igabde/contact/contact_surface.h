#ifndef igabde_contact_contact_surface_h
#define igabde_contact_contact_surface_h

#include <igabde/base/nearest_points.h>

#include <igabde/discretization/body.h>

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
     * @brief What the contact points of Body 1 face: a face of a deformable
     * body (BodyFace) or an obstacle (Obstacle, e.g. RigidPlane).
     *
     * A pairing strategy asks it for points that may coincide with Body 1's
     * points and for the closest point to a location; the condensation
     * asks whether it moves (deformable()).
     */
    template <int dim>
    class ContactSurface
    {
    public:
      virtual ~ContactSurface() = default;

      /// Whether the surface belongs to a deformable body (its points carry
      /// operators into that body's unknowns).
      virtual bool
      deformable() const = 0;

      /// For messages: "Body 2's face 3", "the rigid plane".
      virtual std::string
      description() const = 0;

      /// Points of the surface where Body 1's points may coincide with it
      /// (matching meshes); empty for an obstacle.
      virtual const std::vector<discretization::SurfacePoint<dim>> &
      sample_points() const = 0;

      /**
       * @brief The point of the surface closest to @p location, with the
       * surface's outward unit normal there and (deformable surfaces) its
       * operator. @p nearest is the sample point nearest to @p location, or
       * nullptr when there are no samples.
       */
      virtual discretization::SurfacePoint<dim>
      closest_point(const Point<dim>                        &location,
                    const discretization::SurfacePoint<dim> *nearest) const = 0;

      /**
       * @brief The element grid of a deformable surface in its face
       * coordinates (Body::face_grid()); an obstacle has none and throws.
       */
      virtual discretization::FaceGrid<dim>
      face_grid() const;

      /**
       * @brief The point of a deformable surface at face coordinates
       * @p eta (Body::face_point()); an obstacle throws.
       */
      virtual discretization::FacePoint<dim>
      face_point(const Point<dim - 1> &eta) const;

      /// The tangents' derivatives at @p eta (Body::face_second_derivatives());
      /// an obstacle throws.
      virtual discretization::FaceSecondDerivatives<dim>
      face_second_derivatives(const Point<dim - 1> &eta) const;

      /// The surfaces with face coordinates of their own that this one is
      /// made of: itself, or each patch face of a surface over several.
      virtual std::vector<const ContactSurface<dim> *>
      parts() const
      {
        return {this};
      }

      /**
       * @brief Whether the unit normal is continuous over the surface, on
       * its current configuration, to within a turn of 0.05 (3 degrees)
       * at its element edges and where its faces meet: an obstacle (as its
       * closest point gives it); NURBS faces of degree 2 or more with
       * single knots (C^1); tangent-continuous geometry bent by the strain
       * (a circle's double knots, two quarter rings, a straight extrusion
       * of degree 1). Not a faceted face (FE_Q or degree 1 on a curved
       * geometry: the normal jumps by the facets' angle).
       */
      virtual bool
      normal_continuous() const
      {
        return true;
      }
    };



    /**
     * @brief Patch faces of a deformable body as one contact surface: one
     * face, or several of a multi-patch body (patch faces that meet at
     * interfaces).
     *
     * With several faces the closest point is searched on each (from its
     * own nearest sample) and the closest kept; face coordinates
     * (face_grid(), face_point()) are each face's own, through parts().
     */
    template <int dim>
    class BodyFace : public ContactSurface<dim>
    {
    public:
      /// Samples the faces' candidate points (Body::surface_points()).
      BodyFace(const discretization::Body<dim>       &body,
               const std::vector<types::boundary_id> &faces);

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

      discretization::FaceGrid<dim>
      face_grid() const override;

      discretization::FacePoint<dim>
      face_point(const Point<dim - 1> &eta) const override;

      discretization::FaceSecondDerivatives<dim>
      face_second_derivatives(const Point<dim - 1> &eta) const override;

      std::vector<const ContactSurface<dim> *>
      parts() const override;

      bool
      normal_continuous() const override;

    private:
      const discretization::Body<dim>      &body;
      const std::vector<types::boundary_id> faces;
      /// Each face alone (several faces only).
      std::vector<std::unique_ptr<BodyFace<dim>>>    single_faces;
      std::vector<discretization::SurfacePoint<dim>> samples;
      /// Each face's samples indexed (several faces only).
      std::vector<std::unique_ptr<base::NearestPoints<dim>>> face_index;
    };
  } // namespace contact
} // namespace igabde

#endif
