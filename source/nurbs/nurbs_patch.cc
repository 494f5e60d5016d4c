#include <igabde/nurbs/nurbs_patch.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace igabde
{
  namespace nurbs
  {
    namespace
    {} // namespace



    template <int dim>
    Tensor<1, dim>
    cofactor_column(const Tensor<2, dim> &J, const unsigned int d)
    {
      Tensor<1, dim> n;
      if constexpr (dim == 2)
        {
          if (d == 0)
            {
              n[0] = J[1][1];
              n[1] = -J[0][1];
            }
          else
            {
              n[0] = -J[1][0];
              n[1] = J[0][0];
            }
        }
      else if constexpr (dim == 3)
        {
          const unsigned int d1 = (d + 1) % 3, d2 = (d + 2) % 3;
          Tensor<1, 3>       t1, t2;
          for (unsigned int i = 0; i < 3; ++i)
            {
              t1[i] = J[i][d1];
              t2[i] = J[i][d2];
            }
          const Tensor<1, 3> c = cross_product_3d(t1, t2);
          for (unsigned int i = 0; i < 3; ++i)
            n[i] = c[i];
        }
      else
        Assert(false, ExcNotImplemented());
      return n;
    }



    template <int dim>
    NurbsPatch<dim>::NurbsPatch(const std::array<KnotVector, dim> &knots,
                                const std::vector<Point<dim>> &control_points,
                                const std::vector<double>     &weights)
      : knots(knots)
      , points(control_points)
      , weights(weights)
    {
      unsigned int n = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          AssertThrow(knots[d].knots().size() > 0,
                      ExcMessage("NurbsPatch: the knot vector of direction " +
                                 std::to_string(d) + " is empty."));
          n *= knots[d].n_basis_functions();
        }
      AssertThrow(points.size() == n,
                  ExcMessage("NurbsPatch: the knot vectors define " +
                             std::to_string(n) + " control points, but " +
                             std::to_string(points.size()) +
                             " were given; give one point per tensor index, "
                             "direction 0 fastest."));
      AssertThrow(this->weights.size() == n,
                  ExcMessage("NurbsPatch: " + std::to_string(n) +
                             " control points but " +
                             std::to_string(this->weights.size()) +
                             " weights; give one weight per control point."));
      for (unsigned int a = 0; a < n; ++a)
        AssertThrow(this->weights[a] > 0.,
                    ExcMessage("NurbsPatch: the weight of control point " +
                               std::to_string(a) + " is " +
                               std::to_string(this->weights[a]) +
                               "; NURBS weights must be positive."));
      update_physical_size();
    }



    template <int dim>
    const KnotVector &
    NurbsPatch<dim>::knot_vector(const unsigned int d) const
    {
      AssertIndexRange(d, dim);
      return knots[d];
    }



    template <int dim>
    unsigned int
    NurbsPatch<dim>::n_control_points(const unsigned int d) const
    {
      AssertIndexRange(d, dim);
      return knots[d].n_basis_functions();
    }



    template <int dim>
    unsigned int
    NurbsPatch<dim>::n_control_points() const
    {
      return points.size();
    }



    template <int dim>
    const Point<dim> &
    NurbsPatch<dim>::control_point(const unsigned int a) const
    {
      AssertIndexRange(a, points.size());
      return points[a];
    }



    template <int dim>
    double
    NurbsPatch<dim>::weight(const unsigned int a) const
    {
      AssertIndexRange(a, weights.size());
      return weights[a];
    }



    template <int dim>
    unsigned int
    NurbsPatch<dim>::control_point_index(
      const std::array<unsigned int, dim> &ijk) const
    {
      unsigned int a = 0;
      for (int d = dim - 1; d >= 0; --d)
        {
          AssertIndexRange(ijk[d], n_control_points(d));
          a = a * n_control_points(d) + ijk[d];
        }
      return a;
    }



    template <int dim>
    std::array<unsigned int, dim>
    NurbsPatch<dim>::tensor_index(const unsigned int a) const
    {
      std::array<unsigned int, dim> ijk;
      unsigned int                  rest = a;
      for (unsigned int d = 0; d < dim; ++d)
        {
          ijk[d] = rest % n_control_points(d);
          rest /= n_control_points(d);
        }
      return ijk;
    }



    template <int dim>
    unsigned int
    NurbsPatch<dim>::degree(const unsigned int d) const
    {
      return knot_vector(d).degree();
    }



    template <int dim>
    Point<dim>
    NurbsPatch<dim>::parametric_lower() const
    {
      Point<dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = knots[d].front();
      return p;
    }



    template <int dim>
    Point<dim>
    NurbsPatch<dim>::parametric_upper() const
    {
      Point<dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = knots[d].back();
      return p;
    }



    template <int dim>
    void
    NurbsPatch<dim>::basis(const Point<dim>            &xi,
                           std::vector<unsigned int>   &indices,
                           std::vector<double>         &values,
                           std::vector<Tensor<1, dim>> *gradients) const
    {
      // Per direction the p+1 basis values ders[d][0] and derivatives
      // ders[d][1], on the stack (this runs at every surface and
      // quadrature point of the contact search).
      constexpr unsigned int        m = KnotVector::max_fast_degree + 1;
      std::array<unsigned int, dim> span;
      std::array<std::array<std::array<double, m>, 2>, dim> ders;
      unsigned int                                          n_local = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          AssertThrow(!knots[d].knots().empty(),
                      ExcMessage("NurbsPatch: evaluating an empty patch."));
          const double x = std::clamp(xi[d], knots[d].front(), knots[d].back());
          span[d]        = knots[d].find_span(x);
          if (knots[d].degree() <= KnotVector::max_fast_degree)
            knots[d].basis_and_first_derivatives(x,
                                                 span[d],
                                                 ders[d][0].data(),
                                                 ders[d][1].data());
          else
            AssertThrow(false,
                        ExcMessage(
                          "NurbsPatch: degree " +
                          std::to_string(knots[d].degree()) + " in direction " +
                          std::to_string(d) +
                          " is above the largest supported, " +
                          std::to_string(KnotVector::max_fast_degree)));
          n_local *= knots[d].degree() + 1;
        }

      indices.resize(n_local);
      values.resize(n_local);
      // The weighted derivatives, kept between calls on each thread.
      thread_local std::vector<Tensor<1, dim>> dN;
      dN.resize(n_local);
      double         W = 0.;
      Tensor<1, dim> dW;
      for (unsigned int l = 0; l < n_local; ++l)
        {
          std::array<unsigned int, dim> local, global;
          unsigned int                  rest = l;
          for (unsigned int d = 0; d < dim; ++d)
            {
              local[d]  = rest % (knots[d].degree() + 1);
              rest      = rest / (knots[d].degree() + 1);
              global[d] = span[d] - knots[d].degree() + local[d];
            }
          const unsigned int a = control_point_index(global);
          double             N = 1.;
          for (unsigned int d = 0; d < dim; ++d)
            N *= ders[d][0][local[d]];
          for (unsigned int b = 0; b < dim; ++b)
            {
              double g = 1.;
              for (unsigned int d = 0; d < dim; ++d)
                g *= ders[d][d == b ? 1 : 0][local[d]];
              dN[l][b] = weights[a] * g;
            }
          indices[l] = a;
          values[l]  = weights[a] * N;
          W += values[l];
          dW += dN[l];
        }

      if (gradients != nullptr)
        {
          gradients->resize(n_local);
          for (unsigned int l = 0; l < n_local; ++l)
            (*gradients)[l] = (dN[l] * W - values[l] * dW) / (W * W);
        }
      for (unsigned int l = 0; l < n_local; ++l)
        values[l] /= W;
    }



    template <int dim>
    Point<dim>
    NurbsPatch<dim>::value(const Point<dim> &xi) const
    {
      thread_local std::vector<unsigned int> indices;
      thread_local std::vector<double>       R;
      basis(xi, indices, R);
      Point<dim> x;
      for (unsigned int l = 0; l < indices.size(); ++l)
        x += R[l] * points[indices[l]];
      return x;
    }



    template <int dim>
    std::vector<Point<dim>>
    NurbsPatch<dim>::values_on_grid(
      const std::array<std::vector<double>, dim> &coordinates) const
    {
      // Per direction and coordinate: the span and its p+1 basis values.
      std::array<std::vector<unsigned int>, dim>        spans;
      std::array<std::vector<std::vector<double>>, dim> values;
      std::size_t                                       n_points = 1;
      unsigned int                                      n_local  = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          AssertThrow(!knots[d].knots().empty(),
                      ExcMessage("NurbsPatch: evaluating an empty patch."));
          for (const double u : coordinates[d])
            {
              const double x = std::clamp(u, knots[d].front(), knots[d].back());
              spans[d].push_back(knots[d].find_span(x));
              values[d].emplace_back();
              knots[d].basis_functions(x, spans[d].back(), values[d].back());
            }
          n_points *= coordinates[d].size();
          n_local *= knots[d].degree() + 1;
        }
      std::vector<Point<dim>> result(n_points);
      for (std::size_t q = 0; q < n_points; ++q)
        {
          std::array<unsigned int, dim> at;
          std::size_t                   rest = q;
          for (unsigned int d = 0; d < dim; ++d)
            {
              at[d] = rest % coordinates[d].size();
              rest /= coordinates[d].size();
            }
          Point<dim> x;
          double     W = 0.;
          for (unsigned int l = 0; l < n_local; ++l)
            {
              std::array<unsigned int, dim> global;
              unsigned int                  local = l;
              double                        N     = 1.;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const unsigned int p = knots[d].degree();
                  const unsigned int j = local % (p + 1);
                  local /= p + 1;
                  global[d] = spans[d][at[d]] - p + j;
                  N *= values[d][at[d]][j];
                }
              const unsigned int a  = control_point_index(global);
              const double       wN = weights[a] * N;
              x += wN * points[a];
              W += wN;
            }
          result[q] = x / W;
        }
      return result;
    }



    template <int dim>
    Tensor<2, dim>
    NurbsPatch<dim>::jacobian(const Point<dim> &xi) const
    {
      thread_local std::vector<unsigned int>   indices;
      thread_local std::vector<double>         R;
      thread_local std::vector<Tensor<1, dim>> dR;
      basis(xi, indices, R, &dR);
      Tensor<2, dim> J;
      for (unsigned int l = 0; l < indices.size(); ++l)
        J +=
          outer_product(static_cast<const Tensor<1, dim> &>(points[indices[l]]),
                        dR[l]);
      return J;
    }



    template <int dim>
    std::vector<double>
    NurbsPatch<dim>::breakpoints(const unsigned int d) const
    {
      return knot_vector(d).breakpoints();
    }



    template <int dim>
    std::vector<std::array<double, dim + 1>>
    NurbsPatch<dim>::homogeneous_control_points() const
    {
      std::vector<std::array<double, dim + 1>> pw(points.size());
      for (unsigned int a = 0; a < points.size(); ++a)
        {
          for (unsigned int c = 0; c < dim; ++c)
            pw[a][c] = weights[a] * points[a][c];
          pw[a][dim] = weights[a];
        }
      return pw;
    }



    template <int dim>
    void
    NurbsPatch<dim>::transform_direction(
      const unsigned int                                               d,
      const KnotVector                                                &new_kv,
      const std::vector<std::vector<std::pair<unsigned int, double>>> &T)
    {
      const auto         pw    = homogeneous_control_points();
      const unsigned int n_old = n_control_points(d);
      (void)n_old; // only used in assertions
      const unsigned int n_new = new_kv.n_basis_functions();
      AssertDimension(T.size(), n_new);

      std::array<unsigned int, dim> n_old_dir, n_new_dir;
      for (unsigned int e = 0; e < dim; ++e)
        {
          n_old_dir[e] = n_control_points(e);
          n_new_dir[e] = (e == d ? n_new : n_old_dir[e]);
        }
      unsigned int n_total_new = 1;
      for (unsigned int e = 0; e < dim; ++e)
        n_total_new *= n_new_dir[e];

      // Strides of direction d in the old and new lexicographic numbering.
      unsigned int stride = 1;
      for (unsigned int e = 0; e < d; ++e)
        stride *= n_old_dir[e];

      std::vector<std::array<double, dim + 1>> qw(n_total_new);
      for (unsigned int b = 0; b < n_total_new; ++b)
        {
          // Tensor index of the new point; its line in direction d.
          std::array<unsigned int, dim> ijk;
          unsigned int                  rest = b;
          for (unsigned int e = 0; e < dim; ++e)
            {
              ijk[e] = rest % n_new_dir[e];
              rest /= n_new_dir[e];
            }
          const unsigned int row = ijk[d];
          ijk[d]                 = 0;
          unsigned int base      = 0;
          for (int e = dim - 1; e >= 0; --e)
            base = base * n_old_dir[e] + ijk[e];
          std::array<double, dim + 1> q{};
          for (const auto &[col, value] : T[row])
            {
              Assert(col < n_old, ExcInternalError());
              const auto &p = pw[base + col * stride];
              for (unsigned int c = 0; c <= dim; ++c)
                q[c] += value * p[c];
            }
          qw[b] = q;
        }

      // A polynomial patch (all weights equal) stays polynomial: the rows
      // of T sum to one, but in floating point only to round-off, and a
      // weight of 1 - 1e-16 would make the patch count as rational (more
      // quadrature points in every cell).
      const bool polynomial =
        std::all_of(weights.begin(), weights.end(), [&](const double w) {
          return w == weights[0];
        });
      const double common_weight = weights[0];

      knots[d] = new_kv;
      points.resize(n_total_new);
      weights.resize(n_total_new);
      for (unsigned int b = 0; b < n_total_new; ++b)
        {
          AssertThrow(qw[b][dim] > 0.,
                      ExcMessage("NurbsPatch: refinement produced a "
                                 "non-positive weight; this cannot happen "
                                 "for a valid patch."));
          weights[b] = (polynomial ? common_weight : qw[b][dim]);
          for (unsigned int c = 0; c < dim; ++c)
            points[b][c] = qw[b][c] / qw[b][dim];
        }
      update_physical_size();
    }



    template <int dim>
    void
    NurbsPatch<dim>::update_physical_size()
    {
      double size = 0.;
      for (const auto &p : points)
        size = std::max(size, (p - points[0]).norm());
      physical_size = std::max(size, 1e-300);
    }



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



    template <int dim>
    std::vector<unsigned int>
    NurbsPatch<dim>::face_control_points(const unsigned int face) const
    {
      AssertThrow(face < 2 * dim,
                  ExcMessage("NurbsPatch: face " + std::to_string(face) +
                             " does not exist; faces are 0.." +
                             std::to_string(2 * dim - 1) + "."));
      const unsigned int d     = face / 2;
      const unsigned int fixed = (face % 2 == 0 ? 0 : n_control_points(d) - 1);
      std::vector<unsigned int> result;
      for (unsigned int a = 0; a < n_control_points(); ++a)
        if (tensor_index(a)[d] == fixed)
          result.push_back(a);
      return result;
    }



    template <int dim>
    double
    NurbsPatch<dim>::orientation() const
    {
      const Point<dim> centre = 0.5 * (parametric_lower() + parametric_upper());
      double           det    = determinant(jacobian(centre));
      if (det == 0.)
        {
          // Degenerate centre: look at a point off the middle.
          Point<dim> xi;
          for (unsigned int d = 0; d < dim; ++d)
            xi[d] = parametric_lower()[d] +
                    0.3 * (parametric_upper()[d] - parametric_lower()[d]);
          det = determinant(jacobian(xi));
        }
      AssertThrow(det != 0.,
                  ExcMessage("NurbsPatch: the parametrization is singular "
                             "inside the patch."));
      return det > 0. ? 1. : -1.;
    }



    template <int dim>
    Tensor<1, dim>
    NurbsPatch<dim>::outward_normal(const unsigned int face,
                                    const Point<dim>  &xi) const
    {
      AssertThrow(face < 2 * dim,
                  ExcMessage("NurbsPatch: face " + std::to_string(face) +
                             " does not exist; faces are 0.." +
                             std::to_string(2 * dim - 1) + "."));
      const unsigned int d    = face / 2;
      const double       side = (face % 2 == 0 ? -1. : 1.);
      Point<dim>         x    = xi;
      x[d] = (face % 2 == 0 ? knots[d].front() : knots[d].back());
      const Tensor<1, dim> n =
        side * orientation() * cofactor_column(jacobian(x), d);
      const double length = n.norm();
      AssertThrow(length > 0.,
                  ExcMessage("NurbsPatch: the normal of face " +
                             std::to_string(face) +
                             " is undefined at this point (singular "
                             "parametrization, e.g. a collapsed corner)."));
      return n / length;
    }



    template <int dim>
    Point<dim>
    NurbsPatch<dim>::face_centroid(const unsigned int face) const
    {
      AssertThrow(face < 2 * dim,
                  ExcMessage("NurbsPatch: face " + std::to_string(face) +
                             " does not exist; faces are 0.." +
                             std::to_string(2 * dim - 1) + "."));
      const unsigned int normal = face / 2;
      // The face's Gauss points, direction by direction: two more per span
      // than the degree (the rational measure is not a polynomial).
      std::vector<Point<dim>> xis(1);
      std::vector<double>     weights(1, 1.);
      xis[0][normal] =
        (face % 2 == 0 ? knots[normal].front() : knots[normal].back());
      for (unsigned int d = 0; d < dim; ++d)
        if (d != normal)
          {
            const QGauss<1>         gauss(degree(d) + 2);
            const auto              b = breakpoints(d);
            std::vector<Point<dim>> next_xis;
            std::vector<double>     next_weights;
            for (unsigned int k = 0; k < xis.size(); ++k)
              for (unsigned int e = 0; e + 1 < b.size(); ++e)
                for (unsigned int q = 0; q < gauss.size(); ++q)
                  {
                    Point<dim> xi = xis[k];
                    xi[d] = b[e] + (b[e + 1] - b[e]) * gauss.point(q)[0];
                    next_xis.push_back(xi);
                    next_weights.push_back(weights[k] * (b[e + 1] - b[e]) *
                                           gauss.weight(q));
                  }
            xis.swap(next_xis);
            weights.swap(next_weights);
          }
      double     area = 0.;
      Point<dim> centroid;
      for (unsigned int q = 0; q < xis.size(); ++q)
        {
          const double da =
            weights[q] * cofactor_column(jacobian(xis[q]), normal).norm();
          area += da;
          centroid += da * value(xis[q]);
        }
      AssertThrow(area > 0.,
                  ExcMessage("NurbsPatch: face " + std::to_string(face) +
                             " has no area (a collapsed face): it has no "
                             "centroid."));
      return centroid / area;
    }



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
    std::vector<Point<dim>>
    tensor_product_points(const std::array<std::vector<double>, dim> &coords)
    {
      unsigned int n = 1;
      for (unsigned int d = 0; d < dim; ++d)
        n *= coords[d].size();
      std::vector<Point<dim>> points(n);
      for (unsigned int s = 0; s < n; ++s)
        {
          unsigned int rest = s;
          for (unsigned int d = 0; d < dim; ++d)
            {
              points[s][d] = coords[d][rest % coords[d].size()];
              rest /= coords[d].size();
            }
        }
      return points;
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



    template <int dim>
    std::vector<double>
    interpolate_on_face(const NurbsPatch<dim>                           &patch,
                        const unsigned int                               face,
                        const std::function<double(const Point<dim> &)> &g)
    {
      const std::vector<unsigned int> points = patch.face_control_points(face);
      const unsigned int              fixed  = face / 2;
      // The face's directions, their sizes and 1D collocation matrices
      // B(i, j) = N_j(greville_i); coordinates of the collocation points.
      std::vector<unsigned int>            directions, sizes;
      std::vector<FullMatrix<double>>      B;
      std::array<std::vector<double>, dim> coords;
      coords[fixed] = {face % 2 == 0 ? patch.parametric_lower()[fixed] :
                                       patch.parametric_upper()[fixed]};
      for (unsigned int d = 0; d < dim; ++d)
        if (d != fixed)
          {
            const KnotVector   &kv = patch.knot_vector(d);
            const unsigned int  n  = kv.n_basis_functions();
            const unsigned int  p  = kv.degree();
            FullMatrix<double>  M(n, n);
            std::vector<double> values;
            coords[d] = kv.greville_abscissae();
            for (unsigned int i = 0; i < n; ++i)
              {
                const unsigned int span = kv.find_span(coords[d][i]);
                kv.basis_functions(coords[d][i], span, values);
                for (unsigned int j = 0; j <= p; ++j)
                  M(i, span - p + j) = values[j];
              }
            directions.push_back(d);
            sizes.push_back(n);
            B.push_back(M);
          }
      const unsigned int n_face = points.size();

      // Applies f to every line of the face tensor (direction 0 fastest)
      // along face direction k.
      const auto along = [&](std::vector<double>                         &data,
                             const unsigned int                           k,
                             const std::function<void(Vector<double> &)> &f) {
        unsigned int stride = 1;
        for (unsigned int l = 0; l < k; ++l)
          stride *= sizes[l];
        const unsigned int n = sizes[k];
        Vector<double>     line(n);
        for (unsigned int start = 0; start < n_face; ++start)
          if ((start / stride) % n == 0)
            {
              for (unsigned int i = 0; i < n; ++i)
                line[i] = data[start + i * stride];
              f(line);
              for (unsigned int i = 0; i < n; ++i)
                data[start + i * stride] = line[i];
            }
      };

      // W at the collocation points: (B_1 x B_2) w.
      std::vector<double> W(n_face), rhs(n_face);
      for (unsigned int i = 0; i < n_face; ++i)
        W[i] = patch.weight(points[i]);
      for (unsigned int k = 0; k < B.size(); ++k)
        along(W, k, [&](Vector<double> &line) {
          Vector<double> out(line.size());
          B[k].vmult(out, line);
          line = out;
        });
      const std::vector<Point<dim>> xi = tensor_product_points<dim>(coords);
      for (unsigned int i = 0; i < n_face; ++i)
        rhs[i] = g(patch.value(xi[i])) * W[i];
      // (B_1 x B_2) y = W g, then v = y / w.
      for (unsigned int k = 0; k < B.size(); ++k)
        {
          LAPACKFullMatrix<double> lu;
          lu.copy_from(B[k]);
          lu.compute_lu_factorization();
          along(rhs, k, [&](Vector<double> &line) {
            lu.solve(line);
          });
        }
      for (unsigned int i = 0; i < n_face; ++i)
        rhs[i] /= patch.weight(points[i]);
      return rhs;
    }



    template class NurbsPatch<2>;
    template class NurbsPatch<3>;
    template std::vector<double>
    interpolate_on_face<2>(const NurbsPatch<2> &,
                           unsigned int,
                           const std::function<double(const Point<2> &)> &);
    template std::vector<double>
    interpolate_on_face<3>(const NurbsPatch<3> &,
                           unsigned int,
                           const std::function<double(const Point<3> &)> &);
    template Tensor<1, 2>
    cofactor_column<2>(const Tensor<2, 2> &, const unsigned int);
    template Tensor<1, 3>
    cofactor_column<3>(const Tensor<2, 3> &, const unsigned int);
    template std::vector<Point<2>>
    tensor_product_points<2>(const std::array<std::vector<double>, 2> &);
    template std::vector<Point<3>>
    tensor_product_points<3>(const std::array<std::vector<double>, 3> &);
  } // namespace nurbs
} // namespace igabde
