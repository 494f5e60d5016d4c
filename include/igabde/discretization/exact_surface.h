#ifndef igabde_discretization_exact_surface_h
#define igabde_discretization_exact_surface_h

#include <igabde/discretization/body.h>

#include <deal.II/base/point.h>

#include <memory>
#include <vector>

namespace igabde
{
  namespace discretization
  {
    using namespace dealii;

    /**
     * @brief A surface of exact geometry without unknowns: what a rigid
     * obstacle made of patch faces (contact::RigidSurface) asks of its
     * geometry, behind which the geometry's representation stays in this
     * room (the NURBS faces of make_nurbs_surface()).
     */
    template <int dim>
    class ExactSurface
    {
    public:
      virtual ~ExactSurface() = default;

      /// The point of the surface closest to @p location, with its outward
      /// unit normal (no operator, tributary area 0).
      virtual SurfacePoint<dim>
      closest_point(const Point<dim> &location) const = 0;

      /// The mean of the faces' centroids.
      virtual Point<dim>
      centroid() const = 0;

      /// The smallest radius of curvature over the surface; infinite where
      /// every face is flat.
      virtual double
      smallest_curvature_radius() const = 0;
    };
  } // namespace discretization
} // namespace igabde

#endif
