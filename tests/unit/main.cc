// GoogleTest entry point of igabde_unit_tests: MPI (through deal.II) must be
// initialised for the Trilinos-based solvers, with one thread per core for
// the deal.II task scheduler.

#include <igabde/base/utilities.h>

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#ifdef IGABDE_SANITIZE
// OpenMPI's dynamically loaded components leak at MPI_Finalize from frames
// LeakSanitizer cannot name (unloaded modules), so no suppression file can
// match them: leak checking is off in sanitizer builds; AddressSanitizer's
// memory-error checks and UBSan stay on.
extern "C" const char *
__asan_default_options()
{
  return "detect_leaks=0";
}
#endif



int
main(int argc, char **argv)
{
  const igabde::base::LightMpiSingleton    light_mpi_singleton;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
