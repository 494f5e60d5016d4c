// convergence_study: see `usage` below (also printed by --help).

#include <igabde/base/utilities.h>

#include <igabde/scene/simulator.h>

#include <deal.II/base/mpi.h>

#include "option_value.h"
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
  const char *const usage =
    R"(Accuracy against cost for an elasticity scene with an exact solution:
runs the scene over a range of uniform refinements and prints a Markdown
table of DOFs, relative L2 and energy errors, observed rates and wall time
per phase.

Usage: convergence_study SCENE.prm TYPE DEGREE FIRST LAST
  e.g. convergence_study prm/v1-plate-with-hole.prm nurbs 2 1 5
)";
} // namespace

int
main(int argc, char **argv)
{
  igabde::benchmarks::answer_help(argc, argv, usage);
  using igabde::benchmarks::option_value;
  const std::string tool = "convergence_study";
  // MUMPS (the direct solver) runs on MPI_COMM_SELF.
  const igabde::base::LightMpiSingleton    light_mpi_singleton;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using namespace igabde;
  if (argc != 6)
    {
      std::cerr
        << "Usage: convergence_study SCENE.prm TYPE DEGREE FIRST LAST\n";
      return 2;
    }
  const std::string  scene  = argv[1];
  const std::string  type   = argv[2];
  const std::string  degree = argv[3];
  const unsigned int first = option_value<unsigned int>(tool, "FIRST", argv[4]);
  const unsigned int last  = option_value<unsigned int>(tool, "LAST", argv[5]);

  std::cout << "| refinements | elements | DOFs | L2 error | rate | energy "
               "error | rate | setup s | total s |\n"
               "|---|---|---|---|---|---|---|---|---|\n";
  double previous_l2 = 0., previous_energy = 0.;
  for (unsigned int r = first; r <= last; ++r)
    {
      std::ostringstream log;
      const auto         summary = scene::run_scene_in_process(
        scene,
        {{"Discretization/Type", type},
                 {"Discretization/Degree", degree},
                 {"Discretization/Refinements", std::to_string(r)},
                 {"Output/Directory", "output/convergence-study"},
                 {"Output/Write vtu", "false"},
                 {"Output/Print timing", "false"}},
        log);
      const double l2 = summary.at("checks").at("l2_error").get<double>();
      const double energy =
        summary.at("checks").at("energy_error").get<double>();
      std::cout << std::defaultfloat << "| " << r << " | "
                << static_cast<long long>(
                     summary.at("n_elements").get<double>())
                << " | "
                << static_cast<long long>(summary.at("n_dofs").get<double>())
                << " | " << std::scientific << std::setprecision(3) << l2
                << " | " << std::fixed << std::setprecision(2);
      if (r > first)
        std::cout << std::log2(previous_l2 / l2);
      else
        std::cout << "-";
      std::cout << " | " << std::scientific << std::setprecision(3) << energy
                << " | " << std::fixed << std::setprecision(2);
      if (r > first)
        std::cout << std::log2(previous_energy / energy);
      else
        std::cout << "-";
      std::cout << " | " << std::setprecision(3)
                << summary.at("timing").at("assembly").get<double>() +
                     summary.at("timing").at("factorization").get<double>()
                << " | " << summary.at("timing").at("total").get<double>()
                << " |\n";
      previous_l2     = l2;
      previous_energy = energy;
    }
}
