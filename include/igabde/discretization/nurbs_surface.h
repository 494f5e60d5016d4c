#ifndef igabde_discretization_nurbs_surface_h
#define igabde_discretization_nurbs_surface_h

#include <igabde/nurbs/nurbs_patch.h>

#include <igabde/discretization/exact_surface.h>

#include <memory>
#include <vector>

namespace igabde
{
  namespace discretization
  {
    /**
     * @brief The faces @p faces (patch p's face f as 2 dim p + f) of
     * @p patches as an ExactSurface.
     *
     * The closest point is the projection on each face (Newton from the
     * face's sampled breakpoints and span points,
     * nurbs::NurbsPatch::closest_point_on_face()), the nearest of the
     * faces kept, with the patch's outward normal there. The smallest
     * radius of curvature comes from the normal's turn between
     * neighbouring points, eight per knot span and direction:
     * |n_i - n_j| / |x_i - x_j| is exactly 1 / R on a circle of radius R.
     */
    template <int dim>
    std::unique_ptr<ExactSurface<dim>>
    make_nurbs_surface(const std::vector<nurbs::NurbsPatch<dim>> &patches,
                       const std::vector<unsigned int>           &faces);
  } // namespace discretization
} // namespace igabde

#endif
