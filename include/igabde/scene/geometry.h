#ifndef igabde_scene_geometry_h
#define igabde_scene_geometry_h

#include <igabde/nurbs/nurbs_patch.h>

#include <igabde/scene/parameters.h>

#include <array>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief The exact NURBS geometry a body's parameters name, elevated to
     * at least @p degree and then split into its base subdivisions (knot
     * insertion after elevation: C^{p-1} across the new knots); @p where
     * prefixes error messages. With @p subdivisions, the split is checked
     * and returned there but not applied: the size guard counts the
     * subdivided patch without building it.
     */
    template <int dim>
    nurbs::NurbsPatch<dim>
    make_geometry(const BodyParameters          &body,
                  const std::string             &where,
                  const unsigned int             degree,
                  std::array<unsigned int, dim> *subdivisions = nullptr);

    /**
     * @brief The patch faces of the geometry named @p geometry (a
     * Body n/Geometry value) in @p dimension dimensions: entry f describes
     * face f, the boundary id that Supports, Tractions and the contact faces
     * name. Empty when the geometry does not exist in that dimension.
     */
    std::vector<std::string>
    patch_faces(const Geometry geometry, const unsigned int dimension);
  } // namespace scene
} // namespace igabde

#endif
