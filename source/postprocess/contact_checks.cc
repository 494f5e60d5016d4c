#include <igabde/postprocess/contact_checks.h>

#include <algorithm>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <limits>
#include <sstream>

namespace igabde
{
  namespace postprocess
  {
    namespace
    {
      /// Depth: the stress under a Hertz contact decays over a depth of
      /// about a (the largest shear stress sits at 0.78 a in 2D, 0.48 a in
      /// 3D); elements much deeper hold that decay inside one polynomial
      /// and flatten the pressure. V5 (NURBS p = 2, 64 spans along the
      /// arc), depth / a = 0.6, 2.5, 3.3, 5: half-width error 0.5, 1.1,
      /// 2.6, 5 %, peak pressure -0.8, -0.3, +0.8, +7 %; a zone of R/100 on
      /// elements R/8 deep had its peak 37 % off. Past 2 a the answer
      /// depends on the depth.
      std::string
      depth_warning(const double depth, const double a, const std::string &size)
      {
        std::ostringstream w;
        w << "Hertz check: Body 1's elements under the contact are " << depth
          << " deep, more than twice the contact " << size << " " << a
          << " (Hertz): the stress under the contact changes within one "
             "element across the depth, so the pressure comes out "
             "flattened. Grade Body 1's spans toward the contact face "
             "(Body 1/Grading = face: ratio) or add spans across the depth "
             "(Body 1/Subdivisions) until the elements there are at most "
             "twice the "
          << size << " deep.";
        return w.str();
      }

      /// Units: a contact zone a thousand times smaller than the radius is
      /// rarely the scene meant; E given in Pa where the lengths are in mm
      /// (and the forces in N) makes the bodies 10^6 times too stiff and
      /// the Hertz zone 10^3 (line contact) or 10^2 (point contact) times
      /// too small. Empty where the zone is not that small.
      std::string
      units_hint(const double a, const double R, const std::string &size)
      {
        if (!(a < 1e-3 * R))
          return "";
        std::ostringstream w;
        w << " The " << size << " is only " << a / R << " of the radius " << R
          << ": if that is not meant, check the units (E, loads and "
             "lengths in one system: with lengths in mm and forces in N, "
             "E is in MPa = N/mm^2; E in Pa makes the bodies 10^6 times too "
             "stiff).";
        return w.str();
      }
    } // namespace



    template <int dim>
    double
    pressure_uniformity(const std::vector<contact::PairState<dim>> &pairs,
                        const double expected_pressure)
    {
      double worst = 0.;
      for (const auto &pair : pairs)
        worst =
          std::max(worst, std::abs(pair.pressure() / expected_pressure - 1.));
      return worst;
    }



    template <int dim>
    double
    effective_modulus(const elasticity::IsotropicMaterial<dim> &body1,
                      const elasticity::IsotropicMaterial<dim> *body2)
    {
      const auto compliance = [](const elasticity::IsotropicMaterial<dim> &m) {
        const bool plane_stress =
          (dim == 2 && m.plane_model == elasticity::PlaneModel::plane_stress);
        return (plane_stress ? 1. : 1. - m.poisson_ratio * m.poisson_ratio) /
               m.youngs_modulus;
      };
      return 1. / (compliance(body1) + (body2 ? compliance(*body2) : 0.));
    }



    template <int dim>
    double
    dundurs_beta(const elasticity::IsotropicMaterial<dim> &body1,
                 const elasticity::IsotropicMaterial<dim> *body2)
    {
      const auto kappa = [](const elasticity::IsotropicMaterial<dim> &m) {
        const double nu = m.poisson_ratio;
        return dim == 2 &&
                   m.plane_model == elasticity::PlaneModel::plane_stress ?
                 (3. - nu) / (1. + nu) :
                 3. - 4. * nu;
      };
      const double k1 = kappa(body1);
      if (body2 == nullptr)
        return -(k1 - 1.) / (k1 + 1.);
      const double k2 = kappa(*body2);
      const double g1 =
        body1.youngs_modulus / (2. * (1. + body1.poisson_ratio));
      const double g2 =
        body2->youngs_modulus / (2. * (1. + body2->poisson_ratio));
      return (g1 * (k2 - 1.) - g2 * (k1 - 1.)) /
             (g1 * (k2 + 1.) + g2 * (k1 + 1.));
    }



    HertzCheck::Result
    HertzCheck::evaluate(const std::vector<contact::PairState<2>> &pairs) const
    {
      Result       result;
      const double P = line_load, R = radius;
      const double a  = std::sqrt(4. * P * R / (M_PI * effective_modulus));
      const double p0 = 2. * P / (M_PI * a);
      result.half_width_exact    = a;
      result.peak_pressure_exact = p0;

      // Pair pressures by signed distance from the symmetry axis; a full
      // model has pairs on both sides, a half model on one.
      const Tensor<1, 2> e = axis_direction / axis_direction.norm();
      const Tensor<1, 2> e_normal({-e[1], e[0]});
      std::vector<std::pair<double, double>> signed_profile;
      double                                 peak = 0., extent = 0.;
      for (const auto &pair : pairs)
        {
          const Tensor<1, 2> r = pair.location - axis_point;
          signed_profile.emplace_back(r * e_normal, pair.pressure());
          peak   = std::max(peak, pair.pressure());
          extent = std::max(extent, std::abs(r * e_normal));
        }
      result.peak_pressure = peak;
      {
        double force = 0., moment = 0.;
        for (const auto &pair : pairs)
          {
            const Tensor<1, 2> r = pair.location - axis_point;
            const double       x = r * e_normal;
            force += pair.force_local[0];
            moment += pair.force_local[0] * x * x;
          }
        result.half_width_moment =
          (force > 0. ? 2. * std::sqrt(std::max(moment, 0.) / force) : 0.);
      }
      // Loaded: above 1e-6 of the peak, the solver's round-off.
      for (const auto &[x, pr] : signed_profile)
        if (pr > 1e-6 * peak)
          ++result.n_loaded;

      // Each side as a profile by distance from the axis (pairs on the
      // axis belong to both); a side with fewer than two pairs off the
      // axis is the symmetry plane of a half model and is left out.
      std::vector<std::vector<std::pair<double, double>>> sides;
      const double on_axis = 1e-12 * extent;
      for (const double sign : {1., -1.})
        {
          std::vector<std::pair<double, double>> side;
          unsigned int                           off_axis = 0;
          for (const auto &[x, pr] : signed_profile)
            if (sign * x >= -on_axis)
              {
                side.emplace_back(std::abs(x), pr);
                if (sign * x > on_axis)
                  ++off_axis;
              }
          std::sort(side.begin(), side.end());
          if (off_axis >= 2)
            sides.push_back(side);
        }

      double       a_sum = 0., e2 = 0., n2 = 0.;
      unsigned int n_sides = 0;
      result.pair_spacing  = std::numeric_limits<double>::max();
      for (const auto &profile : sides)
        {
          // Half-width: the last loaded pair, refined by the ellipse
          // p^2 = c (a^2 - x^2) through the last two loaded pairs, kept
          // between the last loaded and the first open pair.
          int last = -1;
          for (unsigned int k = 0; k < profile.size(); ++k)
            if (profile[k].second > 1e-6 * peak)
              last = k;
          double a_h = (last >= 0 ? profile[last].first : 0.);
          if (last >= 1)
            {
              const double x1 = profile[last - 1].first,
                           p1 = profile[last - 1].second;
              const double x2 = profile[last].first, p2 = profile[last].second;
              if (p1 > p2)
                {
                  const double a2 = (p1 * p1 * x2 * x2 - p2 * p2 * x1 * x1) /
                                    (p1 * p1 - p2 * p2);
                  double       estimate = std::sqrt(std::max(a2, 0.));
                  const double upper =
                    (last + 1 < int(profile.size()) ? profile[last + 1].first :
                                                      estimate);
                  a_h = std::min(std::max(estimate, x2), upper);
                }
            }
          a_sum += a_h;
          ++n_sides;
          if (last >= 0 && last + 1 < int(profile.size()))
            result.edge_pair_spacing =
              std::max(result.edge_pair_spacing,
                       profile[last + 1].first - profile[last].first);
          else if (last >= 1)
            result.edge_pair_spacing =
              std::max(result.edge_pair_spacing,
                       profile[last].first - profile[last - 1].first);
          result.pair_spacing =
            std::min(result.pair_spacing, profile[1].first - profile[0].first);

          // L2 distance of the piecewise linear pair profile to Johnson's
          // over |x| <= 1.2 a.
          auto p_h = [&](const double x) {
            if (x <= profile.front().first)
              return profile.front().second;
            for (unsigned int k = 1; k < profile.size(); ++k)
              if (x <= profile[k].first)
                {
                  const double t = (x - profile[k - 1].first) /
                                   (profile[k].first - profile[k - 1].first);
                  return (1 - t) * profile[k - 1].second +
                         t * profile[k].second;
                }
            return profile.back().second;
          };
          const unsigned int n_samples = 4000;
          for (unsigned int k = 0; k < n_samples; ++k)
            {
              const double x = 1.2 * a * (k + 0.5) / n_samples;
              const double pe =
                (x < a ? p0 * std::sqrt(1. - x * x / (a * a)) : 0.);
              e2 += std::pow(p_h(x) - pe, 2);
              n2 += pe * pe;
            }
        }
      if (n_sides == 0)
        result.pair_spacing = 0.;
      result.half_width       = (n_sides > 0 ? a_sum / n_sides : 0.);
      result.profile_l2_error = (n2 > 0. ? std::sqrt(e2 / n2) : 0.);

      // Pair by pair inside |x| < 0.9 a, where the profile is smooth on the
      // scale of the pairs (its curvature grows as (1 - x^2/a^2)^{-3/2}
      // towards the edge, a factor 12 at 0.9 a).
      for (const auto &[x, pr] : signed_profile)
        if (std::abs(x) < 0.9 * a)
          {
            const double pe = p0 * std::sqrt(1. - x * x / (a * a));
            result.max_pair_deviation =
              std::max(result.max_pair_deviation, std::abs(pr - pe) / p0);
            ++result.n_inner_pairs;
          }

      // Resolution: the pairs resolve the contact zone only when several
      // of them lie inside it; with the zone narrower than the pair
      // spacing next to the axis, one pair carries the whole load and the
      // figures above measure the spacing, not the method.
      if (result.n_loaded < 3 || a < 2. * result.pair_spacing)
        {
          std::ostringstream w;
          w << "Hertz check: the contact zone (Johnson half-width " << a
            << ") is not resolved by the pairs (" << result.n_loaded
            << " loaded, spacing " << result.pair_spacing
            << " next to the axis); its half-width, peak pressure and "
               "profile error measure the pair spacing, not the method. "
               "Refine the contact face (Discretization/Refinements or Body "
               "1/Subdivisions) until the half-width spans several pairs."
            << units_hint(a, R, "half-width");
          result.warnings.push_back(w.str());
        }
      if (element_depth > 2. * a)
        result.warnings.push_back(
          depth_warning(element_depth, a, "half-width"));
      return result;
    }



    double
    RoundedPunchCheck::half_width() const
    {
      const double b = flat_half_width, R = corner_radius;
      const double E = effective_modulus, P = line_load;
      const auto   load_of = [&](const double a) {
        const double phi0 = std::asin(std::min(1., b / a));
        return E * a * a * (M_PI - 2. * phi0 - std::sin(2. * phi0)) / (4. * R);
      };
      // The load grows from 0 at a = b without bound: bracket, then
      // TOMS 748 to round-off.
      double hi = std::max(2. * b, std::sqrt(4. * P * R / (M_PI * E)));
      while (load_of(hi) < P)
        hi *= 2.;
      std::uintmax_t iterations = 200;
      const auto     bracket    = boost::math::tools::toms748_solve(
        [&](const double a) {
          return load_of(a) - P;
        },
        b,
        hi,
        boost::math::tools::eps_tolerance<double>(50),
        iterations);
      return 0.5 * (bracket.first + bracket.second);
    }



    double
    RoundedPunchCheck::pressure(const double x_signed) const
    {
      const double x = std::abs(x_signed);
      const double a = half_width();
      if (x >= a)
        return 0.;
      const double b = flat_half_width, R = corner_radius;
      const double phi0 = std::asin(std::min(1., b / a));
      const double t0   = std::tan(0.5 * phi0);
      const double s    = std::sqrt(a * a - x * x);
      // L(sigma x) with a - s = x^2 / (a + s), the factor x cancelled: no
      // cancellation near the axis, where L tends to ln(1 / t0).
      const double q = x / (a + s);
      const auto   L = [&](const double sigma) {
        return std::log(std::abs((sigma + q) / (sigma * t0 + q))) -
               std::log(
                 std::abs((sigma * x + a + s) / (sigma * x * t0 + a + s)));
      };
      // (x - b) L(-x) vanishes at x = b, where L(-x) is singular, and
      // (x + b) L(x) on the axis of a punch without a flat (Hertz).
      double bracket = (M_PI - 2. * phi0) * s;
      if (x + b != 0.)
        bracket -= (x + b) * L(1.);
      if (x != b)
        bracket += (x - b) * L(-1.);
      return effective_modulus / (2. * M_PI * R) * bracket;
    }



    RoundedPunchCheck::Result
    RoundedPunchCheck::evaluate(
      const std::vector<contact::PairState<2>> &pairs) const
    {
      Result       result;
      const double a          = half_width();
      result.half_width_exact = a;
      // The peak lies in the corners' part of the contact, b <= x < a (at
      // the axis when b = 0).
      const double b = flat_half_width;
      if (b > 0.)
        {
          const auto minimum = boost::math::tools::brent_find_minima(
            [&](const double x) {
              return -pressure(x);
            },
            b,
            a,
            50);
          result.peak_location_exact = minimum.first;
          result.peak_pressure_exact = -minimum.second;
        }
      if (!(result.peak_pressure_exact >= pressure(0.)))
        {
          result.peak_location_exact = 0.;
          result.peak_pressure_exact = pressure(0.);
        }

      const Tensor<1, 2> e = axis_direction / axis_direction.norm();
      const Tensor<1, 2> e_normal({-e[1], e[0]});
      for (const auto &pair : pairs)
        result.peak_pressure = std::max(result.peak_pressure, pair.pressure());
      for (const auto &pair : pairs)
        {
          const double x = (pair.location - axis_point) * e_normal;
          if (pair.pressure() > 1e-6 * result.peak_pressure)
            ++result.n_loaded;
          if (std::abs(x) >= 0.9 * a)
            continue;
          ++result.n_inner_pairs;
          result.max_pair_deviation =
            std::max(result.max_pair_deviation,
                     std::abs(pair.pressure() - pressure(x)) /
                       result.peak_pressure_exact);
        }
      return result;
    }



    HertzPointCheck::Result
    HertzPointCheck::evaluate(
      const std::vector<contact::PairState<3>> &pairs) const
    {
      Result       result;
      const double P = load, R = radius;
      const double a  = std::cbrt(3. * P * R / (4. * effective_modulus));
      const double p0 = 3. * P / (2. * M_PI * a * a);
      result.contact_radius_exact = a;
      result.peak_pressure_exact  = p0;

      const Tensor<1, 3> e        = axis_direction / axis_direction.norm();
      const auto         distance = [&](const Point<3> &x) {
        const Tensor<1, 3> r = x - axis_point;
        return (r - (r * e) * e).norm();
      };
      const auto hertz = [&](const double r) {
        return (r < a ? p0 * std::sqrt(1. - r * r / (a * a)) : 0.);
      };

      double force = 0., moment = 0.;
      for (const auto &pair : pairs)
        {
          const double r = distance(pair.location);
          result.peak_pressure =
            std::max(result.peak_pressure, pair.pressure());
          force += pair.force_local[0];
          moment += pair.force_local[0] * r * r;
        }
      const double peak = result.peak_pressure;
      result.contact_radius_moment =
        (force > 0. ? std::sqrt(2.5 * std::max(moment, 0.) / force) : 0.);

      // The ellipse p^2 = alpha - c r^2 through the pairs above half the
      // peak, by least squares (2 x 2 normal equations).
      double s0 = 0., s1 = 0., s2 = 0., t0 = 0., t1 = 0.;
      double e2 = 0., n2 = 0.;
      for (const auto &pair : pairs)
        {
          const double r = distance(pair.location), p = pair.pressure();
          if (p > 1e-6 * peak)
            ++result.n_loaded;
          if (p >= 0.5 * peak && peak > 0.)
            {
              ++result.n_fitted;
              s0 += 1.;
              s1 += r * r;
              s2 += r * r * r * r;
              t0 += p * p;
              t1 += p * p * r * r;
            }
          if (r <= 1.2 * a)
            {
              e2 += pair.area * std::pow(p - hertz(r), 2);
              n2 += pair.area * std::pow(hertz(r), 2);
            }
          if (r < 0.9 * a)
            {
              result.max_pair_deviation = std::max(result.max_pair_deviation,
                                                   std::abs(p - hertz(r)) / p0);
              ++result.n_inner_pairs;
            }
        }
      result.profile_l2_error = (n2 > 0. ? std::sqrt(e2 / n2) : 0.);
      // alpha s0 - c s1 = t0, alpha s1 - c s2 = t1.
      const double det   = s1 * s1 - s0 * s2;
      const double c     = (det != 0. ? (s0 * t1 - s1 * t0) / det : 0.);
      const double alpha = (s0 > 0. ? (t0 + c * s1) / s0 : 0.);
      result.contact_radius =
        (c > 0. && alpha > 0. ? std::sqrt(alpha / c) : 0.);

      // Resolution: the fit needs pairs at several distances inside the
      // zone; with fewer the figures measure the pair spacing.
      if (result.n_fitted < 6 || !(result.contact_radius > 0.))
        {
          std::ostringstream w;
          w << "Hertz check: the contact zone (Hertz radius " << a
            << ") is not resolved by the pairs (" << result.n_loaded
            << " loaded, " << result.n_fitted
            << " above half the peak pressure); its radius, peak pressure "
               "and profile error measure the pair spacing, not the method. "
               "Refine the contact face (Body 1/Subdivisions or Grading "
               "toward the contact) until the zone spans several pairs in "
               "each direction."
            << units_hint(a, R, "contact radius");
          result.warnings.push_back(w.str());
        }
      if (element_depth > 2. * a)
        result.warnings.push_back(depth_warning(element_depth, a, "radius"));
      return result;
    }



    HertzEllipticCheck::Exact
    HertzEllipticCheck::exact() const
    {
      const double A = std::min(curvature_x, curvature_y);
      const double B = std::max(curvature_x, curvature_y);
      AssertThrow(A > 0. && effective_modulus > 0. && load > 0.,
                  ExcMessage("HertzEllipticCheck: both relative curvatures, "
                             "E* and the load must be positive."));
      Exact  result;
      double e = 0.;
      // B/A as a function of e rises from 1 (e = 0) without bound (e -> 1).
      const auto ratio = [](const double e) {
        const double K = boost::math::ellint_1(e), E = boost::math::ellint_2(e);
        return (E / (1. - e * e) - K) / (K - E);
      };
      // Near the sphere, from the series ratio = 1 + 3 e^2 / 4 + 21 e^4 /
      // 32 + O(e^6) inverted: e^2 = 4 d / 3 - 14 d^2 / 9 + O(d^3), d =
      // B/A - 1 (the elliptic integrals' differences lose their digits
      // there).
      const double d = B / A - 1.;
      if (d < 1e-3)
        e = std::sqrt(4. / 3. * d - 14. / 9. * d * d);
      else
        {
          double hi = 0.5;
          while (ratio(hi) < B / A && hi < 1. - 1e-15)
            hi = 1. - 0.5 * (1. - hi);
          std::uintmax_t iterations = 200;
          const auto     bracket    = boost::math::tools::toms748_solve(
            [&](const double x) {
              return ratio(x) - B / A;
            },
            1e-2,
            hi,
            boost::math::tools::eps_tolerance<double>(50),
            iterations);
          e = 0.5 * (bracket.first + bracket.second);
        }
      // (K - E) / e^2 = pi / 4 (1 + 3 e^2 / 8 + 15 e^4 / 64 + O(e^6)).
      const double K_minus_E_over_e2 =
        e < 1e-2 ?
          M_PI / 4. * (1. + 3. / 8. * e * e + 15. / 64. * e * e * e * e) :
          (boost::math::ellint_1(e) - boost::math::ellint_2(e)) / (e * e);
      const double a       = std::cbrt(3. * load * K_minus_E_over_e2 /
                                 (2. * M_PI * effective_modulus * A));
      const double b       = a * std::sqrt(1. - e * e);
      result.eccentricity  = e;
      result.semi_axis_x   = (curvature_x <= curvature_y ? a : b);
      result.semi_axis_y   = (curvature_x <= curvature_y ? b : a);
      result.peak_pressure = 3. * load / (2. * M_PI * a * b);
      return result;
    }



    HertzEllipticCheck::Result
    HertzEllipticCheck::evaluate(
      const std::vector<contact::PairState<3>> &pairs) const
    {
      Result result;
      result.exact          = exact();
      const double       ax = result.exact.semi_axis_x;
      const double       ay = result.exact.semi_axis_y;
      const double       p0 = result.exact.peak_pressure;
      const Tensor<1, 3> ez = axis_direction / axis_direction.norm();
      Tensor<1, 3> ex = principal_direction - (principal_direction * ez) * ez;
      ex /= ex.norm();
      const Tensor<1, 3> ey    = cross_product_3d(ez, ex);
      const auto         hertz = [&](const double x, const double y) {
        const double s = 1. - x * x / (ax * ax) - y * y / (ay * ay);
        return s > 0. ? p0 * std::sqrt(s) : 0.;
      };
      double force = 0., mx = 0., my = 0., e2 = 0., n2 = 0.;
      for (const auto &pair : pairs)
        result.peak_pressure = std::max(result.peak_pressure, pair.pressure());
      for (const auto &pair : pairs)
        {
          const Tensor<1, 3> r = pair.location - axis_point;
          const double       x = r * ex, y = r * ey;
          const double       f = pair.force_local[0], p = pair.pressure();
          force += f;
          mx += f * x * x;
          my += f * y * y;
          if (p > 1e-6 * result.peak_pressure)
            ++result.n_loaded;
          if (x * x / (ax * ax) + y * y / (ay * ay) <= 1.44)
            {
              e2 += pair.area * std::pow(p - hertz(x, y), 2);
              n2 += pair.area * std::pow(hertz(x, y), 2);
            }
        }
      if (force > 0.)
        {
          result.semi_axis_x_moment = std::sqrt(5. * std::max(mx, 0.) / force);
          result.semi_axis_y_moment = std::sqrt(5. * std::max(my, 0.) / force);
        }
      result.profile_l2_error = n2 > 0. ? std::sqrt(e2 / n2) : 0.;
      if (result.n_loaded < 12)
        {
          std::ostringstream w;
          w << "Hertz check: the elliptical contact zone (Hertz semi-axes "
            << ax << ", " << ay << ") is not resolved by the pairs ("
            << result.n_loaded
            << " loaded); its semi-axes, peak pressure and profile error "
               "measure the pair spacing, not the method. Refine the "
               "contact face (Body 1/Subdivisions or Grading toward the "
               "contact) until the zone spans several pairs in each "
               "direction."
            << units_hint(std::min(ax, ay),
                          1. / (2. * std::max(curvature_x, curvature_y)),
                          "smaller semi-axis");
          result.warnings.push_back(w.str());
        }
      return result;
    }



    template double
    pressure_uniformity<2>(const std::vector<contact::PairState<2>> &,
                           const double);
    template double
    pressure_uniformity<3>(const std::vector<contact::PairState<3>> &,
                           const double);
    template double
    effective_modulus<2>(const elasticity::IsotropicMaterial<2> &,
                         const elasticity::IsotropicMaterial<2> *);
    template double
    effective_modulus<3>(const elasticity::IsotropicMaterial<3> &,
                         const elasticity::IsotropicMaterial<3> *);
    template double
    dundurs_beta<2>(const elasticity::IsotropicMaterial<2> &,
                    const elasticity::IsotropicMaterial<2> *);
    template double
    dundurs_beta<3>(const elasticity::IsotropicMaterial<3> &,
                    const elasticity::IsotropicMaterial<3> *);
  } // namespace postprocess
} // namespace igabde
