#ifndef igabde_scene_geometry_h
#define igabde_scene_geometry_h

#include <igabde/nurbs/geometry_file.h>
#include <igabde/nurbs/nurbs_patch.h>

#include <igabde/discretization/body.h>

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
     * @brief The exact NURBS geometry a body's parameters name (one patch,
     * or a file's patches and interfaces), elevated to at least @p degree
     * and then split into its base subdivisions (knot insertion after
     * elevation: C^{p-1} across the new knots; several patches are then
     * checked to stay conforming, nurbs::glue_control_points()); @p where
     * prefixes error messages. With @p subdivisions, the split is checked
     * and returned there but not applied: the size guard counts the
     * subdivided patch without building it.
     */
    template <int dim>
    nurbs::MultiPatchGeometry<dim>
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
     * read or is not valid (nurbs::read_geometry_file()), or whose
     * interfaces the body's Subdivisions (at @p degree) leave
     * non-conforming. Returns the number of patches.
     */
    unsigned int
    check_geometry_file(const BodyParameters &body,
                        const unsigned int    dimension,
                        const unsigned int    degree,
                        const std::string    &where);

    /**
     * @brief What summary.json says of @p body: its geometry's source
     * (the built-in shape or the file as the scene names it), patches,
     * control points (the analysis space's, glued; a Lagrange body's
     * geometry map's) and measure (area or volume of the exact geometry,
     * nurbs::patch_measure() summed over the body's patches elevated to
     * @p degree before Subdivisions and Refinements), then its name,
     * unknowns, elements, matrix entries and rigid modes.
     */
    template <int dim>
    nlohmann::json
    body_record(const BodyParameters            &parameters,
                const unsigned int               degree,
                const discretization::Body<dim> &body);

    /**
     * @brief Writes the analysis geometry of @p body (every patch after
     * elevation, Subdivisions and Refinements, and the interfaces) as the
     * G+Smo XML file @p directory/name-geometry.xml and the control nets
     * as @p directory/name-control-net.vtu.
     */
    template <int dim>
    void
    export_geometry(const discretization::Body<dim> &body,
                    const std::string               &directory);
  } // namespace scene
} // namespace igabde

#endif
