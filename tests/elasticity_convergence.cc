// Convergence of the elasticity paths on V1 (plate with a hole, Kirsch) and
// V2 (Lame cylinder): observed L2 and energy rates over the last levels
// against the theoretical rates, NURBS p = 2, 3 and FE_Q(2).

#include "tests.h"

#include <igabde/base/utilities.h>

#include <igabde/scene/simulator.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

using namespace igabde;

namespace
{
  struct Level
  {
    double l2, energy;
  };

  Level
  run(const std::string &scene,
      const std::string &type,
      const unsigned int degree,
      const unsigned int refinements)
  {
    std::ostringstream log;
    const auto         summary = scene::run_scene_in_process(
      (std::filesystem::path(SOURCE_DIR) / ".." / "prm" / (scene + ".prm"))
        .string(),
      {{"Discretization/Type", type},
               {"Discretization/Degree", std::to_string(degree)},
               {"Discretization/Refinements", std::to_string(refinements)},
               {"Output/Directory", "results"},
               {"Output/Write vtu", "false"},
               {"Output/Print timing", "false"}},
      log);
    return {summary.at("checks").at("l2_error").get<double>(),
            summary.at("checks").at("energy_error").get<double>()};
  }
} // namespace



namespace
{
  /**
   * Observed rate between two levels whose mesh size halves: log2 of the
   * error ratio.
   */
  double
  rate(const double coarse, const double fine)
  {
    return std::log2(coarse / fine);
  }
} // namespace



int
main(int argc, char **argv)
{
  // MUMPS (the direct solver) runs on MPI_COMM_SELF.
  const igabde::base::LightMpiSingleton    light_mpi_singleton;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  deallog << std::fixed << std::setprecision(1);

  // Theory (smooth exact solutions, exact geometry for NURBS, isoparametric
  // geometry of the same degree for FE_Q): the relative L2 error converges
  // as h^(p+1), the energy error as h^p.
  //
  // Criterion, from the asymptotic expansion e(h) = C h^r (1 + c h +
  // O(h^2)): the rate observed between the levels h and h/2 is
  // r_k = r + c h_k / (2 ln 2) + O(h^2), so its distance to r halves with
  // each level and the remaining distance after level k is about
  // r_k - r_{k-1} (a geometric series of ratio 1/2). Both the last observed
  // rate and its extrapolation r_k + (r_k - r_{k-1}) must be within 0.2 of
  // the theoretical rate: a loss of 0.2 is an error ratio 2^0.2 = 1.15 per
  // halving away from optimal, which no pre-asymptotic term of the
  // expansion leaves after the extrapolation, but a lost order (a wrong
  // geometry, quadrature or a singular map, rate p or p - 1/2) cannot meet.
  // Levels: refinements 4, 5, 6, where the change of the rate has dropped
  // below 0.2 for every case below.
  for (const std::string scene : {"v1-plate-with-hole", "v2-lame-cylinder"})
    for (const auto &[type, degree] :
         std::vector<std::pair<std::string, int>>{{"nurbs", 2},
                                                  {"nurbs", 3},
                                                  {"lagrange", 2}})
      {
        std::vector<Level> levels;
        for (unsigned int r = 4; r <= 6; ++r)
          levels.push_back(run(scene, type, degree, r));
        const auto criterion = [&](const double e0,
                                   const double e1,
                                   const double e2,
                                   const double theory) {
          const double last         = rate(e1, e2);
          const double extrapolated = last + (last - rate(e0, e1));
          return std::min(last, extrapolated) >= theory - 0.2;
        };
        const bool l2 =
          criterion(levels[0].l2, levels[1].l2, levels[2].l2, degree + 1);
        const bool energy = criterion(levels[0].energy,
                                      levels[1].energy,
                                      levels[2].energy,
                                      degree);
        deallog << (scene == "v1-plate-with-hole" ? "V1 " : "V2 ") << type
                << " p=" << degree << ": L2 rate >= " << degree + 1 - 0.2
                << ": " << (l2 ? "yes" : "NO")
                << ", energy rate >= " << degree - 0.2 << ": "
                << (energy ? "yes" : "NO") << std::endl;
      }
}
