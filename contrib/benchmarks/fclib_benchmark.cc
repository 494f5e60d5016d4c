// fclib_benchmark: see `usage` below (also printed by --help).

#include <igabde/contact/bnewton.h>
#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_problem.h>
#include <igabde/contact/fclib_reader.h>

#include "option_value.h"
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

namespace
{
  const char *const usage =
    R"(Runs igabde's damped B-Newton contact solver on every local/global 2D and
3D FCLIB / Siconos problem found under a folder and prints a table.

Usage: fclib_benchmark [--only TEXT] [--log] [--repeat N] [folder]
                       [max_iterations] [seconds_per_problem] [max_rows]
  --only TEXT          run only the problems whose file name contains TEXT
  --log                print the solver's iterations
  --repeat N           solve each problem N times, the fastest counting
                       (default 1: the first solve in a process pays
                       start-up costs; repeat to time small problems or
                       to profile one)
  folder               default $IGABDE_FCLIB_DIR, else
                       ../shared/fclib/data (run from the repository root)
  max_iterations       iteration budget per problem (default 300)
  seconds_per_problem  wall-time limit per solve (default 60)
  max_rows             larger problems (rows of the dense W) are skipped
                       (default 6000)

"solved" means the FCLIB relative natural-map error |p - P_K(p - u_hat)|
/ |q| is <= 1e-8 (the measure of research/contact-solvers.md §4).
)";
} // namespace

using namespace igabde::contact;

int
main(int argc, char **argv)
{
  igabde::benchmarks::answer_help(argc, argv, usage);
  using igabde::benchmarks::option_value;
  const std::string tool   = "fclib_benchmark";
  std::string       folder = "../shared/fclib/data";
  if (const char *env = std::getenv("IGABDE_FCLIB_DIR"))
    folder = env;
  std::string              only;
  bool                     log    = false;
  unsigned int             repeat = 1;
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i)
    {
      const std::string a = argv[i];
      if (a == "--only" && i + 1 < argc)
        only = argv[++i];
      else if (a == "--log")
        log = true;
      else if (a == "--repeat" && i + 1 < argc)
        repeat = std::max(1, option_value<int>(tool, a, argv[++i]));
      else
        args.push_back(a);
    }
  if (args.size() > 0)
    folder = args[0];
  const unsigned int max_iterations =
    args.size() > 1 ?
      option_value<unsigned int>(tool, "max_iterations", args[1]) :
      300;
  const double seconds =
    args.size() > 2 ?
      option_value<double>(tool, "seconds_per_problem", args[2]) :
      60.;
  const long max_rows =
    args.size() > 3 ? option_value<long>(tool, "max_rows", args[3]) : 6000;

  if (!std::filesystem::is_directory(folder))
    {
      std::cerr << "fclib_benchmark: no folder '" << folder << "'\n";
      return 1;
    }
  std::vector<std::filesystem::path> files;
  for (const auto &entry :
       std::filesystem::recursive_directory_iterator(folder))
    if (entry.is_regular_file())
      files.push_back(entry.path());
  std::sort(files.begin(), files.end(), [](const auto &a, const auto &b) {
    return a.filename().string() < b.filename().string();
  });

  BNewtonSolver::Settings settings;
  settings.tolerance        = 1e-8;
  settings.fclib_stopping   = true;
  settings.max_iterations   = max_iterations;
  settings.max_wall_seconds = seconds;
  settings.log              = log;
  const BNewtonSolver solver(settings);

  std::cout << "| problem | d | nc | mu | it | rel. natural map | balanced | "
               "solved | checks | ms | diagnosis |\n"
            << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  unsigned int solved[4] = {0, 0, 0, 0}, attempted[4] = {0, 0, 0, 0};
  std::vector<std::string> skipped;
  for (const auto &path : files)
    {
      const std::string name = path.filename().string();
      if (!only.empty() && name.find(only) == std::string::npos)
        continue;
      const FclibFileKind kind = classify_fclib_file(path.string());
      if (kind == FclibFileKind::unknown ||
          kind == FclibFileKind::hdf5_global_rolling)
        {
          skipped.push_back(name + " (not a local/global FCLIB problem)");
          continue;
        }
      ContactProblem problem;
      try
        {
          problem = read_fclib_problem(path.string());
        }
      catch (const std::exception &e)
        {
          std::string what = e.what();
          const auto  pos  = what.find("FCLIB reader");
          const auto  pos2 = what.find("Siconos reader");
          what             = what.substr(
            std::min(pos, pos2) == std::string::npos ? 0 : std::min(pos, pos2));
          what = what.substr(0, what.find('\n'));
          skipped.push_back(name + " (unreadable: " + what + ")");
          continue;
        }
      if (problem.n_components < 2)
        {
          skipped.push_back(name + " (frictionless, not an FCLIB case)");
          continue;
        }
      if (static_cast<long>(problem.n_rows()) > max_rows)
        {
          skipped.push_back(name + " (" + std::to_string(problem.n_rows()) +
                            " rows > " + std::to_string(max_rows) +
                            ", dense W too large)");
          continue;
        }
      BNewtonSolver::Result r;
      double                ms = 0.;
      for (unsigned int k = 0; k < repeat; ++k)
        {
          const auto t0  = std::chrono::steady_clock::now();
          r              = solver.solve(problem);
          const double t = std::chrono::duration<double, std::milli>(
                             std::chrono::steady_clock::now() - t0)
                             .count();
          ms = k == 0 ? t : std::min(ms, t);
        }
      const bool ok = r.residual <= 1e-8 && r.p.allFinite();
      const bool checks =
        check_contact_conditions(problem, r.p, r.u, 1e-6).passed();
      const unsigned int d = problem.n_components;
      ++attempted[d];
      if (ok)
        ++solved[d];
      double mu_min = problem.mu.empty() ? 0. : problem.mu[0], mu_max = mu_min;
      for (const double mu : problem.mu)
        {
          mu_min = std::min(mu_min, mu);
          mu_max = std::max(mu_max, mu);
        }
      std::string diagnosis = r.converged ? "" : r.diagnosis;
      if (diagnosis.size() > 80)
        diagnosis = diagnosis.substr(0, 77) + "...";
      std::cout << "| " << name << " | " << d << " | " << problem.n_contacts
                << " | " << std::setprecision(3) << mu_min;
      if (mu_max > mu_min)
        std::cout << "-" << mu_max;
      std::cout << " | " << r.iterations;
      if (r.sweeps > 0)
        std::cout << " + " << r.sweeps << " sweeps";
      std::cout << " | " << std::scientific << std::setprecision(1)
                << r.residual << " | " << r.balanced_residual << " | "
                << (ok ? "yes" : "no") << " | " << (checks ? "pass" : "FAIL")
                << " | " << std::fixed << std::setprecision(ms < 10. ? 3 : 1)
                << ms << " | " << diagnosis << " |" << std::defaultfloat
                << std::endl;
    }
  std::cout << "\nsolved (relative natural map <= 1e-8): 3D " << solved[3]
            << "/" << attempted[3] << ", 2D " << solved[2] << "/"
            << attempted[2] << '\n';
  std::cout << "skipped:\n";
  for (const std::string &s : skipped)
    std::cout << "  " << s << '\n';
  return 0;
}
