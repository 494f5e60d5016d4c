#ifndef igabde_contact_master_side_h
#define igabde_contact_master_side_h

#include <igabde/base/nearest_points.h>

#include <igabde/contact/contact_surface.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/point.h>

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

// The master surface as the weighted-gap pairing projects on it: closest
// points on deformable master faces in their face coordinates, or on an
// obstacle.

namespace igabde
{
  namespace contact
  {
    namespace internal
    {
      /**
       * Closest-point projection on a deformable master face in its face
       * coordinates: Gauss-Newton on |x(eta) - x|^2 from the nearest of
       * the face's element corners and midpoints, clamped to the face.
       */
      template <int dim>
      class FaceProjector
      {
      public:
        FaceProjector(const ContactSurface<dim> &master,
                      const std::string         &context)
          : master(master)
          , grid(master.face_grid())
          , context(context)
        {
          std::array<std::vector<double>, dim - 1> coords;
          unsigned int                             n = 1;
          for (unsigned int k = 0; k < dim - 1; ++k)
            {
              const auto &b = grid.breaks[k];
              for (unsigned int e = 0; e + 1 < b.size(); ++e)
                {
                  coords[k].push_back(b[e]);
                  coords[k].push_back(0.5 * (b[e] + b[e + 1]));
                }
              coords[k].push_back(b.back());
              n *= coords[k].size();
              extent = std::max(extent, b.back() - b.front());
            }
          std::vector<Point<dim>> sample_x;
          for (unsigned int i = 0; i < n; ++i)
            {
              Point<dim - 1> eta;
              unsigned int   rest = i;
              for (unsigned int k = 0; k < dim - 1; ++k)
                {
                  eta[k] = coords[k][rest % coords[k].size()];
                  rest /= coords[k].size();
                }
              sample_eta.push_back(eta);
              sample_x.push_back(master.face_point(eta).location);
            }
          index =
            std::make_unique<base::NearestPoints<dim>>(std::move(sample_x));
        }

        /**
         * The face coordinates of the point of the face closest to @p x:
         * Newton's method on f = |x - x(eta)|^2 / 2 with the curvature term
         * (the tangents' derivatives by central differences), Gauss-Newton
         * where that Hessian is not positive definite, each step shortened
         * until f falls enough (Armijo). Gauss-Newton alone, without the
         * curvature term, diverges on a curved face from a point farther
         * than twice the radius of curvature from its centre (on a circle
         * of radius r its step scales the angle error by 1 - d / r at
         * distance d from the centre): the points of a large slave cylinder
         * outside the contact zone of a small master one.
         */
        Point<dim - 1>
        project(const Point<dim> &x) const
        {
          constexpr int n       = dim - 1;
          const auto    clamped = [&](Point<n> eta) {
            for (unsigned int k = 0; k < n; ++k)
              eta[k] = std::clamp(eta[k],
                                  grid.breaks[k].front(),
                                  grid.breaks[k].back());
            return eta;
          };
          const auto objective = [&](const Point<n> &eta) {
            return 0.5 * (x - master.face_point(eta).location).norm_square();
          };
          Point<n> eta = sample_eta[index->nearest(x)];
          double   f   = objective(eta);
          for (unsigned int it = 0; it < 100; ++it)
            {
              const auto           fp = master.face_point(eta);
              const Tensor<1, dim> r  = x - fp.location;
              // Descent direction -grad f = T^T r; Gauss-Newton matrix T^T T.
              Tensor<1, n> g;
              Tensor<2, n> gn, H;
              for (unsigned int a = 0; a < n; ++a)
                {
                  g[a] = fp.tangents[a] * r;
                  for (unsigned int b = 0; b < n; ++b)
                    gn[a][b] = fp.tangents[a] * fp.tangents[b];
                }
              // Curvature term - r . d t_a / d eta_b, by central differences
              // inside the face.
              H = gn;
              for (unsigned int b = 0; b < n; ++b)
                {
                  const double h =
                    1e-6 * (grid.breaks[b].back() - grid.breaks[b].front());
                  Point<n> up = eta, down = eta;
                  up[b]         = std::min(eta[b] + h, grid.breaks[b].back());
                  down[b]       = std::max(eta[b] - h, grid.breaks[b].front());
                  const auto pu = master.face_point(up);
                  const auto pd = master.face_point(down);
                  for (unsigned int a = 0; a < n; ++a)
                    H[a][b] -=
                      r * (pu.tangents[a] - pd.tangents[a]) / (up[b] - down[b]);
                }
              H = 0.5 * (H + transpose(H));
              // Coordinates on a bound that the descent direction g pushes
              // past stay there (projected Newton); the others take the
              // step of their own block.
              std::array<bool, n> held;
              for (unsigned int k = 0; k < n; ++k)
                held[k] = (eta[k] <= grid.breaks[k].front() && g[k] < 0.) ||
                          (eta[k] >= grid.breaks[k].back() && g[k] > 0.);
              const bool   newton = H[0][0] > 0. && determinant(H) > 0.;
              Tensor<1, n> step   = invert(newton ? H : gn) * g;
              if (std::any_of(held.begin(), held.end(), [](bool h) {
                    return h;
                  }))
                for (unsigned int k = 0; k < n; ++k)
                  step[k] =
                    held[k] ? 0. : g[k] / (H[k][k] > 0. ? H[k][k] : gn[k][k]);
              // A step below what counts as a move (1e-14 of the face's
              // extent) is the minimum within round-off: done, without
              // the line search's halvings, each a face evaluation, that
              // would only confirm it.
              bool negligible = true;
              for (unsigned int k = 0; k < n; ++k)
                negligible = negligible && std::abs(step[k]) <=
                                             1e-14 * (grid.breaks[k].back() -
                                                      grid.breaks[k].front());
              if (negligible)
                return eta;
              // Shortened until f falls by a tenth of a thousandth of the
              // linear model's decrease; none does at the minimum (within
              // round-off), which ends the search.
              bool moved = false;
              for (double alpha = 1.; alpha > 1e-12; alpha *= 0.5)
                {
                  const Point<n> next   = clamped(eta + alpha * step);
                  const double   f_next = objective(next);
                  if (f_next <= f - 1e-4 * (g * (next - eta)) && f_next < f)
                    {
                      for (unsigned int k = 0; k < n; ++k)
                        moved = moved || std::abs(next[k] - eta[k]) >
                                           1e-14 * (grid.breaks[k].back() -
                                                    grid.breaks[k].front());
                      eta = next;
                      f   = f_next;
                      break;
                    }
                }
              if (!moved)
                return eta;
            }
          AssertThrow(
            false,
            base::ExcInput(
              context + ": the closest point projection of (" +
              base::to_string(x) + ") on " + master.description() +
              " did not settle in 100 safeguarded Newton steps (the point "
              "is " +
              std::to_string(std::sqrt(2. * f)) +
              " from the face); the face may fold back on itself near "
              "there. Cut the slave face to the part that faces the master "
              "(Contact/Slave face), or swap Contact/Slave face and "
              "Contact/Master face."));
          return eta;
        }

        const ContactSurface<dim>          &master;
        const discretization::FaceGrid<dim> grid;

      private:
        const std::string                         context;
        double                                    extent = 0.;
        std::vector<Point<dim - 1>>               sample_eta;
        std::unique_ptr<base::NearestPoints<dim>> index;
      };



      /**
       * The master surface as the slave integration sees it: one
       * closest-point projector per master face when it is deformable (a
       * surface over several patches has one face coordinate system per
       * patch face), the closest point of the obstacle otherwise.
       */
      template <int dim>
      class MasterSide
      {
      public:
        MasterSide(const ContactSurface<dim> &master,
                   const std::string         &context)
          : master(master)
          , parts(master.parts())
        {
          if (master.deformable())
            for (const ContactSurface<dim> *part : parts)
              projectors.push_back(
                std::make_unique<FaceProjector<dim>>(*part, context));
        }

        /// The master face holding the point closest to @p x, and the
        /// point's face coordinates there.
        std::pair<unsigned int, Point<dim - 1>>
        project(const Point<dim> &x) const
        {
          if (projectors.size() == 1)
            return std::make_pair(0u, projectors[0]->project(x));
          // A face far from x may leave the clamped Gauss-Newton cycling on
          // its edge: such a face is not the closest one.
          std::pair<unsigned int, Point<dim - 1>> best;
          double best_distance = std::numeric_limits<double>::max();
          for (unsigned int k = 0; k < projectors.size(); ++k)
            try
              {
                const Point<dim - 1> eta = projectors[k]->project(x);
                const double         distance =
                  parts[k]->face_point(eta).location.distance(x);
                if (distance < best_distance)
                  {
                    best_distance = distance;
                    best          = {k, eta};
                  }
              }
            catch (const ExceptionBase &)
              {
                if (k + 1 == projectors.size() &&
                    best_distance == std::numeric_limits<double>::max())
                  throw;
              }
          return best;
        }

        /// The master point facing the slave point @p x: location, normal
        /// and operator; on a deformable master also its face (@p part) and
        /// face coordinates (@p xi) where those are not nullptr.
        discretization::FacePoint<dim>
        facing(const Point<dim> &x,
               unsigned int     *part = nullptr,
               Point<dim - 1>   *xi   = nullptr) const
        {
          discretization::FacePoint<dim> m;
          if (!projectors.empty())
            {
              const auto [k, eta] = project(x);
              m                   = parts[k]->face_point(eta);
              if (part != nullptr)
                *part = k;
              if (xi != nullptr)
                *xi = eta;
            }
          else
            {
              const auto cp = master.closest_point(x, nullptr);
              m.location    = cp.location;
              m.normal      = cp.normal;
            }
          return m;
        }

        const ContactSurface<dim>                       &master;
        const std::vector<const ContactSurface<dim> *>   parts;
        std::vector<std::unique_ptr<FaceProjector<dim>>> projectors;
      };
    } // namespace internal
  }   // namespace contact
} // namespace igabde

#endif
