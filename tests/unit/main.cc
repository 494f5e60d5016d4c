// GoogleTest entry point of igabde_unit_tests: MPI (through deal.II) must be
// initialised for the Trilinos-based solvers, with one thread per core for
// the deal.II task scheduler.

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
