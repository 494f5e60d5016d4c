#include <igabde/nurbs/knot_vector.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <sstream>

namespace igabde
{
  namespace nurbs
  {
    namespace
    {
      std::string
      knots_to_string(const std::vector<double> &u)
      {
        std::ostringstream s;
        s << "[";
        for (unsigned int i = 0; i < u.size(); ++i)
          s << (i > 0 ? " " : "") << u[i];
        s << "]";
        return s.str();
      }



      /**
       * The table ndu of P&T A2.3 at @p x in @p span: the basis functions
       * of degree 0..p in its upper triangle (ndu[r][j]), the knot
       * differences in its lower one. @p Table is anything indexed as
       * ndu[i][j] with at least p+1 rows and columns, @p Buffer likewise
       * as left[j] (the heap tables of basis_function_derivatives() and the
       * stack ones of basis_and_first_derivatives() give the same numbers).
       */
      template <typename Table, typename Buffer>
      void
      fill_ndu_table(const std::vector<double> &u,
                     const unsigned int         p,
                     const double               x,
                     const unsigned int         span,
                     Table                     &ndu,
                     Buffer                    &left,
                     Buffer                    &right)
      {
        ndu[0][0] = 1.;
        for (unsigned int j = 1; j <= p; ++j)
          {
            left[j]      = x - u[span + 1 - j];
            right[j]     = u[span + j] - x;
            double saved = 0.;
            for (unsigned int r = 0; r < j; ++r)
              {
                // Lower triangle: knot differences.
                ndu[j][r]         = right[r + 1] + left[j - r];
                const double temp = ndu[r][j - 1] / ndu[j][r];
                // Upper triangle: basis functions.
                ndu[r][j] = saved + right[r + 1] * temp;
                saved     = left[j - r] * temp;
              }
            ndu[j][j] = saved;
          }
      }
    } // namespace



    KnotVector::KnotVector(const unsigned int         degree,
                           const std::vector<double> &knots)
      : p(degree)
      , u(knots)
    {
      const std::string where = "Knot vector " + knots_to_string(u) +
                                " of degree " + std::to_string(p) + ": ";
      AssertThrow(p >= 1, ExcMessage(where + "the degree must be at least 1."));
      AssertThrow(u.size() >= 2 * (p + 1),
                  ExcMessage(where + "too few knots (" +
                             std::to_string(u.size()) +
                             "); an open knot vector of degree p needs at "
                             "least 2(p+1) = " +
                             std::to_string(2 * (p + 1)) +
                             " knots, e.g. [0 ... 0 1 ... 1] with p+1 copies "
                             "of each end."));
      for (unsigned int i = 0; i + 1 < u.size(); ++i)
        AssertThrow(u[i] <= u[i + 1],
                    ExcMessage(where + "knots must be non-decreasing, but u_" +
                               std::to_string(i) + " > u_" +
                               std::to_string(i + 1) + "; sort the knots."));
      AssertThrow(u.front() < u.back(),
                  ExcMessage(where + "all knots are equal; the parametric "
                                     "interval must have positive length."));
      for (unsigned int i = 1; i <= p; ++i)
        AssertThrow(u[i] == u[0] && u[u.size() - 1 - i] == u.back(),
                    ExcMessage(where +
                               "the knot vector is not open: the first and "
                               "the last knot must each be repeated p+1 = " +
                               std::to_string(p + 1) +
                               " times (clamped ends), so that the patch "
                               "interpolates its boundary control points."));
      AssertThrow(
        u[p + 1] > u[0] && u[u.size() - p - 2] < u.back(),
        ExcMessage(where + "an end knot is repeated more than p+1 = " +
                   std::to_string(p + 1) + " times; remove the extra copies."));
      const std::vector<double>       b = breakpoints();
      const std::vector<unsigned int> m = multiplicities();
      for (unsigned int i = 1; i + 1 < b.size(); ++i)
        AssertThrow(m[i] <= p,
                    ExcMessage(
                      where + "the interior knot " + std::to_string(b[i]) +
                      " is repeated " + std::to_string(m[i]) +
                      " times, more than the degree p = " + std::to_string(p) +
                      ", which makes the basis discontinuous; use "
                      "at most p copies (p copies give C0)."));
    }



    KnotVector
    KnotVector::uniform(const unsigned int degree,
                        const unsigned int n_spans,
                        const double       a,
                        const double       b)
    {
      AssertThrow(n_spans >= 1,
                  ExcMessage("KnotVector::uniform: at least one span needed."));
      AssertThrow(a < b,
                  ExcMessage("KnotVector::uniform: the interval [a, b] must "
                             "have a < b."));
      std::vector<double> knots(degree + 1, a);
      for (unsigned int i = 1; i < n_spans; ++i)
        knots.push_back(a + (b - a) * i / n_spans);
      knots.insert(knots.end(), degree + 1, b);
      return KnotVector(degree, knots);
    }



    unsigned int
    KnotVector::degree() const
    {
      return p;
    }



    const std::vector<double> &
    KnotVector::knots() const
    {
      return u;
    }



    unsigned int
    KnotVector::n_basis_functions() const
    {
      return u.size() - p - 1;
    }



    double
    KnotVector::front() const
    {
      return u.front();
    }



    double
    KnotVector::back() const
    {
      return u.back();
    }



    unsigned int
    KnotVector::find_span(const double x) const
    {
      Assert(!u.empty(), ExcMessage("Empty knot vector."));
      const unsigned int n = n_basis_functions();
      if (x >= u[n])
        return n - 1;
      if (x <= u[p])
        return p;
      // Largest k with u_k <= x, which then has u_k < u_{k+1}.
      const auto it = std::upper_bound(u.begin() + p, u.begin() + n + 1, x);
      return static_cast<unsigned int>(it - u.begin()) - 1;
    }



    std::vector<double>
    KnotVector::breakpoints() const
    {
      std::vector<double> b;
      for (const double x : u)
        if (b.empty() || x != b.back())
          b.push_back(x);
      return b;
    }



    std::vector<unsigned int>
    KnotVector::multiplicities() const
    {
      std::vector<double>       b;
      std::vector<unsigned int> m;
      for (const double x : u)
        if (b.empty() || x != b.back())
          {
            b.push_back(x);
            m.push_back(1);
          }
        else
          ++m.back();
      return m;
    }



    unsigned int
    KnotVector::n_spans() const
    {
      return breakpoints().size() - 1;
    }



    unsigned int
    KnotVector::span_knot_index(const unsigned int e) const
    {
      unsigned int count = 0;
      for (unsigned int k = p; k + 1 < u.size(); ++k)
        if (u[k] < u[k + 1])
          {
            if (count == e)
              return k;
            ++count;
          }
      AssertThrow(false,
                  ExcMessage("KnotVector::span_knot_index: span " +
                             std::to_string(e) + " does not exist; there are " +
                             std::to_string(count) + " non-empty spans."));
      return 0;
    }



    unsigned int
    KnotVector::element_of(const double x) const
    {
      const unsigned int k     = find_span(x);
      unsigned int       count = 0;
      for (unsigned int i = p; i < k; ++i)
        if (u[i] < u[i + 1])
          ++count;
      return count;
    }



    std::vector<double>
    KnotVector::greville_abscissae() const
    {
      const unsigned int  n = n_basis_functions();
      std::vector<double> g(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          double s = 0.;
          for (unsigned int j = 1; j <= p; ++j)
            s += u[i + j];
          g[i] = s / p;
        }
      // Round-off may leave the end values a hair off the interval.
      g.front() = u.front();
      g.back()  = u.back();
      return g;
    }



    void
    KnotVector::basis_functions(const double         x,
                                const unsigned int   span,
                                std::vector<double> &N) const
    {
      N.assign(p + 1, 0.);
      std::vector<double> left(p + 1), right(p + 1);
      N[0] = 1.;
      for (unsigned int j = 1; j <= p; ++j)
        {
          left[j]      = x - u[span + 1 - j];
          right[j]     = u[span + j] - x;
          double saved = 0.;
          for (unsigned int r = 0; r < j; ++r)
            {
              const double temp = N[r] / (right[r + 1] + left[j - r]);
              N[r]              = saved + right[r + 1] * temp;
              saved             = left[j - r] * temp;
            }
          N[j] = saved;
        }
    }



    void
    KnotVector::basis_function_derivatives(
      const double                      x,
      const unsigned int                span,
      const unsigned int                n_derivatives,
      std::vector<std::vector<double>> &ders) const
    {
      const unsigned int n = std::min(n_derivatives, p);
      ders.assign(n_derivatives + 1, std::vector<double>(p + 1, 0.));

      std::vector<std::vector<double>> ndu(p + 1, std::vector<double>(p + 1));
      std::vector<double>              left(p + 1), right(p + 1);
      fill_ndu_table(u, p, x, span, ndu, left, right);
      for (unsigned int j = 0; j <= p; ++j)
        ders[0][j] = ndu[j][p];

      std::vector<std::vector<double>> a(2, std::vector<double>(p + 1));
      for (int r = 0; r <= static_cast<int>(p); ++r)
        {
          int s1 = 0, s2 = 1;
          a[0][0] = 1.;
          for (int k = 1; k <= static_cast<int>(n); ++k)
            {
              double    d  = 0.;
              const int rk = r - k;
              const int pk = static_cast<int>(p) - k;
              if (r >= k)
                {
                  a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                  d        = a[s2][0] * ndu[rk][pk];
                }
              const int j1 = (rk >= -1 ? 1 : -rk);
              const int j2 = (r - 1 <= pk ? k - 1 : static_cast<int>(p) - r);
              for (int j = j1; j <= j2; ++j)
                {
                  a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
                  d += a[s2][j] * ndu[rk + j][pk];
                }
              if (r <= pk)
                {
                  a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                  d += a[s2][k] * ndu[r][pk];
                }
              ders[k][r] = d;
              std::swap(s1, s2);
            }
        }
      double factor = p;
      for (unsigned int k = 1; k <= n; ++k)
        {
          for (unsigned int j = 0; j <= p; ++j)
            ders[k][j] *= factor;
          factor *= static_cast<double>(p) - k;
        }
    }



    void
    KnotVector::basis_and_first_derivatives(const double       x,
                                            const unsigned int span,
                                            double            *values,
                                            double *derivatives) const
    {
      // P&T A2.3 for one derivative, on the stack: the table ndu of
      // basis_function_derivatives(), then its a-table recursion for k = 1
      // written out (a[0] = 1 / ndu[p][r-1], a[1] = -1 / ndu[p][r]).
      constexpr unsigned int m = max_fast_degree + 1;
      AssertThrow(p <= max_fast_degree,
                  ExcMessage("KnotVector: degree " + std::to_string(p) +
                             " is above the fast basis' " +
                             std::to_string(max_fast_degree)));
      double ndu[m][m], left[m], right[m];
      fill_ndu_table(u, p, x, span, ndu, left, right);
      for (unsigned int j = 0; j <= p; ++j)
        values[j] = ndu[j][p];
      if (p == 0)
        {
          derivatives[0] = 0.;
          return;
        }
      for (unsigned int r = 0; r <= p; ++r)
        {
          double d = 0.;
          if (r >= 1)
            {
              const double a0 = 1. / ndu[p][r - 1];
              d               = a0 * ndu[r - 1][p - 1];
            }
          if (r + 1 <= p)
            {
              const double a1 = -1. / ndu[p][r];
              d += a1 * ndu[r][p - 1];
            }
          derivatives[r] = d * static_cast<double>(p);
        }
    }



    std::vector<FullMatrix<double>>
    KnotVector::bezier_extraction_operators() const
    {
      // Borden et al. (2011), Algorithm 1, with 0-based knot and matrix
      // indices: knot U(i) of the paper is u[i-1], C(r, c) is C(r-1, c-1).
      const unsigned int              m  = u.size();
      const unsigned int              ne = n_spans();
      std::vector<FullMatrix<double>> C(ne + 1, IdentityMatrix(p + 1));
      std::vector<double>             alphas(p + 1);

      unsigned int a  = p;
      unsigned int b  = a + 1;
      unsigned int nb = 0;
      while (b < m - 1)
        {
          const unsigned int i = b;
          while (b < m - 1 && u[b + 1] == u[b])
            ++b;
          const unsigned int mult = b - i + 1;
          if (mult < p)
            {
              const double numer = u[b] - u[a];
              for (unsigned int j = p; j > mult; --j)
                alphas[j - mult - 1] = numer / (u[a + j] - u[a]);
              const unsigned int r = p - mult;
              for (unsigned int j = 1; j <= r; ++j)
                {
                  const unsigned int save = r - j; // 0-based column
                  const unsigned int s    = mult + j;
                  for (unsigned int k = p; k >= s; --k)
                    {
                      const double alpha = alphas[k - s];
                      for (unsigned int row = 0; row <= p; ++row)
                        C[nb](row, k) = alpha * C[nb](row, k) +
                                        (1. - alpha) * C[nb](row, k - 1);
                    }
                  if (b < m - 1)
                    for (unsigned int l = 0; l <= j; ++l)
                      C[nb + 1](save + l, save) = C[nb](p - j + l, p);
                }
            }
          ++nb;
          if (b < m - 1)
            {
              a = b;
              ++b;
            }
        }
      C.resize(ne);
      return C;
    }



    KnotVector
    KnotVector::elevated(const unsigned int t) const
    {
      const std::vector<double>       b = breakpoints();
      const std::vector<unsigned int> m = multiplicities();
      std::vector<double>             knots;
      for (unsigned int i = 0; i < b.size(); ++i)
        knots.insert(knots.end(), m[i] + t, b[i]);
      return KnotVector(p + t, knots);
    }



    bool
    KnotVector::operator==(const KnotVector &other) const
    {
      return p == other.p && u == other.u;
    }
  } // namespace nurbs
} // namespace igabde
