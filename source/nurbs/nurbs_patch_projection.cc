#include <igabde/nurbs/nurbs_patch.h>

#include <deal.II/base/exceptions.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace igabde
{
  namespace nurbs
  {
    template <int dim>
    Point<dim>
    NurbsPatch<dim>::minimize_distance(const Point<dim>            &x,
                                       Point<dim>                   xi,
                                       const std::array<bool, dim> &fixed,
                                       double *distance) const
    {
      const Point<dim> lo = parametric_lower(), hi = parametric_upper();
      double           scale = 0.;
      for (unsigned int d = 0; d < dim; ++d)
        scale = std::max(scale, hi[d] - lo[d]);
      // Physical size, for the stopping test.
      const double size = physical_size;

      auto objective = [&](const Point<dim> &z) {
        return 0.5 * (value(z) - x).norm_square();
      };

      double f = objective(xi);
      for (unsigned int it = 0; it < 100; ++it)
        {
          const Tensor<1, dim> r = value(xi) - x;
          const Tensor<2, dim> J = jacobian(xi);
          const Tensor<1, dim> g = transpose(J) * r;

          // Hessian of f: J^T J + sum_i r_i d^2 x_i / dxi^2, the second
          // derivatives by central differences of J (they only affect the
          // convergence rate, not the converged point).
          Tensor<2, dim> H = transpose(J) * J;
          Tensor<2, dim> H2;
          const double   h = 1e-6 * scale;
          for (unsigned int b = 0; b < dim; ++b)
            {
              Point<dim> xp = xi, xm = xi;
              xp[b] = std::min(xi[b] + h, hi[b]);
              xm[b] = std::max(xi[b] - h, lo[b]);
              const Tensor<2, dim> dJ =
                (jacobian(xp) - jacobian(xm)) / (xp[b] - xm[b]);
              for (unsigned int a = 0; a < dim; ++a)
                for (unsigned int i = 0; i < dim; ++i)
                  H2[a][b] += r[i] * dJ[i][a];
            }
          H2 = 0.5 * (H2 + transpose(H2));

          // Active set: fixed coordinates and bounds the gradient pushes on.
          std::array<bool, dim> active;
          for (unsigned int d = 0; d < dim; ++d)
            active[d] = fixed[d] || (xi[d] <= lo[d] && g[d] > 0.) ||
                        (xi[d] >= hi[d] && g[d] < 0.);

          auto solve_free = [&](const Tensor<2, dim> &M, Tensor<1, dim> &s) {
            FullMatrix<double> Mf(dim, dim);
            for (unsigned int a = 0; a < dim; ++a)
              for (unsigned int b = 0; b < dim; ++b)
                Mf(a, b) =
                  (active[a] || active[b]) ? (a == b ? 1. : 0.) : M[a][b];
            // Positive definite? Cholesky-like check through the
            // determinants of the leading minors is overkill: test s.g < 0.
            const double detM = Mf.determinant();
            if (!(std::abs(detM) > 0.) || !std::isfinite(detM))
              return false;
            Mf.gauss_jordan();
            Vector<double> rhs(dim), sol(dim);
            for (unsigned int a = 0; a < dim; ++a)
              rhs[a] = active[a] ? 0. : -g[a];
            Mf.vmult(sol, rhs);
            for (unsigned int a = 0; a < dim; ++a)
              s[a] = active[a] ? 0. : sol[a];
            return s * g < 0.;
          };

          Tensor<1, dim> step;
          bool           ok = solve_free(H + H2, step);
          if (!ok)
            {
              // Gauss-Newton with a little regularisation.
              Tensor<2, dim> M  = H;
              double         tr = 0.;
              for (unsigned int a = 0; a < dim; ++a)
                tr += H[a][a];
              for (unsigned int a = 0; a < dim; ++a)
                M[a][a] += 1e-12 * tr + 1e-300;
              ok = solve_free(M, step);
            }
          if (!ok)
            break;

          // Backtracking on f along the projected path.
          double     t = 1.;
          Point<dim> trial;
          double     f_trial = f;
          for (unsigned int ls = 0; ls < 40; ++ls, t *= 0.5)
            {
              trial = xi;
              for (unsigned int d = 0; d < dim; ++d)
                trial[d] = std::clamp(xi[d] + t * step[d], lo[d], hi[d]);
              f_trial = objective(trial);
              if (f_trial <= f)
                break;
            }
          const double moved = (trial - xi).norm();
          if (f_trial > f)
            break;
          xi                 = trial;
          const double f_old = f;
          f                  = f_trial;
          if (moved <= 1e-15 * scale || std::sqrt(2. * f) <= 1e-15 * size ||
              (f_old - f) <= 1e-30 * size * size)
            break;
        }
      if (distance != nullptr)
        *distance = (value(xi) - x).norm();
      return xi;
    }



    template <int dim>
    Point<dim>
    NurbsPatch<dim>::nearest_sample(
      const std::array<std::vector<double>, dim> &samples,
      const Point<dim>                           &x) const
    {
      // The sampled point whose image is nearest to x starts the Newton
      // projection.
      Point<dim> xi;
      double     best = std::numeric_limits<double>::max();
      for (const Point<dim> &z : tensor_product_points<dim>(samples))
        {
          const double dist = (value(z) - x).norm_square();
          if (dist < best)
            {
              best = dist;
              xi   = z;
            }
        }
      return xi;
    }



    template <int dim>
    Point<dim>
    NurbsPatch<dim>::closest_parametric_point(const Point<dim> &x,
                                              const Point<dim> *start,
                                              double           *distance) const
    {
      Point<dim> xi;
      if (start != nullptr)
        xi = *start;
      else
        {
          // Sample the images of the breakpoints and span midpoints.
          std::array<std::vector<double>, dim> samples;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const auto b = breakpoints(d);
              for (unsigned int e = 0; e + 1 < b.size(); ++e)
                {
                  samples[d].push_back(b[e]);
                  samples[d].push_back(0.5 * (b[e] + b[e + 1]));
                }
              samples[d].push_back(b.back());
            }
          xi = nearest_sample(samples, x);
        }
      std::array<bool, dim> fixed;
      fixed.fill(false);
      return minimize_distance(x, xi, fixed, distance);
    }



    template <int dim>
    Point<dim>
    NurbsPatch<dim>::closest_point_on_face(const unsigned int face,
                                           const Point<dim>  &x,
                                           const Point<dim>  *near) const
    {
      AssertThrow(face < 2 * dim,
                  ExcMessage("NurbsPatch: face " + std::to_string(face) +
                             " does not exist; faces are 0.." +
                             std::to_string(2 * dim - 1) + "."));
      const unsigned int d = face / 2;
      const double       value_d =
        (face % 2 == 0 ? knots[d].front() : knots[d].back());
      std::array<bool, dim> fixed;
      fixed.fill(false);
      fixed[d] = true;

      // Sample the face at breakpoints and three points per span, over
      // the spans [first, last) of each direction: all of them, or those
      // within one span of near's. Returns the Newton answer and whether
      // it lies in the sampled spans.
      const auto project_from_samples = [&](const bool local) {
        std::array<std::vector<double>, dim> samples;
        Point<dim>                           lo, hi;
        for (unsigned int e = 0; e < dim; ++e)
          {
            if (e == d)
              {
                samples[e] = {value_d};
                lo[e] = hi[e] = value_d;
                continue;
              }
            const auto   b     = breakpoints(e);
            unsigned int first = 0, last = b.size() - 1;
            if (local)
              {
                const unsigned int span = static_cast<unsigned int>(
                  std::upper_bound(b.begin(), b.end() - 1, (*near)[e]) -
                  b.begin() - 1);
                first = (span > 0 ? span - 1 : 0);
                last  = std::min<unsigned int>(span + 2, b.size() - 1);
              }
            for (unsigned int s = first; s < last; ++s)
              for (unsigned int j = 0; j < 4; ++j)
                samples[e].push_back(b[s] + (b[s + 1] - b[s]) * j / 4.);
            samples[e].push_back(b[last]);
            lo[e] = b[first];
            hi[e] = b[last];
          }
        const Point<dim> xi =
          minimize_distance(x, nearest_sample(samples, x), fixed, nullptr);
        bool inside = true;
        for (unsigned int e = 0; e < dim; ++e)
          inside = inside && xi[e] >= lo[e] && xi[e] <= hi[e];
        return std::make_pair(xi, inside);
      };

      if (near == nullptr)
        return project_from_samples(false).first;
      // Thousands of pairs project onto faces of hundreds of spans: the
      // whole face's samples for every point were slow already on V7's
      // 20 x 20 face (doc/architecture.md). The answer near's spans give stands
      // when Newton stayed in them; otherwise near was not near, and the whole
      // face is sampled.
      const auto [xi, inside] = project_from_samples(true);
      if (inside)
        return xi;
      return project_from_samples(false).first;
    }



    template Point<2>
    NurbsPatch<2>::minimize_distance(const Point<2> &,
                                     Point<2>,
                                     const std::array<bool, 2> &,
                                     double *) const;
    template Point<2>
    NurbsPatch<2>::nearest_sample(const std::array<std::vector<double>, 2> &,
                                  const Point<2> &) const;
    template Point<2>
    NurbsPatch<2>::closest_parametric_point(const Point<2> &,
                                            const Point<2> *,
                                            double *) const;
    template Point<2>
    NurbsPatch<2>::closest_point_on_face(unsigned int,
                                         const Point<2> &,
                                         const Point<2> *) const;
    template Point<3>
    NurbsPatch<3>::minimize_distance(const Point<3> &,
                                     Point<3>,
                                     const std::array<bool, 3> &,
                                     double *) const;
    template Point<3>
    NurbsPatch<3>::nearest_sample(const std::array<std::vector<double>, 3> &,
                                  const Point<3> &) const;
    template Point<3>
    NurbsPatch<3>::closest_parametric_point(const Point<3> &,
                                            const Point<3> *,
                                            double *) const;
    template Point<3>
    NurbsPatch<3>::closest_point_on_face(unsigned int,
                                         const Point<3> &,
                                         const Point<3> *) const;
  } // namespace nurbs
} // namespace igabde
