#include <igabde/contact/path_cost.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace igabde
{
  namespace contact
  {
    PathCostConstants
    PathCostConstants::measured()
    {
      // Fitted by contrib/benchmarks/path-cost (doc/performance.md,
      // "Choosing the contact path", gives the cases and their figures):
      // dense and schur from the largest case (the B-Newton phase over
      // N m^3/3, the condensation and the Schur part of the factorisation
      // over the face term); sparse_d the largest seconds per factor entry
      // and Newton iteration of the full-system solve among the cases of
      // each dimension; the Newton iterations per step those of B2.
      PathCostConstants c;
      c.dense               = 1.1e-11;
      c.schur               = 4.8e-11;
      c.sparse_2d           = 3.4e-8;
      c.sparse_3d           = 1.1e-7;
      c.iterations_per_step = 8.;
      return c;
    }



    PathCostEstimate
    estimate_path_costs(const PathCostInputs    &inputs,
                        const PathCostConstants &constants)
    {
      const double m    = inputs.contact_unknowns;
      const double N    = inputs.newton_iterations;
      double       face = 0., factor = 0.;
      for (const double n_I : inputs.face_unknowns)
        face += n_I * n_I * n_I / 3. + n_I * n_I * m + n_I * m * m;
      for (const double L : inputs.factor_entries)
        factor += L;
      const double     condensation = constants.schur * face;
      const double     bnewton      = constants.dense * N * m * m * m / 3.;
      PathCostEstimate e;
      e.condensed_seconds = condensation + bnewton;
      e.full_seconds =
        (inputs.dimension == 2 ? constants.sparse_2d : constants.sparse_3d) *
        N * factor;
      e.path =
        (e.full_seconds < e.condensed_seconds ? Path::full : Path::condensed);
      std::ostringstream s;
      s << std::setprecision(3) << "auto: estimated condensed "
        << e.condensed_seconds << " s (condensation " << condensation
        << " s, dense B-Newton " << bnewton << " s for " << m
        << " contact unknowns) against full " << e.full_seconds << " s (" << N
        << " sparse factorisations of ";
      double entries = 0.;
      for (const double L : inputs.factor_entries)
        entries += L;
      s << entries << " factor entries): " << to_string(e.path)
        << " is cheaper";
      e.reason = s.str();
      return e;
    }
  } // namespace contact
} // namespace igabde
