// FCLIB problems: reading (local/global HDF5, Siconos .dat), bad files, and
// solving the elastic problems to a relative natural-map error <= 1e-8.
// Skipped (never passed) when the FCLIB data folder is missing.

#include <igabde/contact/bnewton.h>
#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_problem.h>
#include <igabde/contact/fclib_reader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace igabde::contact;

namespace
{
  std::string
  fclib_dir()
  {
    const char *env = std::getenv("IGABDE_FCLIB_DIR");
    return env ? std::string(env) :
                 (std::filesystem::path(IGABDE_SOURCE_DIR) / ".." / "shared" /
                  "fclib" / "data")
                   .string();
  }

  /// The corpus file @p relative (e.g. "hdf5_global/CubeH8.hdf5").
  std::string
  fclib_file(const std::string &relative)
  {
    return (std::filesystem::path(fclib_dir()) / relative).string();
  }

  // The elastic problems the solver targets (research/contact-solvers.md
  // §5.9): Rover, Confeti, the LMGC FEM cubes, CubeH8, FC3D_Example1.
  std::vector<std::string>
  elastic_problems()
  {
    std::vector<std::string> files;
    const std::string        dat = fclib_file("siconos_dat");
    if (std::filesystem::is_directory(dat))
      for (const auto &e : std::filesystem::directory_iterator(dat))
        {
          const std::string name = e.path().filename().string();
          if (name.rfind("Rover", 0) == 0 || name.rfind("Confeti", 0) == 0)
            files.push_back(e.path().string());
        }
    files.push_back(
      fclib_file("hdf5_global/LMGC_GlobalFrictionContactProblem00046.hdf5"));
    files.push_back(fclib_file("hdf5_global/CubeH8.hdf5"));
    files.push_back(fclib_file("siconos_dat/FC3D_Example1.dat"));
    return files;
  }
} // namespace



#define SKIP_WITHOUT_FCLIB()                           \
  if (!std::filesystem::is_directory(fclib_dir()))     \
  GTEST_SKIP() << "FCLIB data folder '" << fclib_dir() \
               << "' not found (set IGABDE_FCLIB_DIR)"



TEST(ContactFclib, ReadersAgree)
{
  SKIP_WITHOUT_FCLIB();
  // The same problem stored dense and sparse-block.
  const ContactProblem dense =
    read_siconos_dat(fclib_file("siconos_dat/FC3D_Example1.dat"));
  const ContactProblem sbm =
    read_siconos_dat(fclib_file("siconos_dat/FC3D_Example1_SBM.dat"));
  EXPECT_EQ(dense.n_contacts, 3u);
  EXPECT_EQ(dense.n_components, 3u);
  EXPECT_EQ((dense.W - sbm.W).norm(), 0.);
  EXPECT_EQ((dense.q - sbm.q).norm(), 0.);
  EXPECT_EQ(dense.mu, sbm.mu);

  // A local HDF5 problem (compressed-row W). Its /solution group holds
  // zeros (a placeholder), so only sizes and finiteness are checked here.
  const std::string local = fclib_file("hdf5_local/Capsules-i97-269.hdf5");
  EXPECT_EQ(classify_fclib_file(local), FclibFileKind::hdf5_local);
  const ContactProblem capsules = read_fclib_problem(local);
  EXPECT_EQ(capsules.n_contacts, 216u);
  EXPECT_EQ(capsules.W.rows(), 648);
  EXPECT_TRUE(capsules.W.allFinite());
  EXPECT_TRUE(read_fclib_solution(local).available);

  // A global problem condensed to W = H^T M^-1 H, q = H^T M^-1 f + w
  // (FCLIB: M v = H r + f, u = H^T v + w). Sign check: boxes stacked under
  // gravity must all be pressed together (with f of the wrong sign every
  // contact would open); the solution is reached in a couple of steps.
  const std::string global =
    fclib_file("hdf5_global/Box_Stacks-i0035-31-0.hdf5");
  EXPECT_EQ(classify_fclib_file(global), FclibFileKind::hdf5_global);
  const ContactProblem boxes = read_fclib_problem(global);
  EXPECT_EQ(boxes.n_contacts, 31u);
  EXPECT_LE((boxes.W - boxes.W.transpose()).norm(), 1e-12 * boxes.W.norm());
  const BNewtonSolver::Result rb = BNewtonSolver().solve(boxes);
  EXPECT_TRUE(rb.converged) << rb.summary();
  EXPECT_EQ(rb.n_open, 0u);
  EXPECT_LE(rb.iterations, 3u);

  EXPECT_EQ(classify_fclib_file(
              fclib_file("hdf5_global/Chute-ndof-768-nc-4-3.hdf5")),
            FclibFileKind::hdf5_global_rolling);
  EXPECT_EQ(classify_fclib_file(fclib_file("siconos_dat/GFC3D_Example1.dat")),
            FclibFileKind::siconos_global_dat);
}



TEST(ContactFclib, BadFilesThrowNamingTheFile)
{
  SKIP_WITHOUT_FCLIB();
  // A folder that does not exist below the scratch folder.
  const std::string missing = (std::filesystem::temp_directory_path() /
                               "igabde-no-such-folder" / "problem.hdf5")
                                .string();
  try
    {
      read_fclib_local(missing);
      ADD_FAILURE() << "no exception for a missing file";
    }
  catch (const std::exception &e)
    {
      EXPECT_NE(std::string(e.what()).find(missing), std::string::npos);
    }
  // A truncated .dat file.
  const std::string truncated =
    (std::filesystem::temp_directory_path() / "igabde_truncated.dat").string();
  {
    std::ofstream out(truncated);
    out << "3\n2\n0\n6\n6\n6\t6\n1 0 0\n";
  }
  try
    {
      read_siconos_dat(truncated);
      ADD_FAILURE() << "no exception for a truncated file";
    }
  catch (const std::exception &e)
    {
      EXPECT_NE(std::string(e.what()).find(truncated), std::string::npos);
    }
  std::filesystem::remove(truncated);
  // A local reader on a global file.
  EXPECT_ANY_THROW(read_fclib_local(fclib_file("hdf5_global/CubeH8.hdf5")));
  // Not a problem at all.
  EXPECT_ANY_THROW(read_fclib_problem(fclib_file("siconos_dat/ACinputs.dat")));
}



TEST(ContactFclib, ElasticProblemsSolve)
{
  SKIP_WITHOUT_FCLIB();
  BNewtonSolver::Settings settings;
  settings.tolerance = 1e-9;
  const BNewtonSolver solver(settings);
  unsigned int        n_solved = 0;
  for (const std::string &file : elastic_problems())
    {
      SCOPED_TRACE(file);
      ASSERT_TRUE(std::filesystem::exists(file)) << file;
      const ContactProblem        problem = read_fclib_problem(file);
      const BNewtonSolver::Result result  = solver.solve(problem);
      EXPECT_TRUE(result.converged) << result.summary();
      EXPECT_LE(result.residual, 1e-8) << result.summary();
      const ConditionReport report =
        check_contact_conditions(problem, result.p, result.u, 1e-6);
      EXPECT_TRUE(report.passed()) << report.first_violation();
      if (file.find("CubeH8") != std::string::npos ||
          file.find("00046") != std::string::npos)
        {
          EXPECT_LE(result.iterations, 3u); // Siconos: 1-2 iterations
          EXPECT_GT(result.p.norm(), 0.);   // the cubes are pressed
        }
      n_solved += result.converged;
    }
  EXPECT_GE(n_solved, 20u);
}



// Rigid capsule heaps whose reduced Newton matrix is singular at every
// iteration: with a fixed Levenberg-Marquardt parameter (1e-10 max diag
// J^T J) the Newton steps lost the directions of the small singular values
// and stalled near a relative natural map of 1e-7 (300 iterations); the
// parameter now shrinks with the residual. Solved means the FCLIB measure
// <= 1e-8, and the post-solve condition check at 1e-6.
TEST(ContactFclib, SingularRigidHeapsReachTheFclibTolerance)
{
  SKIP_WITHOUT_FCLIB();
  const BNewtonSolver solver{BNewtonSolver::Settings()};
  for (const std::string name :
       {"Capsules-i100-1090.dat", "Capsules-i100-889.dat"})
    {
      SCOPED_TRACE(name);
      const ContactProblem problem =
        read_fclib_problem(fclib_file("siconos_dat/" + name));
      const BNewtonSolver::Result result = solver.solve(problem);
      EXPECT_TRUE(result.converged) << result.summary();
      EXPECT_LE(result.residual, 1e-8) << result.summary();
      // The case this test is about: Levenberg-Marquardt steps were taken.
      EXPECT_TRUE(std::any_of(result.history.begin(),
                              result.history.end(),
                              [](const auto &record) {
                                return record.note.find("lm") !=
                                       std::string::npos;
                              }));
      const ConditionReport report =
        check_contact_conditions(problem, result.p, result.u, 1e-6);
      EXPECT_TRUE(report.passed()) << report.describe();
    }
}
