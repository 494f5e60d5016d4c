#ifndef igabde_scene_geometry_h
#define igabde_scene_geometry_h

#include <igabde/nurbs/nurbs_patch.h>

#include <igabde/scene/parameters.h>

#include <string>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief The exact NURBS geometry a body's parameters name, elevated to
     * at least @p degree and then split into its base subdivisions (knot
     * insertion after elevation: C^{p-1} across the new knots); @p where
     * prefixes error messages.
     */
    template <int dim>
    nurbs::NurbsPatch<dim>
    make_geometry(const BodyParameters &body,
                  const std::string    &where,
                  const unsigned int    degree);
  } // namespace scene
} // namespace igabde

#endif
