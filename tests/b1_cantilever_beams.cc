// B1 (prm/b1-cantilever-beams.prm, 12 x 2 x 2 per beam, NURBS p = 2) as
// the scene defines it (E = 30e9), solved by the B-Newton on the condensed
// system and by the augmented Lagrangian on the full system. The
// augmented Lagrangian stops on the B-Newton's natural-map test (tolerance
// 1e-10), so both print the same figures to far more than six digits: a
// second method on the same discrete problem. The agreement of NURBS and
// FE_Q(2) within their discretisation errors is
// tests/unit/cli_b1_discretisations_test.cc.
//
// The figures are printed in units that put them above numdiff's absolute
// tolerance of 1e-6, so that its relative one compares them: forces in kN,
// displacements in micrometres (1e-7 m to 1e-5 m at E = 30e9). The scene
// stays inside the model's range (largest strain about 4e-4, slip a small
// fraction of the pair spacing): no warning is expected, and one would
// print.

#include "tests.h"

#include <igabde/base/utilities.h>

#include <igabde/scene/simulator.h>

#include <deal.II/base/mpi.h>

#include <filesystem>
#include <sstream>
#include <string>

using namespace igabde;

int
main(int argc, char **argv)
{
  // MUMPS (the direct solver) runs on MPI_COMM_SELF.
  const igabde::base::LightMpiSingleton    light_mpi_singleton;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  const std::string scene = (std::filesystem::path(SOURCE_DIR) / ".." / "prm" /
                             "b1-cantilever-beams.prm")
                              .string();
  for (const std::string algorithm : {"bde", "augmented-lagrange"})
    {
      std::ostringstream   log;
      const nlohmann::json summary =
        scene::run_scene_in_process(scene,
                                    {{"Contact/Algorithm", algorithm},
                                     {"Output/Directory",
                                      "output-" + algorithm},
                                     {"Output/Write vtu", "false"},
                                     {"Output/Print timing", "false"}},
                                    log);
      deallog << "B1, " << algorithm << ": status "
              << summary.at("status").get<std::string>() << ", "
              << summary.at("n_contact_pairs").get<unsigned int>() << " pairs"
              << std::endl;
      if (summary.contains("warnings"))
        for (const auto &w : summary.at("warnings"))
          deallog << "  warning: "
                  << (w.is_string() ? w.get<std::string>() : w.dump())
                  << std::endl;
      deallog << "  total contact force on Body 1 (kN):";
      for (const auto &f :
           summary.at("load_steps").back().at("total_contact_force"))
        deallog << ' ' << f.get<double>() / 1e3;
      deallog << std::endl;
      for (const std::string probe : {"A", "C"})
        {
          deallog << "  probe " << probe << ": displacement (um):";
          for (const auto &u : summary.at("points").at(probe))
            deallog << ' ' << u.get<double>() * 1e6;
          deallog << std::endl;
        }
    }
}
