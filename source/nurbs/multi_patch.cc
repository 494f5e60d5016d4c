#include <igabde/base/disjoint_sets.h>
#include <igabde/base/nearest_points.h>
#include <igabde/base/utilities.h>

#include <igabde/nurbs/multi_patch.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace igabde
{
  namespace nurbs
  {
    template <int dim>
    std::pair<std::vector<std::vector<unsigned int>>, unsigned int>
    glue_control_points(const std::vector<NurbsPatch<dim>> &patches,
                        const std::vector<PatchInterface>  &interfaces,
                        const std::string                  &where)
    {
      std::vector<unsigned int> offset(patches.size() + 1, 0u);
      for (unsigned int p = 0; p < patches.size(); ++p)
        offset[p + 1] = offset[p] + patches[p].n_control_points();
      base::DisjointSets sets(offset.back());

      for (unsigned int k = 0; k < interfaces.size(); ++k)
        {
          const PatchInterface &i = interfaces[k];
          AssertThrow(i.patch[0] < patches.size() &&
                        i.patch[1] < patches.size() && i.face[0] < 2 * dim &&
                        i.face[1] < 2 * dim,
                      base::ExcInput(where + "interface " + std::to_string(k) +
                                     " names a patch or face that does not "
                                     "exist."));
          const std::string at =
            where + "interface (patch " + std::to_string(i.patch[0]) +
            " face " + std::to_string(i.face[0]) + ", patch " +
            std::to_string(i.patch[1]) + " face " + std::to_string(i.face[1]) +
            ") is not conforming after Degree, Subdivisions and Refinements: ";
          const NurbsPatch<dim>          &a = patches[i.patch[0]];
          const NurbsPatch<dim>          &b = patches[i.patch[1]];
          const std::vector<unsigned int> face_a =
            a.face_control_points(i.face[0]);
          const std::vector<unsigned int> face_b =
            b.face_control_points(i.face[1]);
          AssertThrow(face_a.size() == face_b.size(),
                      base::ExcInput(
                        at + "its faces have " + std::to_string(face_a.size()) +
                        " and " + std::to_string(face_b.size()) +
                        " control points. Give both patches the same "
                        "number of spans along the interface (Subdivisions "
                        "apply per parametric direction of each patch) and "
                        "no Grading across it."));
          std::vector<Point<dim>> points_b;
          for (const unsigned int c : face_b)
            points_b.push_back(b.control_point(c));
          const base::NearestPoints<dim> nearest(points_b);
          const double                   tolerance =
            1e-10 * std::max(control_net_diameter(a), control_net_diameter(b));
          std::vector<bool> taken(face_b.size(), false);
          const double      ratio =
            b.weight(face_b[nearest.nearest(a.control_point(face_a[0]))]) /
            a.weight(face_a[0]);
          for (const unsigned int c : face_a)
            {
              const Point<dim>   x = a.control_point(c);
              const std::size_t  m = nearest.nearest(x);
              std::ostringstream message;
              message << at << "the control point (" << x << ") of patch "
                      << i.patch[0];
              AssertThrow(x.distance(points_b[m]) <= tolerance && !taken[m],
                          base::ExcInput(
                            message.str() +
                            " has no control point of the other face on it. "
                            "Give both patches the same spans (knots) along "
                            "the interface, and no Grading across it."));
              AssertThrow(std::abs(b.weight(face_b[m]) - ratio * a.weight(c)) <=
                            1e-12 * b.weight(face_b[m]),
                          base::ExcInput(message.str() +
                                         " has another weight than the "
                                         "other face's point on it; the "
                                         "NURBS weights of an interface must "
                                         "agree."));
              taken[m] = true;
              sets.join(offset[i.patch[0]] + c, offset[i.patch[1]] + face_b[m]);
            }
        }

      std::vector<unsigned int>              number(offset.back(),
                                       numbers::invalid_unsigned_int);
      unsigned int                           n = 0;
      std::vector<std::vector<unsigned int>> result(patches.size());
      for (unsigned int p = 0; p < patches.size(); ++p)
        {
          result[p].resize(patches[p].n_control_points());
          for (unsigned int c = 0; c < result[p].size(); ++c)
            {
              const unsigned int root = sets.find(offset[p] + c);
              if (number[root] == numbers::invalid_unsigned_int)
                number[root] = n++;
              result[p][c] = number[root];
            }
        }
      return {result, n};
    }



    template std::pair<std::vector<std::vector<unsigned int>>, unsigned int>
    glue_control_points<2>(const std::vector<NurbsPatch<2>> &,
                           const std::vector<PatchInterface> &,
                           const std::string &);
    template std::pair<std::vector<std::vector<unsigned int>>, unsigned int>
    glue_control_points<3>(const std::vector<NurbsPatch<3>> &,
                           const std::vector<PatchInterface> &,
                           const std::string &);
  } // namespace nurbs
} // namespace igabde
