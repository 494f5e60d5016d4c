#ifndef igabde_nurbs_multi_patch_h
#define igabde_nurbs_multi_patch_h

#include <igabde/nurbs/geometry_file.h>
#include <igabde/nurbs/nurbs_patch.h>

#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace nurbs
  {
    /**
     * @brief One numbering of the control points of patches glued at
     * conforming interfaces: the control points that two interface faces
     * share are one point, whatever the orientation of either patch.
     *
     * The faces of an interface are matched by position: each control
     * point of the one face must coincide (within 1e-10 times the larger
     * net's diameter) with exactly one of the other's, with the same weight
     * up to one factor for the whole face (R = w N / W is unchanged by a
     * common factor). Glued points are joined transitively, so an edge or
     * vertex shared by several patches is one point. The numbering keeps
     * patch 0's own order and appends every further patch's new points in
     * its order: a single patch is numbered as it stands.
     *
     * @return result.first[p][a]: the glued index of control point a of
     * patch p; result.second: the number of glued points.
     * @throws base::ExcInput, prefixed by @p where, naming the interface,
     * when its faces do not have the same control points (different counts
     * of spans, degrees or grading along the interface, or rational weights
     * that do not agree).
     */
    template <int dim>
    std::pair<std::vector<std::vector<unsigned int>>, unsigned int>
    glue_control_points(const std::vector<NurbsPatch<dim>> &patches,
                        const std::vector<PatchInterface>  &interfaces,
                        const std::string                  &where);
  } // namespace nurbs
} // namespace igabde

#endif
