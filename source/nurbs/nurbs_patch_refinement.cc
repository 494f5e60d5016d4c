#include <igabde/nurbs/nurbs_patch.h>

#include <deal.II/base/exceptions.h>

#include <deal.II/lac/full_matrix.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace igabde
{
  namespace nurbs
  {
    template <int dim>
    void
    NurbsPatch<dim>::insert_knots(const unsigned int         d,
                                  const std::vector<double> &new_knots)
    {
      AssertIndexRange(d, dim);
      if (new_knots.empty())
        return;
      std::vector<double> sorted = new_knots;
      std::sort(sorted.begin(), sorted.end());

      const unsigned int  p     = degree(d);
      std::vector<double> u     = knots[d].knots();
      const unsigned int  n_old = u.size() - p - 1;

      // T maps old to new control points; start from the identity and apply
      // Boehm's single-knot insertion (P&T A5.1) to its rows, one knot at a
      // time: Q_i = alpha_i P_i + (1 - alpha_i) P_{i-1}.
      std::vector<std::vector<std::pair<unsigned int, double>>> T(n_old);
      for (unsigned int i = 0; i < n_old; ++i)
        T[i] = {{i, 1.}};

      for (const double x : sorted)
        {
          AssertThrow(x > u.front() && x < u.back(),
                      ExcMessage("NurbsPatch::insert_knots: knot " +
                                 std::to_string(x) +
                                 " is not strictly inside the parametric "
                                 "interval [" +
                                 std::to_string(u.front()) + ", " +
                                 std::to_string(u.back()) + "] of direction " +
                                 std::to_string(d) + "."));
          const KnotVector   kv(p, u);
          const unsigned int k = kv.find_span(x);
          const unsigned int n = u.size() - p - 1;
          std::vector<std::vector<std::pair<unsigned int, double>>> Tn(n + 1);
          auto                                                      combine =
            [](const std::vector<std::pair<unsigned int, double>> &a,
               const double                                        alpha,
               const std::vector<std::pair<unsigned int, double>> &b,
               const double                                        beta) {
              std::vector<std::pair<unsigned int, double>> r;
              for (const auto &e : a)
                r.emplace_back(e.first, alpha * e.second);
              for (const auto &e : b)
                {
                  auto it =
                    std::find_if(r.begin(), r.end(), [&](const auto &f) {
                      return f.first == e.first;
                    });
                  if (it != r.end())
                    it->second += beta * e.second;
                  else
                    r.emplace_back(e.first, beta * e.second);
                }
              return r;
            };
          for (unsigned int i = 0; i <= n; ++i)
            {
              if (i + p <= k)
                Tn[i] = T[i];
              else if (i >= k + 1)
                Tn[i] = T[i - 1];
              else
                {
                  const double alpha = (x - u[i]) / (u[i + p] - u[i]);
                  Tn[i] = combine(T[i], alpha, T[i - 1], 1. - alpha);
                }
            }
          T = std::move(Tn);
          u.insert(u.begin() + k + 1, x);
        }
      // Validates the multiplicities (at most p in the interior).
      const KnotVector new_kv(p, u);
      transform_direction(d, new_kv, T);
    }



    template <int dim>
    void
    NurbsPatch<dim>::refine_uniformly(const unsigned int n_per_span)
    {
      if (n_per_span == 0)
        return;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const std::vector<double> b = breakpoints(d);
          std::vector<double>       new_knots;
          for (unsigned int e = 0; e + 1 < b.size(); ++e)
            for (unsigned int j = 1; j <= n_per_span; ++j)
              new_knots.push_back(b[e] +
                                  (b[e + 1] - b[e]) * j / (n_per_span + 1.));
          insert_knots(d, new_knots);
        }
    }



    template <int dim>
    void
    NurbsPatch<dim>::elevate_degree(const unsigned int d, const unsigned int t)
    {
      AssertIndexRange(d, dim);
      if (t == 0)
        return;
      // The elevated space contains the old one, so the homogeneous curve
      // (w P, w) is reproduced exactly by interpolation at the Greville
      // abscissae of the new knot vector (Schoenberg-Whitney holds there):
      // Q = A_new^{-1} B_old P with A_new(i, j) = N^new_j(g_i) and
      // B_old(i, k) = N^old_k(g_i). Exact up to round-off, like P&T A5.9.
      const KnotVector   &old_kv = knots[d];
      const KnotVector    new_kv = old_kv.elevated(t);
      const unsigned int  n_old  = old_kv.n_basis_functions();
      const unsigned int  n_new  = new_kv.n_basis_functions();
      const auto          g      = new_kv.greville_abscissae();
      FullMatrix<double>  A(n_new, n_new), B(n_new, n_old);
      std::vector<double> N;
      for (unsigned int i = 0; i < n_new; ++i)
        {
          unsigned int k = new_kv.find_span(g[i]);
          new_kv.basis_functions(g[i], k, N);
          for (unsigned int j = 0; j <= new_kv.degree(); ++j)
            A(i, k - new_kv.degree() + j) = N[j];
          k = old_kv.find_span(g[i]);
          old_kv.basis_functions(g[i], k, N);
          for (unsigned int j = 0; j <= old_kv.degree(); ++j)
            B(i, k - old_kv.degree() + j) = N[j];
        }
      A.gauss_jordan();
      FullMatrix<double> M(n_new, n_old);
      A.mmult(M, B);
      std::vector<std::vector<std::pair<unsigned int, double>>> T(n_new);
      for (unsigned int i = 0; i < n_new; ++i)
        for (unsigned int j = 0; j < n_old; ++j)
          if (M(i, j) != 0.)
            T[i].emplace_back(j, M(i, j));
      transform_direction(d, new_kv, T);
    }


    template void
    NurbsPatch<2>::insert_knots(unsigned int, const std::vector<double> &);
    template void
    NurbsPatch<3>::insert_knots(unsigned int, const std::vector<double> &);
    template void
    NurbsPatch<2>::refine_uniformly(unsigned int);
    template void
    NurbsPatch<3>::refine_uniformly(unsigned int);
    template void
    NurbsPatch<2>::elevate_degree(unsigned int, unsigned int);
    template void
    NurbsPatch<3>::elevate_degree(unsigned int, unsigned int);
  } // namespace nurbs
} // namespace igabde
