#ifndef igabde_postprocess_contact_checks_h
#define igabde_postprocess_contact_checks_h

#include <igabde/elasticity/material.h>

#include <igabde/contact/contact_stage.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace igabde
{
  namespace postprocess
  {
    using namespace dealii;

    /**
     * @brief The contact patch test (V3): every pair should carry the
     * applied pressure. Returns max_i |p_i / p - 1| over the pairs.
     */
    template <int dim>
    double
    pressure_uniformity(const std::vector<contact::PairState<dim>> &pairs,
                        const double expected_pressure);

    /**
     * @brief Hertz's effective modulus of two bodies in contact:
     * 1/E* = (1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2 in plane strain and 3D,
     * 1/E* = 1/E_1 + 1/E_2 in plane stress; @p body2 nullptr is a rigid
     * obstacle (its term vanishes).
     */
    template <int dim>
    double
    effective_modulus(const elasticity::IsotropicMaterial<dim> &body1,
                      const elasticity::IsotropicMaterial<dim> *body2);

    /**
     * @brief Dundurs' second constant of two bodies in contact,
     * beta = (G_1 (kappa_2 - 1) - G_2 (kappa_1 - 1)) / (G_1 (kappa_2 + 1)
     * + G_2 (kappa_1 + 1)), kappa = 3 - 4 nu (plane strain and 3D) or
     * (3 - nu) / (1 + nu) (plane stress), G the shear modulus; @p body2
     * nullptr is a rigid obstacle: beta = -(kappa_1 - 1) / (kappa_1 + 1).
     * Zero when normal pressure makes no tangential mismatch of the two
     * surfaces (similar bodies): only then does friction leave Hertz's
     * frictionless solution unchanged (Dundurs; Spence's frictional
     * Hertz problem otherwise).
     */
    template <int dim>
    double
    dundurs_beta(const elasticity::IsotropicMaterial<dim> &body1,
                 const elasticity::IsotropicMaterial<dim> *body2);

    /**
     * @brief The 2D Hertz line contact of a cylinder of radius R pressed by
     * the line load P (Johnson, Contact Mechanics §4.2):
     * a = sqrt(4 P R / (pi E*)), p(x) = p0 sqrt(1 - x^2/a^2),
     * p0 = 2 P / (pi a); x is the distance from the symmetry axis (the line
     * through axis_point along axis_direction).
     */
    struct HertzCheck
    {
      double       line_load         = 0.;
      double       radius            = 0.;
      double       effective_modulus = 0.;
      Point<2>     axis_point;
      Tensor<1, 2> axis_direction;
      /// Depth of Body 1's elements under the contact's centre (their size
      /// normal to the contact face); 0: not checked.
      double element_depth = 0.;

      struct Result
      {
        /// Half-width from the pairs: the last loaded pair, refined by the
        /// ellipse through the last two loaded pairs; the mean of the two
        /// sides of the axis when both have pairs (a full model), the one
        /// side of a half model.
        double half_width = 0.;
        /// Half-width from the second moment of the pair forces about the
        /// axis: Johnson's profile has int p x^2 / int p = a^2 / 4, so
        /// a_m = 2 sqrt(sum F_i x_i^2 / sum F_i). It uses every pair, not
        /// the edge ones: it does not depend on whether a pair's pressure
        /// is a point value (node-to-surface) or a mean over the support
        /// of a basis function (weighted-gap), and is biased by O(h^2) (a
        /// pair's force acts at one x_i).
        double half_width_moment   = 0.;
        double half_width_exact    = 0.;
        double peak_pressure       = 0.;
        double peak_pressure_exact = 0.;
        /// L2 distance of the piecewise linear pair profile to Johnson's
        /// over |x| <= 1.2 a, relative (both sides together).
        double profile_l2_error = 0.;
        /// Largest |p_i - p(x_i)| / p0 over the pairs inside |x| < 0.9 a
        /// (Johnson's a and p0; p_i the pair pressure, x_i its distance
        /// from the axis), and how many pairs lie there.
        double       max_pair_deviation = 0.;
        unsigned int n_inner_pairs      = 0;
        /// Pairs carrying load, and the pair spacing next to the axis.
        unsigned int n_loaded     = 0;
        double       pair_spacing = 0.;
        /// Distance between the last loaded and the first open pair (or
        /// the last two pairs when every pair is loaded): the interval the
        /// half-width estimate is kept in, hence the resolution of
        /// half_width.
        double edge_pair_spacing = 0.;
        /// Why the figures above do not measure the method, if they do not:
        /// the contact zone is not resolved by the pairs, or by the
        /// elements under it (element_depth > 2 a).
        std::vector<std::string> warnings;
      };

      Result
      evaluate(const std::vector<contact::PairState<2>> &pairs) const;
    };

    /**
     * @brief A rigid flat punch with rounded corners pressed by the line load
     * P into an elastic half-plane, frictionless (Ciavarella, Hills & Monno
     * 1998): the profile is flat over |x| <= b and rises as
     * (|x| - b)^2 / (2 R) beyond (the circular corners of radius R to
     * second order), x the distance from the axis through axis_point along
     * axis_direction.
     *
     * With x = a sin(phi) and b = a sin(phi_0), the half-width a follows
     * from P = E* a^2 (pi - 2 phi_0 - sin 2 phi_0) / (4 R), and the
     * pressure, bounded at both ends, is
     * p(x) = E* / (2 pi R) [(pi - 2 phi_0) s + (x - b) L(-x) - (x + b) L(x)],
     * s = sqrt(a^2 - x^2), L(c) = [ln |(c t + a - s) / (c t + a + s)|]
     * from t = tan(phi_0 / 2) to 1 (the inversion of the half-plane's
     * integral equation, evaluated in closed form; b = 0 gives Hertz).
     */
    struct RoundedPunchCheck
    {
      double       line_load         = 0.;
      double       flat_half_width   = 0.;
      double       corner_radius     = 0.;
      double       effective_modulus = 0.;
      Point<2>     axis_point;
      Tensor<1, 2> axis_direction;

      /// The half-width a of the contact under line_load.
      double
      half_width() const;

      /// The closed-form pressure at distance @p x from the axis (0 for
      /// |x| >= a).
      double
      pressure(const double x) const;

      struct Result
      {
        double half_width_exact = 0.;
        /// The closed form's largest pressure and where it is (|x|).
        double peak_pressure_exact = 0.;
        double peak_location_exact = 0.;
        /// The largest pair pressure.
        double peak_pressure = 0.;
        /// Largest |p_i - p(x_i)| over the pairs inside |x| < 0.9 a, over
        /// the closed form's peak, and how many pairs lie there. Beyond,
        /// p falls to 0 as sqrt(a - x), so a shift of the edge that is no
        /// error of the discretisation (the finite body, the obstacle's
        /// tilted normals) shows pointwise magnified (Hertz's check
        /// leaves the edge out alike).
        double       max_pair_deviation = 0.;
        unsigned int n_inner_pairs      = 0;
        /// Pairs carrying load (above 1e-6 of the peak).
        unsigned int n_loaded = 0;
      };

      Result
      evaluate(const std::vector<contact::PairState<2>> &pairs) const;
    };

    /**
     * @brief The 3D Hertz point contact of a sphere of radius R pressed by
     * the force P onto a flat (Johnson, Contact Mechanics §4.2):
     * a = (3 P R / (4 E*))^(1/3), p(r) = p0 sqrt(1 - r^2/a^2),
     * p0 = 3 P / (2 pi a^2); r is the distance from the axis through
     * axis_point along axis_direction (the load direction). A half or
     * quarter model (symmetry planes through the axis) gives the same
     * figures as the whole: each is a pointwise value or a ratio of sums
     * over the pairs, and P stays the whole sphere's load.
     */
    struct HertzPointCheck
    {
      double       load              = 0.;
      double       radius            = 0.;
      double       effective_modulus = 0.;
      Point<3>     axis_point;
      Tensor<1, 3> axis_direction;
      /// Depth of Body 1's elements under the contact's centre; 0: not
      /// checked.
      double element_depth = 0.;

      struct Result
      {
        /// Contact radius from the pairs: the least-squares fit of
        /// Hertz's ellipse p^2 = c (a^2 - r^2) to the pairs carrying at
        /// least half the peak pressure (r up to about 0.87 a), a =
        /// sqrt(c a^2 / c); it uses the pairs where the profile is smooth,
        /// not the edge, where a pair's pressure is smeared over its
        /// support (weighted-gap) or its tributary area.
        double contact_radius = 0.;
        /// Contact radius from the second moment of the pair forces:
        /// Hertz's profile has int p r^2 dA / int p dA = 2 a^2 / 5, so
        /// a_m = sqrt(5/2 sum F_i r_i^2 / sum F_i); biased by O(h^2) where
        /// a pair's force is spread over a basis function's support.
        double contact_radius_moment = 0.;
        double contact_radius_exact  = 0.;
        double peak_pressure         = 0.;
        double peak_pressure_exact   = 0.;
        /// sqrt(sum A_i (p_i - p(r_i))^2 / sum A_i p(r_i)^2) over the pairs
        /// with r_i <= 1.2 a (A_i the pairs' areas), Hertz's a and p0.
        double profile_l2_error = 0.;
        /// Largest |p_i - p(r_i)| / p0 over the pairs inside r < 0.9 a,
        /// and how many pairs lie there.
        double       max_pair_deviation = 0.;
        unsigned int n_inner_pairs      = 0;
        /// Pairs carrying load, and those in the ellipse fit.
        unsigned int n_loaded = 0;
        unsigned int n_fitted = 0;
        /// Why the figures do not measure the method, if they do not.
        std::vector<std::string> warnings;
      };

      Result
      evaluate(const std::vector<contact::PairState<3>> &pairs) const;
    };

    /**
     * @brief Hertz's elliptical point contact (Johnson, Contact Mechanics
     * §4.2): two bodies whose principal directions of curvature at the
     * contact point are aligned, with principal radii (R1x, R1y) and
     * (R2x, R2y) along e_x = principal_direction and e_y = axis x e_x (a
     * flat direction has curvature 0), pressed by P. The gap is
     * A x^2 + B y^2 with A = (1/R1x + 1/R2x)/2, B = (1/R1y + 1/R2y)/2; the
     * contact is the ellipse x^2/a_x^2 + y^2/a_y^2 <= 1 carrying
     * p = p0 sqrt(1 - x^2/a_x^2 - y^2/a_y^2), p0 = 3 P / (2 pi a_x a_y).
     * With a >= b the semi-axes along the smaller and the larger of A, B
     * and e = sqrt(1 - b^2/a^2), Johnson's (4.39)-(4.41):
     * B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e)) for the larger over the
     * smaller, and a^3 = 3 P (K(e) - E(e)) / (2 pi E* e^2 A_small); K, E
     * the complete elliptic integrals of modulus e. A = B gives the
     * sphere. As for HertzPointCheck, a half or quarter model gives the
     * whole contact's figures, P its whole load.
     */
    struct HertzEllipticCheck
    {
      double       load              = 0.;
      double       curvature_x       = 0.; ///< A = (1/R1x + 1/R2x) / 2
      double       curvature_y       = 0.; ///< B = (1/R1y + 1/R2y) / 2
      double       effective_modulus = 0.;
      Point<3>     axis_point;
      Tensor<1, 3> axis_direction;
      Tensor<1, 3> principal_direction;

      struct Exact
      {
        double semi_axis_x = 0., semi_axis_y = 0.;
        double peak_pressure = 0.;
        double eccentricity  = 0.;
      };

      /// Johnson's semi-axes and peak pressure for these inputs.
      Exact
      exact() const;

      struct Result
      {
        Exact exact;
        /// Semi-axes from the second moments of the pair forces: Hertz's
        /// profile has int p x^2 dA / int p dA = a_x^2 / 5 (and y), so
        /// a_x = sqrt(5 sum F_i x_i^2 / sum F_i).
        double semi_axis_x_moment = 0., semi_axis_y_moment = 0.;
        double peak_pressure = 0.;
        /// sqrt(sum A_i (p_i - p(x_i))^2 / sum A_i p(x_i)^2) over the pairs
        /// inside 1.2 times the ellipse.
        double                   profile_l2_error = 0.;
        unsigned int             n_loaded         = 0;
        std::vector<std::string> warnings;
      };

      Result
      evaluate(const std::vector<contact::PairState<3>> &pairs) const;
    };
  } // namespace postprocess
} // namespace igabde

#endif
