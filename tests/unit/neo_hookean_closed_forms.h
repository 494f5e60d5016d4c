// Closed forms of the compressible neo-Hookean law W = mu/2 (tr C - 3) -
// mu ln J + lambda/2 (ln J)^2 in plane strain that the command-line tests
// compare the runs with (derived by hand, independent of the code).

#ifndef igabde_tests_neo_hookean_closed_forms_h
#define igabde_tests_neo_hookean_closed_forms_h

#include <cmath>

namespace neo_hookean_closed_forms
{
  /// Lame's mu and lambda of Young's modulus @p E and Poisson's ratio @p nu.
  inline double
  shear_modulus(const double E, const double nu)
  {
    return E / (2. * (1. + nu));
  }

  inline double
  lame_lambda(const double E, const double nu)
  {
    return E * nu / ((1. + nu) * (1. - 2. * nu));
  }

  /// Uniaxial stress in plane strain with the stretch @p stretch along one
  /// axis: the stretch s across it, the root of mu (s^2 - 1) + lambda
  /// ln(stretch s) = 0 (zero stress across), by bisection (the function
  /// grows with s).
  inline double
  lateral_stretch(const double stretch, const double E, const double nu)
  {
    const double mu = shear_modulus(E, nu), lambda = lame_lambda(E, nu);
    double       low = 1e-3, high = 10.;
    for (unsigned int k = 0; k < 200; ++k)
      {
        const double s = 0.5 * (low + high);
        (mu * (s * s - 1.) + lambda * std::log(stretch * s) < 0. ? low : high) =
          s;
      }
    return 0.5 * (low + high);
  }

  /// The first Piola-Kirchhoff stress along the stretched axis of that
  /// state: stretch (mu (1 - 1/stretch^2) + lambda ln J / stretch^2), J =
  /// stretch s.
  inline double
  uniaxial_first_piola(const double stretch, const double E, const double nu)
  {
    const double mu = shear_modulus(E, nu), lambda = lame_lambda(E, nu);
    const double J = stretch * lateral_stretch(stretch, E, nu);
    return stretch * (mu * (1. - 1. / (stretch * stretch)) +
                      lambda * std::log(J) / (stretch * stretch));
  }
} // namespace neo_hookean_closed_forms

#endif
