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
     * @brief The exact NURBS geometry a body's parameters name, with its base
     * subdivisions applied; @p where prefixes error messages.
     */
    template <int dim>
    nurbs::NurbsPatch<dim>
    make_geometry(const BodyParameters &body, const std::string &where);
  } // namespace scene
} // namespace igabde

#endif
