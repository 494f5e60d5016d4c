#include <igabde/postprocess/contact_checks.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace igabde
{
  namespace postprocess
  {
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



    HertzCheck::Result
    HertzCheck::evaluate(const std::vector<contact::PairState<2>> &pairs) const
    {
      Result       result;
      const double P = line_load, R = radius;
      const double a  = std::sqrt(4. * P * R / (M_PI * effective_modulus));
      const double p0 = 2. * P / (M_PI * a);
      result.half_width_exact    = a;
      result.peak_pressure_exact = p0;

      // Pair pressures by distance from the symmetry axis.
      const Tensor<1, 2> e = axis_direction / axis_direction.norm();
      std::vector<std::pair<double, double>> profile;
      for (const auto &pair : pairs)
        {
          const Tensor<1, 2> r = pair.location - axis_point;
          profile.emplace_back((r - (r * e) * e).norm(), pair.pressure());
        }
      std::sort(profile.begin(), profile.end());
      double peak = 0.;
      for (const auto &[x, pr] : profile)
        peak = std::max(peak, pr);
      result.peak_pressure = peak;

      // Half-width: the last loaded pair (loaded: above 1e-6 of the peak,
      // the solver's round-off), refined by the ellipse
      // p^2 = c (a^2 - x^2) through the last two loaded pairs, kept between
      // the last loaded and the first open pair.
      int last = -1;
      for (unsigned int k = 0; k < profile.size(); ++k)
        if (profile[k].second > 1e-6 * peak)
          {
            last = k;
            ++result.n_loaded;
          }
      double a_h = (last >= 0 ? profile[last].first : 0.);
      if (last >= 1)
        {
          const double x1 = profile[last - 1].first,
                       p1 = profile[last - 1].second;
          const double x2 = profile[last].first, p2 = profile[last].second;
          if (p1 > p2)
            {
              const double a2 =
                (p1 * p1 * x2 * x2 - p2 * p2 * x1 * x1) / (p1 * p1 - p2 * p2);
              double       estimate = std::sqrt(std::max(a2, 0.));
              const double upper =
                (last + 1 < int(profile.size()) ? profile[last + 1].first :
                                                  estimate);
              a_h = std::min(std::max(estimate, x2), upper);
            }
        }
      result.half_width = a_h;
      if (last >= 0 && last + 1 < int(profile.size()))
        result.edge_pair_spacing =
          profile[last + 1].first - profile[last].first;
      else if (last >= 1)
        result.edge_pair_spacing =
          profile[last].first - profile[last - 1].first;

      // L2 distance of the piecewise linear pair profile to Johnson's over
      // |x| <= 1.2 a.
      auto p_h = [&](const double x) {
        if (x <= profile.front().first)
          return profile.front().second;
        for (unsigned int k = 1; k < profile.size(); ++k)
          if (x <= profile[k].first)
            {
              const double t = (x - profile[k - 1].first) /
                               (profile[k].first - profile[k - 1].first);
              return (1 - t) * profile[k - 1].second + t * profile[k].second;
            }
        return profile.back().second;
      };
      double             e2 = 0., n2 = 0.;
      const unsigned int n_samples = 4000;
      for (unsigned int k = 0; k < n_samples; ++k)
        {
          const double x  = 1.2 * a * (k + 0.5) / n_samples;
          const double pe = (x < a ? p0 * std::sqrt(1. - x * x / (a * a)) : 0.);
          e2 += std::pow(p_h(x) - pe, 2);
          n2 += pe * pe;
        }
      result.profile_l2_error = std::sqrt(e2 / n2);

      // Resolution: the pairs resolve the contact zone only when several
      // of them lie inside it; with the zone narrower than the pair
      // spacing next to the axis, one pair carries the whole load and the
      // figures above measure the spacing, not the method.
      if (profile.size() >= 2)
        result.pair_spacing = profile[1].first - profile[0].first;
      if (result.n_loaded < 3 || a < 2. * result.pair_spacing)
        {
          std::ostringstream w;
          w << "Hertz check: the contact zone (Johnson half-width " << a
            << ") is not resolved by the pairs (" << result.n_loaded
            << " loaded, spacing " << result.pair_spacing
            << " next to the axis); its half-width, peak pressure and "
               "profile error measure the pair spacing, not the method. "
               "Refine the contact face (Discretization/Refinements or Body "
               "1/Subdivisions) until the half-width spans several pairs.";
          result.warning = w.str();
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
  } // namespace postprocess
} // namespace igabde
