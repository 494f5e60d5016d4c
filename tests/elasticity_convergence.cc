// Convergence of the elasticity paths on V1 (plate with a hole, Kirsch) and
// V2 (Lame cylinder): observed L2 and energy rates over the last levels,
// NURBS p = 2, 3 and FE_Q(2), and the NURBS-vs-FE_Q(2) error at equal DOFs.

#include "tests.h"

#include <igabde/scene/simulator.h>

#include <deal.II/base/mpi.h>

#include <cmath>
#include <iomanip>
#include <sstream>

using namespace igabde;

namespace
{
  struct Level
  {
    double dofs, l2, energy;
  };

  Level
  run(const std::string &scene,
      const std::string &type,
      const unsigned int degree,
      const unsigned int refinements)
  {
    std::ostringstream log;
    const auto         summary = scene::run_scene_in_process(
      std::string(SOURCE_DIR) + "/../prm/" + scene + ".prm",
      {{"Discretization/Type", type},
               {"Discretization/Degree", std::to_string(degree)},
               {"Discretization/Refinements", std::to_string(refinements)},
               {"Output/Directory", "results"},
               {"Output/Write vtu", "false"},
               {"Output/Print timing", "false"}},
      log);
    return {summary.at("n_dofs").get<double>(),
            summary.at("checks").at("l2_error").get<double>(),
            summary.at("checks").at("energy_error").get<double>()};
  }
} // namespace



int
main(int argc, char **argv)
{
  // MUMPS (the direct solver) runs on MPI_COMM_SELF.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();
  deallog << std::fixed << std::setprecision(1);

  // V1: five levels (refinements 1..5 of the classical two-element mesh);
  // the observed rate over the last three levels is the mean slope
  // log2(e_3 / e_5) / 2 (h halves per level). Criteria: L2 >= p + 0.8,
  // energy >= p - 0.2.
  for (const auto &[type, degree] :
       std::vector<std::pair<std::string, int>>{{"nurbs", 2},
                                                {"nurbs", 3},
                                                {"lagrange", 2}})
    {
      std::vector<Level> levels;
      for (unsigned int r = 1; r <= 5; ++r)
        levels.push_back(run("v1-plate-with-hole", type, degree, r));
      const double l2_rate = std::log2(levels[2].l2 / levels[4].l2) / 2.;
      const double en_rate =
        std::log2(levels[2].energy / levels[4].energy) / 2.;
      deallog << "V1 " << type << " p=" << degree
              << ": L2 rate >= " << degree + 0.8 << ": "
              << (l2_rate >= degree + 0.8 ? "yes" : "NO")
              << ", energy rate >= " << degree - 0.2 << ": "
              << (en_rate >= degree - 0.2 ? "yes" : "NO") << std::endl;
    }

  // V2: on the same mesh the NURBS space has fewer unknowns and smaller
  // errors than FE_Q(2), so its error is below FE_Q(2)'s at equal DOFs.
  for (unsigned int r = 1; r <= 3; ++r)
    {
      const Level nurbs    = run("v2-lame-cylinder", "nurbs", 2, r);
      const Level lagrange = run("v2-lame-cylinder", "lagrange", 2, r);
      deallog << "V2 level " << r << ": NURBS dofs <= FE_Q(2) dofs: "
              << (nurbs.dofs <= lagrange.dofs ? "yes" : "NO")
              << ", NURBS L2 and energy errors below FE_Q(2)'s: "
              << (nurbs.l2 < lagrange.l2 && nurbs.energy < lagrange.energy ?
                    "yes" :
                    "NO")
              << std::endl;
    }
}
