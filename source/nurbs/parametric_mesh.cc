#include <igabde/nurbs/parametric_mesh.h>

#include <deal.II/base/exceptions.h>

#include <deal.II/grid/grid_generator.h>

#include <algorithm>

namespace igabde
{
  namespace nurbs
  {
    template <int dim>
    void
    make_parametric_triangulation(const NurbsPatch<dim> &patch,
                                  Triangulation<dim>    &triangulation,
                                  const bool             mirror_last)
    {
      std::vector<std::vector<double>> steps(dim);
      for (unsigned int d = 0; d < dim; ++d)
        {
          const std::vector<double> b = patch.breakpoints(d);
          AssertThrow(b.size() >= 2,
                      ExcMessage("make_parametric_triangulation: direction " +
                                 std::to_string(d) + " has no knot span."));
          for (unsigned int e = 0; e + 1 < b.size(); ++e)
            steps[d].push_back(b[e + 1] - b[e]);
        }
      if (mirror_last)
        std::reverse(steps[dim - 1].begin(), steps[dim - 1].end());
      triangulation.clear();
      GridGenerator::subdivided_hyper_rectangle(triangulation,
                                                steps,
                                                patch.parametric_lower(),
                                                patch.parametric_upper(),
                                                true);
    }



    template <int dim>
    std::array<unsigned int, dim>
    span_of_point(const std::array<std::vector<double>, dim> &breakpoints,
                  const Point<dim>                           &centre)
    {
      std::array<unsigned int, dim> span;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const auto &b  = breakpoints[d];
          const auto  it = std::upper_bound(b.begin(), b.end(), centre[d]);
          const long  e  = static_cast<long>(it - b.begin()) - 1;
          span[d]        = static_cast<unsigned int>(
            std::clamp<long>(e, 0, static_cast<long>(b.size()) - 2));
        }
      return span;
    }



    template <int dim>
    std::array<unsigned int, dim>
    span_of_cell(const NurbsPatch<dim>                            &patch,
                 const typename Triangulation<dim>::cell_iterator &cell)
    {
      std::array<std::vector<double>, dim> b;
      for (unsigned int d = 0; d < dim; ++d)
        b[d] = patch.breakpoints(d);
      return span_of_point<dim>(b, cell->center());
    }



    template void
    make_parametric_triangulation(const NurbsPatch<2> &,
                                  Triangulation<2> &,
                                  const bool);
    template void
    make_parametric_triangulation(const NurbsPatch<3> &,
                                  Triangulation<3> &,
                                  const bool);
    template std::array<unsigned int, 2>
    span_of_point<2>(const std::array<std::vector<double>, 2> &,
                     const Point<2> &);
    template std::array<unsigned int, 3>
    span_of_point<3>(const std::array<std::vector<double>, 3> &,
                     const Point<3> &);
    template std::array<unsigned int, 2>
    span_of_cell<2>(const NurbsPatch<2> &,
                    const Triangulation<2>::cell_iterator &);
    template std::array<unsigned int, 3>
    span_of_cell<3>(const NurbsPatch<3> &,
                    const Triangulation<3>::cell_iterator &);
  } // namespace nurbs
} // namespace igabde
