#ifndef igabde_scene_geometry_h
#define igabde_scene_geometry_h

#include <igabde/nurbs/nurbs_patch.h>

#include <igabde/scene/parameters.h>

#include <array>
#include <nlohmann/json.hpp>
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

    /**
     * @brief Reads the geometry file of @p body (Geometry = file, its
     * geometry_path resolved) as a @p dimension-D file and refuses, with a
     * one-line input error prefixed by @p where, a file that cannot be
     * read, is not valid (nurbs::read_geometry_file()) or holds more than
     * one patch.
     */
    void
    check_geometry_file(const BodyParameters &body,
                        const unsigned int    dimension,
                        const std::string    &where);

    /**
     * @brief What summary.json says of a body's geometry: its source
     * (the built-in shape or the file as the scene names it), patches,
     * control points of the analysis patch @p patch, and measure (area or
     * volume of the exact geometry, nurbs::patch_measure() on the body's
     * patch elevated to @p degree before Subdivisions and Refinements).
     */
    template <int dim>
    nlohmann::json
    geometry_record(const BodyParameters         &body,
                    const unsigned int            degree,
                    const nurbs::NurbsPatch<dim> &patch);

    /**
     * @brief Writes @p patch as the G+Smo XML file
     * @p directory/@p name-geometry.xml and its control net as
     * @p directory/@p name-control-net.vtu.
     */
    template <int dim>
    void
    export_geometry(const nurbs::NurbsPatch<dim> &patch,
                    const std::string            &directory,
                    const std::string            &name);
  } // namespace scene
} // namespace igabde

#endif
