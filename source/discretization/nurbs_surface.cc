#include <igabde/discretization/nurbs_surface.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace igabde
{
  namespace discretization
  {
    namespace
    {
      /// The faces of NURBS patches as an ExactSurface (make_nurbs_surface()).
      template <int dim>
      class NurbsSurface : public ExactSurface<dim>
      {
      public:
        NurbsSurface(const std::vector<nurbs::NurbsPatch<dim>> &patches_in,
                     const std::vector<unsigned int>           &face_ids)
        {
          AssertThrow(!face_ids.empty(),
                      ExcMessage("NurbsSurface: no faces given."));
          // Only the patches that carry a face are kept.
          std::vector<int> kept(patches_in.size(), -1);
          for (const unsigned int id : face_ids)
            {
              const unsigned int p = id / (2 * dim), f = id % (2 * dim);
              AssertThrow(p < patches_in.size(),
                          ExcMessage("NurbsSurface: face " +
                                     std::to_string(id) +
                                     " is on a patch the geometry does not "
                                     "have."));
              if (kept[p] < 0)
                {
                  kept[p] = patches.size();
                  patches.push_back(patches_in[p]);
                }
              faces.emplace_back(kept[p], f);
            }
          for (const auto &[p, f] : faces)
            mean_centroid += patches[p].face_centroid(f) / double(faces.size());
          for (const auto &[p, f] : faces)
            radius = std::min(radius, face_curvature_radius(patches[p], f));
        }

        SurfacePoint<dim>
        closest_point(const Point<dim> &location) const override
        {
          SurfacePoint<dim> best;
          double            distance = std::numeric_limits<double>::infinity();
          for (const auto &[p, f] : faces)
            {
              const Point<dim> xi =
                patches[p].closest_point_on_face(f, location);
              const Point<dim> x = patches[p].value(xi);
              if ((x - location).norm() < distance)
                {
                  distance        = (x - location).norm();
                  best.location   = x;
                  best.parametric = xi;
                  best.normal     = patches[p].outward_normal(f, xi);
                }
            }
          return best;
        }

        Point<dim>
        centroid() const override
        {
          return mean_centroid;
        }

        double
        smallest_curvature_radius() const override
        {
          return radius;
        }

      private:
        /// The smallest radius of curvature of the face @p f of @p patch,
        /// from the normal's turn between neighbouring sample points along
        /// each face direction (per_span a span, at their midpoints).
        static double
        face_curvature_radius(const nurbs::NurbsPatch<dim> &patch,
                              const unsigned int            f)
        {
          constexpr unsigned int               per_span = 8;
          const unsigned int                   normal   = f / 2;
          std::array<std::vector<double>, dim> samples;
          for (unsigned int d = 0; d < dim; ++d)
            {
              if (d == normal)
                {
                  samples[d] = {f % 2 == 0 ? patch.parametric_lower()[d] :
                                             patch.parametric_upper()[d]};
                  continue;
                }
              const auto b = patch.breakpoints(d);
              for (unsigned int s = 0; s + 1 < b.size(); ++s)
                for (unsigned int j = 0; j < per_span; ++j)
                  samples[d].push_back(b[s] + (b[s + 1] - b[s]) * (j + 0.5) /
                                                per_span);
            }
          std::array<unsigned int, dim> count, index;
          unsigned int                  total = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              count[d] = samples[d].size();
              total *= count[d];
            }
          const auto xi_of = [&](const std::array<unsigned int, dim> &i) {
            Point<dim> xi;
            for (unsigned int d = 0; d < dim; ++d)
              xi[d] = samples[d][i[d]];
            return xi;
          };
          double radius = std::numeric_limits<double>::infinity();
          for (unsigned int k = 0; k < total; ++k)
            {
              unsigned int rest = k;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  index[d] = rest % count[d];
                  rest /= count[d];
                }
              const Point<dim>     xi = xi_of(index);
              const Point<dim>     x  = patch.value(xi);
              const Tensor<1, dim> n  = patch.outward_normal(f, xi);
              for (unsigned int d = 0; d < dim; ++d)
                {
                  if (d == normal || index[d] + 1 == count[d])
                    continue;
                  auto next = index;
                  ++next[d];
                  const Point<dim> xi_next = xi_of(next);
                  const double     chord   = (patch.value(xi_next) - x).norm();
                  const double     turn =
                    (patch.outward_normal(f, xi_next) - n).norm();
                  // Below round-off a turn is no curvature.
                  if (chord > 0. && turn > 1e-12)
                    radius = std::min(radius, chord / turn);
                }
            }
          return radius;
        }

        std::vector<nurbs::NurbsPatch<dim>>                patches;
        std::vector<std::pair<unsigned int, unsigned int>> faces;
        Point<dim>                                         mean_centroid;
        double radius = std::numeric_limits<double>::infinity();
      };
    } // namespace



    template <int dim>
    std::unique_ptr<ExactSurface<dim>>
    make_nurbs_surface(const std::vector<nurbs::NurbsPatch<dim>> &patches,
                       const std::vector<unsigned int>           &faces)
    {
      return std::make_unique<NurbsSurface<dim>>(patches, faces);
    }



    template std::unique_ptr<ExactSurface<2>>
    make_nurbs_surface<2>(const std::vector<nurbs::NurbsPatch<2>> &,
                          const std::vector<unsigned int> &);
    template std::unique_ptr<ExactSurface<3>>
    make_nurbs_surface<3>(const std::vector<nurbs::NurbsPatch<3>> &,
                          const std::vector<unsigned int> &);
  } // namespace discretization
} // namespace igabde
