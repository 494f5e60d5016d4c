#ifndef igabde_nurbs_geometry_file_h
#define igabde_nurbs_geometry_file_h

#include <igabde/nurbs/nurbs_patch.h>

#include <array>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace nurbs
  {
    /**
     * @brief Two patch faces that a G+Smo MultiPatch declares glued, in
     * this project's numbering (patch index in file order, face 0..2dim-1
     * = G+Smo side - 1).
     *
     * The orientation flags that follow the four numbers in the file are
     * kept as read (for writing the file back); whether the two faces
     * coincide is checked geometrically (check_interfaces()).
     */
    struct PatchInterface
    {
      std::array<unsigned int, 2> patch{};
      std::array<unsigned int, 2> face{};
      /// Everything after the four numbers on the file's line.
      std::vector<int> flags;
    };

    /**
     * @brief What a G+Smo XML geometry file holds: the patches (TensorBSpline
     * or TensorNurbs of the scene's dimension), and, from a MultiPatch
     * element, its interfaces and boundary faces.
     */
    template <int dim>
    struct MultiPatchGeometry
    {
      std::vector<NurbsPatch<dim>> patches;
      std::vector<PatchInterface>  interfaces;
      /// (patch, face) pairs of the MultiPatch's boundary list.
      std::vector<std::pair<unsigned int, unsigned int>> boundary;
      /// What the reader took differently from how the file states it (one
      /// line each, for the log): a planar patch stored in 3D space.
      std::vector<std::string> notes;
    };

    /**
     * @brief Reads a G+Smo XML file (Boost.PropertyTree's XML parser).
     *
     * Reads every `Geometry` element of type TensorBSpline<dim> or
     * TensorNurbs<dim> under the root `xml` element (knot vectors with
     * their degrees, weights, `coefs` with `geoDim`); when the file has a
     * `MultiPatch` element, its `patches` (type id_range or id_index, by
     * Geometry id) choose the patches and their order, and `interfaces`
     * and `boundary` are read (one interface per line). Everything is
     * checked as it is read: each defect ends with base::ExcInput naming
     * @p file_name (and the patch id or XML line where there is one) and
     * what to change. The patches' Jacobians and the interfaces are
     * checked too (check_jacobian(), check_interfaces()).
     */
    template <int dim>
    MultiPatchGeometry<dim>
    read_geometry_file(const std::string &file_name);

    /**
     * @brief Writes @p geometry as a G+Smo XML file that
     * read_geometry_file() (and G+Smo) read back exactly: TensorNurbs
     * patches with 17 significant digits, and a MultiPatch element when
     * there is more than one patch or any interface.
     */
    template <int dim>
    void
    write_geometry_file(const MultiPatchGeometry<dim> &geometry,
                        std::ostream                  &out);

    /**
     * @brief Writes the control net of every patch of @p geometry as VTU
     * (deal.II's DataOutBase): one linear cell per cell of each net, with
     * the weight and the patch index as point data.
     */
    template <int dim>
    void
    write_control_net_vtu(const MultiPatchGeometry<dim> &geometry,
                          std::ostream                  &out);

    /**
     * @brief Refuses (base::ExcInput prefixed by @p where) a patch whose
     * Jacobian determinant changes sign or vanishes: det(dx/dxi) is
     * sampled at 4 x 4 (x 4) Gauss points in every knot span and must
     * keep one sign and stay above 1e-10 of its largest magnitude.
     * Left-handed patches (det < 0 throughout) are accepted.
     */
    template <int dim>
    void
    check_jacobian(const NurbsPatch<dim> &patch, const std::string &where);

    /**
     * @brief Refuses (base::ExcInput prefixed by @p where) a patch that
     * meets itself, which a body of one patch would hold as a slit or a
     * puncture: a face that collapses (its area, or length in 2D, below
     * 1e-8 of the patch's diameter^(dim-1): a pole, where the face's control
     * points are one point but separate unknowns), or two faces that
     * coincide (every sample of one, the images of 5 points per knot span
     * and direction, within 1e-8 of the diameter of the other: a closed
     * ring or tube). Gluing a patch to itself is not built.
     */
    template <int dim>
    void
    check_patch_closure(const NurbsPatch<dim> &patch, const std::string &where);

    /**
     * @brief Refuses (base::ExcInput prefixed by @p where) an interface
     * whose two faces do not coincide: points on each face (the images of
     * 5 points per knot span and direction) must lie on the other face
     * within 1e-8 of the patches' diameter.
     */
    template <int dim>
    void
    check_interfaces(const MultiPatchGeometry<dim> &geometry,
                     const std::string             &where);

    /**
     * @brief The diagonal of the bounding box of the control points of
     * @p patch: the patch's size, the scale of the geometric tolerances.
     */
    template <int dim>
    double
    control_net_diameter(const NurbsPatch<dim> &patch);

    /**
     * @brief Area (2D) or volume (3D) of the patch's image, by Gauss
     * quadrature of |det J| with @p n_points per direction and knot span,
     * or, for 0, n = max(p + 1, ceil(17 / ln(4 k))) in a direction of k
     * spans: 13 points on one span give round-off for the project's
     * circular arcs, and finer spans need fewer (4 at k = 16, 3 from
     * k = 64 for p = 2).
     */
    template <int dim>
    double
    patch_measure(const NurbsPatch<dim> &patch,
                  const unsigned int     n_points = 0);
  } // namespace nurbs
} // namespace igabde

#endif
