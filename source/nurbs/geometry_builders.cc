#include <igabde/nurbs/geometry_builders.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

namespace igabde
{
  namespace nurbs
  {
    namespace
    {
      const KnotVector &
      linear()
      {
        static const KnotVector kv(1, {0., 0., 1., 1.});
        return kv;
      }

      const KnotVector &
      quadratic()
      {
        static const KnotVector kv(2, {0., 0., 0., 1., 1., 1.});
        return kv;
      }

      /**
       * One element of degree 2 in both directions from its boundary net
       * P[i][j], w[i][j] (i along direction 0): the interior point is the
       * bilinear Coons blend of the homogeneous boundary net,
       * Pw11 = (edge midpoints) / 2 - (corners) / 4.
       */
      NurbsPatch<2>
      coons_quadratic_patch(std::array<std::array<Point<2>, 3>, 3> P,
                            std::array<std::array<double, 3>, 3>   w)
      {
        Tensor<1, 2> pw;
        double       ww = 0.;
        auto         add =
          [&](const unsigned int i, const unsigned int j, const double c) {
            pw += c * w[i][j] * static_cast<const Tensor<1, 2> &>(P[i][j]);
            ww += c * w[i][j];
          };
        add(0, 1, 0.5);
        add(2, 1, 0.5);
        add(1, 0, 0.5);
        add(1, 2, 0.5);
        add(0, 0, -0.25);
        add(2, 0, -0.25);
        add(0, 2, -0.25);
        add(2, 2, -0.25);
        AssertThrow(ww > 0., ExcInternalError());
        w[1][1] = ww;
        P[1][1] = Point<2>(pw / ww);

        std::vector<Point<2>> points;
        std::vector<double>   weights;
        for (unsigned int j = 0; j < 3; ++j)
          for (unsigned int i = 0; i < 3; ++i)
            {
              points.push_back(P[i][j]);
              weights.push_back(w[i][j]);
            }
        return NurbsPatch<2>({{quadratic(), quadratic()}}, points, weights);
      }

      /// The point at polar angle @p degrees and distance @p r from @p c.
      Point<2>
      polar(const Point<2> &c, const double r, const double degrees)
      {
        const double t = degrees * M_PI / 180.;
        return Point<2>(c[0] + r * std::cos(t), c[1] + r * std::sin(t));
      }

      /**
       * The middle control point and weight of the circular arc of radius
       * @p R about @p c from @p from to @p to degrees (less than 180 deg
       * apart): the tangents' intersection, weight cos(half the angle).
       */
      std::pair<Point<2>, double>
      arc_middle(const Point<2> &c,
                 const double    R,
                 const double    from,
                 const double    to)
      {
        const double half = 0.5 * (to - from) * M_PI / 180.;
        return {polar(c, R / std::cos(half), 0.5 * (from + to)),
                std::cos(half)};
      }
    } // namespace



    template <int dim>
    NurbsPatch<dim>
    make_box(const Point<dim> &lo, const Point<dim> &hi)
    {
      for (unsigned int d = 0; d < dim; ++d)
        AssertThrow(lo[d] < hi[d],
                    ExcMessage("make_box: the lower corner must be below the "
                               "upper corner in every coordinate (direction " +
                               std::to_string(d) + ")."));
      std::array<KnotVector, dim> knots;
      knots.fill(linear());
      std::vector<Point<dim>> points(1u << dim);
      std::vector<double>     weights(1u << dim, 1.);
      for (unsigned int a = 0; a < points.size(); ++a)
        for (unsigned int d = 0; d < dim; ++d)
          points[a][d] = ((a >> d) & 1u) ? hi[d] : lo[d];
      return NurbsPatch<dim>(knots, points, weights);
    }



    NurbsPatch<2>
    make_quarter_annulus(const double r0, const double r1)
    {
      AssertThrow(r0 > 0. && r0 < r1,
                  ExcMessage(
                    "make_quarter_annulus: need 0 < r0 < r1, got r0 = " +
                    std::to_string(r0) + ", r1 = " + std::to_string(r1) + "."));
      const double w = std::sqrt(0.5);
      // Radial index fastest.
      const std::vector<Point<2>> points  = {Point<2>(r0, 0.),
                                             Point<2>(r1, 0.),
                                             Point<2>(r0, r0),
                                             Point<2>(r1, r1),
                                             Point<2>(0., r0),
                                             Point<2>(0., r1)};
      const std::vector<double>   weights = {1., 1., w, w, 1., 1.};
      return NurbsPatch<2>({{linear(), quadratic()}}, points, weights);
    }



    template <int dim>
    NurbsPatch<dim>
    make_thick_cylinder_quarter(const double r0,
                                const double r1,
                                const double height)
    {
      const NurbsPatch<2> annulus = make_quarter_annulus(r0, r1);
      if constexpr (dim == 2)
        {
          (void)height;
          return annulus;
        }
      else
        {
          AssertThrow(height > 0.,
                      ExcMessage("make_thick_cylinder_quarter: the height "
                                 "must be positive."));
          std::vector<Point<3>> points;
          std::vector<double>   weights;
          for (unsigned int k = 0; k < 2; ++k)
            for (unsigned int a = 0; a < annulus.n_control_points(); ++a)
              {
                const Point<2> &p = annulus.control_point(a);
                points.emplace_back(p[0], p[1], k * height);
                weights.push_back(annulus.weight(a));
              }
          return NurbsPatch<3>({{linear(), quadratic(), linear()}},
                               points,
                               weights);
        }
    }



    NurbsPatch<3>
    make_curved_beam(const double r0, const double r1, const double width)
    {
      AssertThrow(width > 0.,
                  ExcMessage("make_curved_beam: the width must be positive."));
      const NurbsPatch<2>   annulus = make_quarter_annulus(r0, r1);
      std::vector<Point<3>> points;
      std::vector<double>   weights;
      for (unsigned int k = 0; k < 2; ++k)
        for (unsigned int a = 0; a < annulus.n_control_points(); ++a)
          {
            // (x, y) of the annulus becomes (x, z) of the beam.
            const Point<2> &p = annulus.control_point(a);
            points.emplace_back(p[0], k * width, p[1]);
            weights.push_back(annulus.weight(a));
          }
      return NurbsPatch<3>({{linear(), quadratic(), linear()}},
                           points,
                           weights);
    }



    NurbsPatch<2>
    make_plate_with_hole(const double R, const double L)
    {
      AssertThrow(R > 0. && R < L,
                  ExcMessage("make_plate_with_hole: need 0 < R < L, got R = " +
                             std::to_string(R) + ", L = " + std::to_string(L) +
                             "."));
      const double s  = std::sqrt(2.);
      const double wm = (1. + 1. / s) / 2.;
      const double m  = (R + L) / 2.;
      // Rows along direction 1 (angle); within a row the index of direction
      // 0 (hole -> outer) runs fastest. Hughes et al.'s upper-left quadrant,
      // mirrored (x -> -x) and transposed so that the patch is right-handed.
      const Point<2>        hole[4]  = {Point<2>(R, 0.),
                                        Point<2>(R, R * (s - 1.)),
                                        Point<2>(R * (s - 1.), R),
                                        Point<2>(0., R)};
      const double          whole[4] = {1., wm, wm, 1.};
      const Point<2>        mid[4]   = {Point<2>(m, 0.),
                                        Point<2>(m, 0.3 * m),
                                        Point<2>(0.3 * m, m),
                                        Point<2>(0., m)};
      const Point<2>        outer[4] = {Point<2>(L, 0.),
                                        Point<2>(L, L),
                                        Point<2>(L, L),
                                        Point<2>(0., L)};
      std::vector<Point<2>> points;
      std::vector<double>   weights;
      for (unsigned int j = 0; j < 4; ++j)
        {
          points.push_back(hole[j]);
          weights.push_back(whole[j]);
          points.push_back(mid[j]);
          weights.push_back(1.);
          points.push_back(outer[j]);
          weights.push_back(1.);
        }
      const KnotVector angular(2, {0., 0., 0., 0.5, 1., 1., 1.});
      return NurbsPatch<2>({{quadratic(), angular}}, points, weights);
    }



    NurbsPatch<2>
    make_hertz_quarter_disc(const double R)
    {
      AssertThrow(R > 0.,
                  ExcMessage("make_hertz_quarter_disc: the radius must be "
                             "positive."));
      const double s  = std::sqrt(2.);
      const double cw = std::cos(M_PI / 8.); // 45-degree arcs
      // Boundary control points and weights (homogeneous Coons interior).
      std::array<std::array<Point<2>, 3>, 3> P; // P[i][j]
      std::array<std::array<double, 3>, 3>   w{};
      P[0][0] = Point<2>(0., 0.);
      w[0][0] = 1.;
      P[1][0] = Point<2>(R * (s - 1.), 0.); // tangents at -90 and -45 deg
      w[1][0] = cw;
      P[2][0] = Point<2>(R / s, R * (1. - 1. / s));
      w[2][0] = 1.;
      P[2][1] = Point<2>(R, R * (2. - s)); // tangents at -45 and 0 deg
      w[2][1] = cw;
      P[2][2] = Point<2>(R, R);
      w[2][2] = 1.;
      P[0][1] = Point<2>(0., 0.5 * R);
      w[0][1] = cw;
      P[0][2] = Point<2>(0., R);
      w[0][2] = 1.;
      P[1][2] = Point<2>(0.5 * R, R);
      w[1][2] = cw;

      return coons_quadratic_patch(P, w);
    }



    NurbsPatch<2>
    make_half_disc(const Point<2> &c, const double R)
    {
      AssertThrow(R > 0.,
                  ExcMessage("make_half_disc: the radius must be positive."));
      std::array<std::array<Point<2>, 3>, 3> P; // P[i][j]
      std::array<std::array<double, 3>, 3>   w{};
      // Corners: the arc's ends at 225 and 315 deg, the diameter's ends.
      P[0][0] = polar(c, R, 225.);
      P[2][0] = polar(c, R, 315.);
      P[0][2] = polar(c, R, 180.);
      P[2][2] = polar(c, R, 0.);
      w[0][0] = w[2][0] = w[0][2] = w[2][2] = 1.;
      std::tie(P[1][0], w[1][0]) = arc_middle(c, R, 225., 315.); // bottom
      std::tie(P[0][1], w[0][1]) = arc_middle(c, R, 225., 180.); // left
      std::tie(P[2][1], w[2][1]) = arc_middle(c, R, 315., 360.); // right
      // The diameter, its middle weighted as the bottom arc's so that
      // direction 0 is parametrised alike at both ends of direction 1.
      P[1][2] = c;
      w[1][2] = w[1][0];
      return coons_quadratic_patch(P, w);
    }



    NurbsPatch<2>
    make_full_disc(const Point<2> &c, const double R)
    {
      AssertThrow(R > 0.,
                  ExcMessage("make_full_disc: the radius must be positive."));
      std::array<std::array<Point<2>, 3>, 3> P; // P[i][j]
      std::array<std::array<double, 3>, 3>   w{};
      P[0][0] = polar(c, R, 225.);
      P[2][0] = polar(c, R, 315.);
      P[0][2] = polar(c, R, 135.);
      P[2][2] = polar(c, R, 45.);
      w[0][0] = w[2][0] = w[0][2] = w[2][2] = 1.;
      std::tie(P[1][0], w[1][0]) = arc_middle(c, R, 225., 315.); // bottom
      std::tie(P[1][2], w[1][2]) = arc_middle(c, R, 135., 45.);  // top
      std::tie(P[0][1], w[0][1]) = arc_middle(c, R, 225., 135.); // left
      std::tie(P[2][1], w[2][1]) = arc_middle(c, R, 315., 405.); // right
      return coons_quadratic_patch(P, w);
    }



    NurbsPatch<3>
    make_cylinder(const Point<3> &base_centre,
                  const double    R,
                  const double    height,
                  const bool      full)
    {
      AssertThrow(height > 0.,
                  ExcMessage("make_cylinder: the height must be positive."));
      const Point<2>      c(base_centre[0], base_centre[1]);
      const NurbsPatch<2> disc =
        full ? make_full_disc(c, R) : make_half_disc(c, R);
      std::vector<Point<3>> points;
      std::vector<double>   weights;
      for (unsigned int k = 0; k < 2; ++k)
        for (unsigned int a = 0; a < disc.n_control_points(); ++a)
          {
            const Point<2> &p = disc.control_point(a);
            points.emplace_back(p[0], p[1], base_centre[2] + k * height);
            weights.push_back(disc.weight(a));
          }
      return NurbsPatch<3>({{quadratic(), quadratic(), linear()}},
                           points,
                           weights);
    }



    template <int dim>
    void
    elevate_to_degree(NurbsPatch<dim> &patch, const unsigned int degree)
    {
      for (unsigned int d = 0; d < dim; ++d)
        if (patch.degree(d) < degree)
          patch.elevate_degree(d, degree - patch.degree(d));
    }



    std::vector<double>
    band_graded_fractions(const unsigned int n,
                          const double       from,
                          const double       to,
                          const double       ratio)
    {
      AssertThrow(0. <= from && from < to && to <= 1. && ratio >= 1. && n >= 1,
                  ExcMessage("band_graded_fractions: needs 0 <= from < to "
                             "<= 1, ratio >= 1 and n >= 1."));
      // Part size h(s) = min(ratio h, h + growth dist(s)) on a fine grid;
      // the number of parts int_0^1 ds / h(s) falls as h grows, so h is
      // found by bisection, then the knots invert the cumulative count.
      // A part of size D centred where h = h_c holds D = h_c (the count
      // over it is 1), so neighbours satisfy D' = D + growth (D + D') / 2:
      // growth 2/9 makes D' / D = (1 + 1/9) / (1 - 1/9) = 1.25.
      const double       growth = 2. / 9.;
      const unsigned int m      = 20000;
      const auto count = [&](const double h, std::vector<double> *cumulative) {
        double sum = 0.;
        if (cumulative != nullptr)
          cumulative->assign(1, 0.);
        double previous = 0.;
        for (unsigned int k = 0; k <= m; ++k)
          {
            const double s    = double(k) / m;
            const double dist = std::max({0., from - s, s - to});
            const double rho  = 1. / std::min(ratio * h, h + growth * dist);
            if (k > 0)
              {
                sum += 0.5 * (rho + previous) / m;
                if (cumulative != nullptr)
                  cumulative->push_back(sum);
              }
            previous = rho;
          }
        return sum;
      };
      double low = 1e-12, high = 1.;
      for (unsigned int it = 0; it < 60; ++it)
        {
          const double mid                       = std::sqrt(low * high);
          (count(mid, nullptr) > n ? low : high) = mid;
        }
      std::vector<double> cumulative;
      const double        total = count(high, &cumulative);
      std::vector<double> fractions;
      unsigned int        k = 0;
      for (unsigned int j = 1; j < n; ++j)
        {
          const double target = total * j / n;
          while (k + 1 < cumulative.size() && cumulative[k + 1] < target)
            ++k;
          const double t =
            (target - cumulative[k]) / (cumulative[k + 1] - cumulative[k]);
          fractions.push_back((k + t) / m);
        }
      return fractions;
    }



    template <int dim>
    void
    subdivide(
      NurbsPatch<dim>                                               &patch,
      const std::array<unsigned int, static_cast<std::size_t>(dim)> &n_spans,
      const std::array<double, static_cast<std::size_t>(dim)>       &grading,
      const std::array<bool, static_cast<std::size_t>(dim)> &toward_high,
      const std::array<std::array<double, 2>, static_cast<std::size_t>(dim)>
        &bands)
    {
      for (unsigned int d = 0; d < dim; ++d)
        {
          AssertThrow(n_spans[d] >= 1,
                      ExcMessage("subdivide: every direction needs at least "
                                 "one part per span."));
          const std::vector<double> b = patch.breakpoints(d);
          std::vector<double>       new_knots;
          const unsigned int        n = n_spans[d] * (b.size() - 1);
          if (grading[d] > 1. && n > 1 && bands[d][0] < bands[d][1])
            {
              const double lo = b.front(), length = b.back() - b.front();
              for (const double f : band_graded_fractions(n,
                                                          bands[d][0],
                                                          bands[d][1],
                                                          grading[d]))
                {
                  const double knot = lo + f * length;
                  if (std::none_of(b.begin(), b.end(), [&](const double x) {
                        return std::abs(x - knot) <= 1e-12 * length;
                      }))
                    new_knots.push_back(knot);
                }
            }
          else if (grading[d] > 1. && n > 1)
            {
              const double q  = std::pow(grading[d], 1. / (n - 1.));
              const double lo = b.front(), length = b.back() - b.front();
              const double sum = std::pow(q, n) - 1.;
              for (unsigned int j = 1; j < n; ++j)
                {
                  // The fraction from the end the parts are smallest at.
                  const double f    = toward_high[d] ?
                                        1. - (std::pow(q, n - j) - 1.) / sum :
                                        (std::pow(q, j) - 1.) / sum;
                  const double knot = lo + f * length;
                  if (std::none_of(b.begin(), b.end(), [&](const double x) {
                        return std::abs(x - knot) <= 1e-12 * length;
                      }))
                    new_knots.push_back(knot);
                }
            }
          else
            for (unsigned int e = 0; e + 1 < b.size(); ++e)
              for (unsigned int j = 1; j < n_spans[d]; ++j)
                new_knots.push_back(b[e] + (b[e + 1] - b[e]) * j / n_spans[d]);
          patch.insert_knots(d, new_knots);
        }
    }



    template NurbsPatch<2>
    make_box(const Point<2> &, const Point<2> &);
    template NurbsPatch<3>
    make_box(const Point<3> &, const Point<3> &);
    template NurbsPatch<2>
    make_thick_cylinder_quarter(const double, const double, const double);
    template NurbsPatch<3>
    make_thick_cylinder_quarter(const double, const double, const double);
    template void
    elevate_to_degree(NurbsPatch<2> &, const unsigned int);
    template void
    elevate_to_degree(NurbsPatch<3> &, const unsigned int);
    template void
    subdivide<2>(NurbsPatch<2> &,
                 const std::array<unsigned int, 2> &,
                 const std::array<double, 2> &,
                 const std::array<bool, 2> &,
                 const std::array<std::array<double, 2>, 2> &);
    template void
    subdivide<3>(NurbsPatch<3> &,
                 const std::array<unsigned int, 3> &,
                 const std::array<double, 3> &,
                 const std::array<bool, 3> &,
                 const std::array<std::array<double, 2>, 3> &);
  } // namespace nurbs
} // namespace igabde
