#ifndef igabde_nurbs_parametric_mesh_h
#define igabde_nurbs_parametric_mesh_h

#include <igabde/nurbs/nurbs_patch.h>

#include <deal.II/grid/tria.h>

#include <array>

namespace igabde
{
  namespace nurbs
  {
    using namespace dealii;

    /**
     * @brief Builds the parametric mesh of @p patch: one cell per non-empty
     * knot span (GridGenerator::subdivided_hyper_rectangle with the
     * breakpoint differences as step sizes, colorized), so boundary id f of
     * a cell face is the patch face f (low/high end of direction f/2).
     * @p triangulation is cleared first. With @p mirror_last the last
     * direction's spans are laid out in reverse order: the mesh for a
     * patch whose last direction is run backwards (xi' = lower + upper -
     * xi), whose cells must still be the patch's knot spans when those are
     * not uniform.
     */
    template <int dim>
    void
    make_parametric_triangulation(const NurbsPatch<dim> &patch,
                                  Triangulation<dim>    &triangulation,
                                  const bool             mirror_last = false);

    /**
     * @brief Tensor index (e_0, .., e_{dim-1}) of the non-empty knot span a
     * cell of the parametric mesh covers, found from the cell centre (not
     * from cell->index(), whose order is not guaranteed).
     */
    template <int dim>
    std::array<unsigned int, dim>
    span_of_cell(const NurbsPatch<dim>                            &patch,
                 const typename Triangulation<dim>::cell_iterator &cell);

    /**
     * @brief Same as the other overload, from the cell centre @p centre
     * and the breakpoints of each direction.
     */
    template <int dim>
    std::array<unsigned int, dim>
    span_of_point(const std::array<std::vector<double>, dim> &breakpoints,
                  const Point<dim>                           &centre);
  } // namespace nurbs
} // namespace igabde

#endif
