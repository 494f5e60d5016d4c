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
    {
      /// The local tensor index of basis function @p l of a span (direction
      /// 0 fastest) in @p local, its control point's in @p global.
      template <int dim>
      void
      span_function_index(const unsigned int                   l,
                          const std::array<KnotVector, dim>   &knots,
                          const std::array<unsigned int, dim> &span,
                          std::array<unsigned int, dim>       &local,
                          std::array<unsigned int, dim>       &global)
      {
        unsigned int rest = l;
        for (unsigned int d = 0; d < dim; ++d)
          {
            local[d]  = rest % (knots[d].degree() + 1);
            rest      = rest / (knots[d].degree() + 1);
            global[d] = span[d] - knots[d].degree() + local[d];
          }
      }
    } // namespace



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
          span_function_index<dim>(l, knots, span, local, global);
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
    Tensor<3, dim>
    NurbsPatch<dim>::second_derivatives(const Point<dim> &xi) const
    {
      // In homogeneous coordinates, P = sum N_A w_A X_A and W = sum N_A
      // w_A are polynomial, x = P / W, and differentiating W x = P twice,
      //   W x,ij = P,ij - W,i x,j - W,j x,i - W,ij x.
      std::array<unsigned int, dim>                     span;
      std::array<std::vector<std::vector<double>>, dim> ders;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double x = std::clamp(xi[d], knots[d].front(), knots[d].back());
          span[d]        = knots[d].find_span(x);
          knots[d].basis_function_derivatives(x, span[d], 2, ders[d]);
        }
      unsigned int n_local = 1;
      for (unsigned int d = 0; d < dim; ++d)
        n_local *= knots[d].degree() + 1;
      // Homogeneous sums: value, first and second derivatives, of the
      // dim coordinates (c < dim) and of the weight (c = dim).
      std::array<double, dim + 1>         P{};
      std::array<Tensor<1, dim>, dim + 1> dP;
      std::array<Tensor<2, dim>, dim + 1> ddP;
      std::array<unsigned int, dim>       local, global;
      for (unsigned int l = 0; l < n_local; ++l)
        {
          span_function_index<dim>(l, knots, span, local, global);
          const unsigned int a = control_point_index(global);
          // N and its derivatives: the product of one factor per direction,
          // differentiated in the directions asked for.
          const auto product = [&](const unsigned int i, const unsigned int j) {
            double v = 1.;
            for (unsigned int d = 0; d < dim; ++d)
              v *= ders[d][(d == i ? 1 : 0) + (d == j ? 1 : 0)][local[d]];
            return v;
          };
          const double   N = product(dim, dim);
          Tensor<1, dim> dN;
          Tensor<2, dim> ddN;
          for (unsigned int i = 0; i < dim; ++i)
            {
              dN[i] = product(i, dim);
              for (unsigned int j = 0; j < dim; ++j)
                ddN[i][j] = product(i, j);
            }
          for (unsigned int c = 0; c <= dim; ++c)
            {
              const double value = weights[a] * (c < dim ? points[a][c] : 1.);
              P[c] += value * N;
              dP[c] += value * dN;
              ddP[c] += value * ddN;
            }
        }
      const double   W = P[dim];
      Tensor<3, dim> result;
      for (unsigned int c = 0; c < dim; ++c)
        {
          const double   x  = P[c] / W;
          Tensor<1, dim> dx = (dP[c] - x * dP[dim]) / W;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              result[c][i][j] = (ddP[c][i][j] - dP[dim][i] * dx[j] -
                                 dP[dim][j] * dx[i] - ddP[dim][i][j] * x) /
                                W;
        }
      return result;
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
