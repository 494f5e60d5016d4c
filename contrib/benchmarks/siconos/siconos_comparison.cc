// siconos_comparison: see `usage` below (also printed by --help).

#include <igabde/contact/bnewton.h>
#include <igabde/contact/contact_law.h>
#include <igabde/contact/contact_operator.h>
#include <igabde/contact/contact_problem.h>
#include <igabde/contact/fclib_reader.h>

#include <deal.II/base/mpi.h>

#include <Eigen/Eigenvalues>

#include "../option_value.h"
#include "protocol.h"
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <siconos/numerics/Friction_cst.h>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>
#include <vector>

namespace
{
  const char *const usage =
    R"(igabde's B-Newton beside Siconos' FCLIB solvers, in one run,
on every local/global 2D and 3D problem under a folder (FCLIB HDF5 and
Siconos numerics .dat), every answer judged by the same measure.

Usage: siconos_comparison [--only TEXT] [--max-rows N] [--max-iterations N]
                          [--w-prepared] [folder]
  folder            default $IGABDE_FCLIB_DIR, else ../shared/fclib/data
  --only TEXT       only the problems whose file name contains TEXT
  --max-rows N      larger problems (rows of the condensed W) are left
                    out (default 6000: our dense W)
  --max-iterations  Siconos' iteration budget (default 1000 for the
                    Newton and proximal solvers, 10 times that for NSGS)
  --w-prepared      igabde's time leaves out the preparation of its W
                    (the operator over the dense W, W's structure: its
                    sparse copy and symmetry), as Siconos' time leaves
                    out the conversion to its sparse-block storage;
                    without it igabde's time includes them
  --verify FILE [--agree TOL]   (in any order)
                    instead of the table: hand the FCLIB local problem
                    FILE (e.g. a scene's Output/FCLIB export) to Siconos
                    (3D: PROX, NSN-AC, NSGS and ADMM; 2D: Lemke's
                    pivoting method and NSGS) at internal tolerance 1e-14 and compare their
                    forces with the solution stored in the file; exit
                    status 0 ("same answer") if the first of them to meet
                    FCLIB's measure at 1e-8 lies within TOL of the stored
                    one (relative), or without --agree within the distance
                    the two answers' FCLIB errors allow (the natural-map
                    error bound; where W is only semidefinite, if both
                    meet 1e-8); 1 ("DIFFERENT answer") if not, or if the
                    stored solution does not meet 1e-8. A file that stores
                    no solution, or zeros (the FCLIB collection's
                    placeholders), has igabde's B-Newton answer judged
                    instead; 3 ("no verdict")
                    when no Siconos solver meets 1e-8 (those after the
                    first that does are not run), naming them; 4 for a
                    problem that is not a Coulomb friction problem
                    (rolling friction); 2 for bad input; ctests with scenes from prm/ and the
                    FCLIB problems

Each problem is read once, by igabde's reader (a global problem condensed
through its sparse M, W = H^T M^-1 H), and handed to both: igabde's
B-Newton works on the dense W, Siconos' solvers on the same W in their
sparse-block storage (blocks of the contact's size, exact zeros left
out), the storage they are written for. (Debian's Siconos is built
without FCLIB, so it cannot read the HDF5 files itself.) Each Siconos
solve runs in a process of its own, siconos_solver beside this program,
which links Siconos and its sequential MUMPS only: in one process with
igabde's MPI MUMPS a single dmumps_c would serve both, and Siconos'
sparse solvers would reach the MPI build. Every answer r
is judged on that problem by FCLIB's relative natural-map error
|r - P_K(r - (W r + q + mu |u_t| e_n))| / |q| (not by Siconos' own
measure, which divides by max(|q|, |r|, |u|)); "solved" is an error
<= 1e-8. Siconos' internal tolerance starts at 1e-8 and is tightened
(1e-10, 1e-12, 1e-14) until its answer passes or its solver stops
converging; the time is that of the run whose answer is reported. Times
are the solve alone (reading and conversion excluded), milliseconds, the
fastest of repeated runs (at least two for a solve under a second, more
while they take under 20 ms together: see run_again()), for both sides
alike. igabde stops as soon as the FCLIB error passes
(BNewtonSettings::fclib_stopping), as Siconos does.
)";
} // namespace


using namespace igabde::contact;

namespace
{
  using Clock = std::chrono::steady_clock;

  double
  milliseconds_since(const Clock::time_point start)
  {
    return std::chrono::duration<double, std::milli>(Clock::now() - start)
      .count();
  }

  using siconos_protocol::run_again;

  struct Outcome
  {
    bool   ran        = false;
    double error      = 1.;
    double ms         = 0.;
    int    iterations = 0;
    /// igabde's Gauss-Seidel sweeps (not counted in iterations).
    int         sweeps    = 0;
    double      tolerance = 0.;
    std::string note;
  };

  /// FCLIB's measure of @p r on igabde's copy of the problem.
  double
  fclib_error(const ContactProblem &problem, const Eigen::VectorXd &r)
  {
    if (!r.allFinite())
      return 1.;
    return relative_natural_map_error(problem,
                                      r,
                                      problem.relative_displacement(r));
  }

  long
  W_nonzeros(const Eigen::MatrixXd &W)
  {
    return std::max<long>(1, (W.array() != 0.).count());
  }

  /// The problem as siconos_solver reads it: W's nonzero entries, q, mu.
  siconos_protocol::Problem
  protocol_problem(const ContactProblem &problem)
  {
    siconos_protocol::Problem p;
    p.dimension   = problem.n_components;
    p.contacts    = problem.n_contacts;
    const int  n  = problem.n_rows();
    const long nz = W_nonzeros(problem.W);
    p.rows.reserve(nz);
    p.columns.reserve(nz);
    p.values.reserve(nz);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (problem.W(i, j) != 0.)
          {
            p.rows.push_back(i);
            p.columns.push_back(j);
            p.values.push_back(problem.W(i, j));
          }
    p.q.assign(problem.q.data(), problem.q.data() + n);
    p.mu.assign(problem.mu.begin(), problem.mu.end());
    return p;
  }

  /// A scratch folder, removed with this object, holding the problem file
  /// and the solver's reports; the solver runs in it too (Siconos' MUMPS
  /// calls leave empty Fortran unit files, fort.N, in the working folder).
  struct Scratch
  {
    std::string path;

    Scratch()
    {
      path =
        (std::filesystem::temp_directory_path() / "siconos-XXXXXX").string();
      if (mkdtemp(path.data()) == nullptr)
        throw std::runtime_error(
          "siconos_comparison: no scratch folder in " +
          std::filesystem::temp_directory_path().string());
    }

    ~Scratch()
    {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }

    std::string
    file(const std::string &name) const
    {
      return (std::filesystem::path(path) / name).string();
    }
  };

  /// siconos_solver, beside this program.
  std::string
  solver_program()
  {
    return (std::filesystem::read_symlink("/proc/self/exe").parent_path() /
            "siconos_solver")
      .string();
  }

  /**
   * One Siconos solve at @p tolerance of the problem in @p scratch
   * (problem.bin), by siconos_solver in a child process with at most 8 GiB
   * of address space and 120 s: some solvers exhaust the memory on some
   * problems (NSN-AC on RockPile_tob1 took 24 GB) or abort, and the table
   * must go on. Returns false, with the reason in @p why, if the child did
   * not report.
   */
  bool
  solve_isolated(const Scratch            &scratch,
                 const int                 solver_id,
                 const int                 max_iterations,
                 const double              tolerance,
                 const bool                dense,
                 const bool                once,
                 siconos_protocol::Report &report,
                 std::string              &why)
  {
    const std::string program = solver_program(),
                      problem = scratch.file("problem.bin"),
                      answer  = scratch.file("report.bin");
    std::filesystem::remove(answer);
    std::ostringstream tolerance_text;
    tolerance_text << std::setprecision(17) << tolerance;
    std::vector<std::string> args = {program,
                                     problem,
                                     answer,
                                     std::to_string(solver_id),
                                     tolerance_text.str(),
                                     std::to_string(max_iterations)};
    if (dense)
      args.push_back("--dense");
    if (once)
      args.push_back("--once");
    std::vector<char *> argv;
    for (auto &a : args)
      argv.push_back(a.data());
    argv.push_back(nullptr);
    std::cout.flush();
    const pid_t child = fork();
    if (child == 0)
      {
        if (chdir(scratch.path.c_str()) != 0)
          _exit(126);
        // Its output (Siconos' and MUMPS' messages) to a file, whose last
        // line names a failure.
        if (freopen("solver.log", "w", stdout) == nullptr ||
            dup2(fileno(stdout), 2) < 0)
          _exit(126);
        const rlimit memory = {8ul << 30, 8ul << 30};
        setrlimit(RLIMIT_AS, &memory);
        alarm(120);
        execv(program.c_str(), argv.data());
        _exit(127);
      }
    int status = 0;
    if (child > 0)
      waitpid(child, &status, 0);
    // The last line the solver printed, if any.
    std::string last_line;
    {
      std::ifstream log(scratch.file("solver.log"));
      for (std::string line; std::getline(log, line);)
        if (line.find_first_not_of(" \t*") != std::string::npos)
          last_line = line.substr(line.find_first_not_of(" \t"));
    }
    if (child > 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0 &&
        std::filesystem::exists(answer))
      try
        {
          report = siconos_protocol::read_report(answer);
          return true;
        }
      catch (const std::exception &e)
        {
          why = e.what();
          return false;
        }
    if (child > 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0)
      {
        why =
          "ended without an answer" +
          (last_line.empty() ? std::string() : ", after \"" + last_line + "\"");
        return false;
      }
    why = child <= 0 ?
            "no child process" :
          WIFSIGNALED(status) ?
            (WTERMSIG(status) == SIGALRM ? "time limit (120 s)" :
             WTERMSIG(status) == SIGABRT ? "aborted (memory?)" :
                                           "killed by signal " +
                                             std::to_string(WTERMSIG(status))) :
          WEXITSTATUS(status) == 127 ?
            "cannot run " + program :
            "siconos_solver exit status " + std::to_string(WEXITSTATUS(status));
    return false;
  }

  /// One Siconos solver on the problem in @p scratch, its tolerance
  /// tightened until our
  /// measure passes.
  Outcome
  run_siconos(const Scratch        &scratch,
              const ContactProblem &problem,
              const int             solver_id,
              const int             max_iterations,
              const bool            dense = false)
  {
    Outcome best;
    for (const double tolerance : {1e-8, 1e-10, 1e-12, 1e-14})
      {
        siconos_protocol::Report report;
        std::string              why;
        if (!solve_isolated(scratch,
                            solver_id,
                            max_iterations,
                            tolerance,
                            dense,
                            false,
                            report,
                            why))
          {
            if (!best.ran)
              {
                best.ran  = true;
                best.note = why;
              }
            break;
          }
        Outcome outcome;
        outcome.ran        = true;
        outcome.ms         = report.ms;
        outcome.iterations = report.iterations;
        outcome.tolerance  = tolerance;
        outcome.error =
          report.r.size() == static_cast<std::size_t>(problem.n_rows()) ?
            fclib_error(problem,
                        Eigen::Map<const Eigen::VectorXd>(report.r.data(),
                                                          problem.n_rows())) :
            1.;
        outcome.note =
          report.info == 0 ? "" : "info " + std::to_string(report.info);
        if (!best.ran || !best.note.empty() || outcome.error < best.error)
          best = outcome;
        // Passed, or the solver no longer claims convergence.
        if (outcome.error <= 1e-8 || report.info != 0)
          break;
      }
    return best;
  }

  std::string
  cell(const Outcome &o)
  {
    if (!o.ran)
      return "— | — | —";
    if (o.iterations == 0 && o.ms == 0. && !o.note.empty())
      return "no: " + o.note + " | — | —";
    std::ostringstream s;
    s << (o.error <= 1e-8 ? "yes" : "no") << " (" << std::scientific
      << std::setprecision(0) << o.error << ") | " << o.iterations;
    if (o.sweeps > 0)
      s << " + " << o.sweeps << " sweeps";
    s << " | " << std::fixed
      << std::setprecision(o.ms < 0.01 ? 5 :
                           o.ms < 0.1  ? 4 :
                           o.ms < 10   ? 2 :
                                         0)
      << o.ms;
    return s.str();
  }
} // namespace



namespace
{
  /// --verify: Siconos on a problem whose solution the file stores.
  int
  verify(const std::string &file, const double agreement)
  {
    const FclibFileKind kind = classify_fclib_file(file);
    if (kind == FclibFileKind::hdf5_global_rolling)
      {
        std::cout << "left out: " << file
                  << " is a rolling-friction problem, not a Coulomb "
                     "friction problem (neither igabde nor Siconos' fc3d "
                     "solvers take it): no verdict to give\n";
        return 4;
      }
    if (kind != FclibFileKind::hdf5_local && kind != FclibFileKind::hdf5_global)
      {
        std::cerr << "siconos_comparison: " << file
                  << " is not an FCLIB problem file (HDF5 with fclib_local "
                     "or fclib_global)\n";
        return 2;
      }
    const ContactProblem problem   = read_fclib_problem(file);
    FclibSolution        reference = read_fclib_solution(file);
    // The answer judged: the file's stored solution, or where it stores
    // none (the FCLIB collection's problems), igabde's B-Newton answer.
    std::string judged = "the stored solution";
    // Many files of the FCLIB collection store zeros in /solution, a
    // placeholder (doc/contact-solver.md): no answer to judge either.
    const bool placeholder = reference.available &&
                             reference.r.size() == problem.n_rows() &&
                             reference.r.lpNorm<Eigen::Infinity>() == 0. &&
                             problem.q.lpNorm<Eigen::Infinity>() > 0.;
    if (placeholder)
      std::cout << file << " stores zeros as its solution (a placeholder)\n";
    if (!reference.available || reference.r.size() != problem.n_rows() ||
        placeholder)
      {
        BNewtonSolver::Settings settings;
        settings.tolerance      = 1e-10;
        settings.max_iterations = 300;
        reference.r             = BNewtonSolver(settings).solve(problem).p;
        reference.available     = true;
        judged                  = "igabde's B-Newton answer";
        std::cout << file << (placeholder ? "" : " stores no solution")
                  << ": igabde's B-Newton answer (FCLIB error "
                  << std::scientific << std::setprecision(2)
                  << fclib_error(problem, reference.r) << std::defaultfloat
                  << ") is judged instead\n";
      }
    const Scratch scratch;
    siconos_protocol::write(scratch.file("problem.bin"),
                            protocol_problem(problem));
    const int n = problem.n_rows();
    // How far two answers may lie apart given their FCLIB errors: for a
    // strongly monotone problem the natural map bounds the distance to the
    // solution, |r - r*| <= (1 + lambda_max) / lambda_min |F_nat(r)|
    // (lambda of the symmetric part of W), and |F_nat(r)| is the FCLIB error
    // times |q|. (With friction the problem is not monotone; the bound is
    // then an estimate, exact in the frictionless limit.)
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(
      0.5 * (problem.W + problem.W.transpose()),
      Eigen::EigenvaluesOnly);
    const double lambda_min      = eigen.eigenvalues().minCoeff(),
                 lambda_max      = eigen.eigenvalues().maxCoeff();
    const double reference_error = fclib_error(problem, reference.r);
    const double amplification   = (1. + lambda_max) / lambda_min *
                                 problem.q.norm() /
                                 std::max(reference.r.norm(), 1e-300);
    std::cout << judged << ": FCLIB error " << std::scientific
              << std::setprecision(2) << reference_error;
    if (lambda_min > 1e-12 * std::abs(lambda_max))
      std::cout << "; |r - r*| / |r| <= " << amplification
                << " x (the FCLIB error)";
    else
      std::cout << "; W is not positive definite (smallest eigenvalue "
                << lambda_min << ")";
    std::cout << std::defaultfloat << '\n';
    // 3D: PROX (judged), NSN-AC, NSGS (Gauss-Seidel over the contacts, no
    // sparse factorisation) and ADMM on the sparse-block storage; 2D:
    // Lemke's pivoting method on the equivalent LCP (judged: exact up to
    // round-off where it ends) and NSGS, both on a dense copy (Siconos'
    // 2D solvers other than NSGS take dense storage only).
    const bool three = problem.n_components == 3;
    const std::vector<std::pair<int, const char *>> solvers =
      three ?
        std::vector<std::pair<int, const char *>>{
          {SICONOS_FRICTION_3D_PROX, "PROX"},
          {SICONOS_FRICTION_3D_NSN_AC, "NSN-AC"},
          {SICONOS_FRICTION_3D_NSGS, "NSGS"},
          {SICONOS_FRICTION_3D_ADMM, "ADMM"}} :
        std::vector<std::pair<int, const char *>>{
          {SICONOS_FRICTION_2D_LEMKE, "Lemke"},
          {SICONOS_FRICTION_2D_NSGS, "NSGS"}};
    // The first solver that meets FCLIB's measure at 1e-8 judges; one that
    // does not is named, and if none does there is no verdict.
    std::string judge, failures;
    double      judged_difference = 0., judged_error = 0.;
    for (const auto &[id, label] : solvers)
      {
        siconos_protocol::Report report;
        std::string              why;
        if (!solve_isolated(scratch,
                            id,
                            10000,
                            1e-14,
                            !three,
                            true,
                            report,
                            why) ||
            report.r.size() != static_cast<std::size_t>(n))
          {
            std::cout << label << ": no answer (" << why << ")\n";
            failures += (failures.empty() ? "" : ", ") + std::string(label) +
                        " (no answer: " + why + ")";
            continue;
          }
        const int                               info = report.info;
        const Eigen::Map<const Eigen::VectorXd> rs(report.r.data(), n);
        const double error = fclib_error(problem, rs);
        // Relative to the larger of the two (a stored answer may be zero).
        const double difference =
          (rs - reference.r).norm() /
          std::max({reference.r.norm(), rs.norm(), 1e-300});
        std::cout << label << ": info " << info << ", FCLIB error "
                  << std::scientific << std::setprecision(2) << error
                  << ", |r - r_file| / max(|r|, |r_file|) " << difference
                  << std::defaultfloat << '\n';
        if (error > 1e-8)
          {
            std::ostringstream why;
            why << label << " (info " << info << ", FCLIB error "
                << std::scientific << std::setprecision(2) << error << ")";
            failures += (failures.empty() ? "" : ", ") + why.str();
          }
        else
          {
            // The first that solves it judges; the rest are not run.
            judge             = label;
            judged_difference = difference;
            judged_error      = error;
            break;
          }
      }

    // The verdict on the stored solution, by the judge's answer.
    const bool definite = lambda_min > 1e-12 * std::abs(lambda_max);
    // An answer that does not meet FCLIB's measure is not a solution,
    // whatever Siconos reaches.
    if (judge.empty() && reference_error > 1e-8)
      {
        std::cout << std::scientific << std::setprecision(2)
                  << "DIFFERENT answer: " << judged
                  << " does not solve the problem (FCLIB error "
                  << reference_error
                  << " > 1e-8); no Siconos solver solved it either: "
                  << failures << '\n';
        return 1;
      }
    if (judge.empty())
      {
        std::cout << "no verdict: no Siconos solver solved the problem to "
                     "FCLIB's 1e-8: "
                  << failures << '\n';
        return 3;
      }
    if (!failures.empty())
      std::cout << "not solved to 1e-8 by " << failures << '\n';
    std::cout << std::scientific << std::setprecision(2);
    if (reference_error > 1e-8)
      {
        std::cout << "DIFFERENT answer: " << judged
                  << " does not solve the problem (FCLIB error "
                  << reference_error << " > 1e-8); " << judge
                  << " does (FCLIB error " << judged_error << ")\n";
        return 1;
      }
    if (agreement > 0.)
      {
        const bool same = judged_difference <= agreement;
        std::cout << (same ? "same answer" : "DIFFERENT answer") << ": "
                  << judge << " and " << judged << " differ by "
                  << judged_difference << (same ? " <= " : " > ") << agreement
                  << " (--agree)\n";
        return same ? 0 : 1;
      }
    if (!definite)
      {
        // W only semidefinite: the solution need not be unique, and the
        // natural map bounds no distance; both answers solve the problem.
        std::cout << "same answer: " << judge << " and " << judged
                  << " both solve the problem "
                     "(FCLIB errors "
                  << judged_error << " and " << reference_error
                  << "); W is not positive definite (smallest eigenvalue "
                  << lambda_min
                  << "), so the solution need not be unique "
                     "(they differ by "
                  << judged_difference << ")\n";
        return 0;
      }
    const double bound = amplification * (judged_error + reference_error);
    const bool   same  = judged_difference <= bound;
    std::cout << (same ? "same answer" : "DIFFERENT answer") << ": " << judge
              << " and " << judged << " differ by " << judged_difference
              << (same ? " <= " : " > ") << bound
              << ", the distance their FCLIB errors allow\n";
    return same ? 0 : 1;
  }
} // namespace



int
main(int argc, char **argv)
{
  igabde::benchmarks::answer_help(argc, argv, usage);
  // igabde's library starts MPI for its MUMPS; Siconos' solves run in
  // siconos_solver processes of their own.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using igabde::benchmarks::option_value;
  const std::string tool   = "siconos_comparison";
  std::string       folder = "../shared/fclib/data";
  if (const char *env = std::getenv("IGABDE_FCLIB_DIR"))
    folder = env;
  std::string only, verify_file;
  long        max_rows       = 6000;
  int         max_iterations = 1000;
  double      agreement      = 0.;
  bool        w_prepared     = false;
  for (int i = 1; i < argc; ++i)
    {
      const std::string a = argv[i];
      if (a == "--only" && i + 1 < argc)
        only = argv[++i];
      else if (a == "--max-rows" && i + 1 < argc)
        max_rows = option_value<long>(tool, a, argv[++i]);
      else if (a == "--max-iterations" && i + 1 < argc)
        max_iterations = option_value<int>(tool, a, argv[++i]);
      else if (a == "--w-prepared")
        w_prepared = true;
      else if (a == "--verify" && i + 1 < argc)
        verify_file = argv[++i];
      else if (a == "--agree" && i + 1 < argc)
        agreement = option_value<double>(tool, a, argv[++i]);
      else if (a.rfind("--", 0) == 0)
        {
          std::cerr << "siconos_comparison: unknown option or missing value: "
                    << a << " (see --help)\n";
          return 2;
        }
      else
        folder = a;
    }
  if (agreement != 0. && verify_file.empty())
    {
      std::cerr << "siconos_comparison: --agree needs --verify FILE\n";
      return 2;
    }
  if (!verify_file.empty())
    return verify(verify_file, agreement);
  if (!std::filesystem::is_directory(folder))
    {
      std::cerr << "siconos_comparison: no folder '" << folder << "'\n";
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
  settings.tolerance      = 1e-8;
  settings.fclib_stopping = true;
  settings.max_iterations = 300;
  const BNewtonSolver solver(settings);

  std::cout << "| problem | d | nc | igabde B-Newton: solved (error) | it | "
               "ms | Siconos NSN-AC | it | ms | Siconos NSGS | it | ms | "
               "Siconos PROX | it | ms |\n"
            << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
               "---|\n";
  unsigned int             solved[4] = {0, 0, 0, 0}, attempted = 0;
  unsigned int             both_solve = 0, fastest = 0, within_two = 0;
  std::vector<std::string> skipped;
  for (const auto &path : files)
    {
      const std::string name = path.filename().string();
      if (!only.empty() && name.find(only) == std::string::npos)
        continue;
      const FclibFileKind kind = classify_fclib_file(path.string());
      if (kind != FclibFileKind::hdf5_local &&
          kind != FclibFileKind::hdf5_global &&
          kind != FclibFileKind::siconos_local_dat &&
          kind != FclibFileKind::siconos_global_dat)
        {
          skipped.push_back(name + " (not a local/global Coulomb problem)");
          continue;
        }
      ContactProblem problem;
      try
        {
          problem = read_fclib_problem(path.string());
        }
      catch (const std::exception &)
        {
          skipped.push_back(name + " (unreadable by igabde)");
          continue;
        }
      if (problem.n_contacts == 0)
        {
          skipped.push_back(name + " (no contacts: nothing to solve)");
          continue;
        }
      if (problem.n_components < 2 ||
          static_cast<long>(problem.n_rows()) > max_rows)
        {
          skipped.push_back(name + " (" + std::to_string(problem.n_rows()) +
                            " rows, " + std::to_string(problem.n_components) +
                            " components)");
          continue;
        }
      const Scratch scratch;
      siconos_protocol::write(scratch.file("problem.bin"),
                              protocol_problem(problem));
      ++attempted;

      Outcome               ours;
      BNewtonSolver::Result r;
      ours.ms      = std::numeric_limits<double>::max();
      double spent = 0.;
      for (unsigned int run = 0; run_again(run, ours.ms, spent); ++run)
        {
          // With --w-prepared a fresh operator each run (it keeps
          // factorisations), its structure read before the clock starts.
          std::optional<CondensedOperator> op;
          if (w_prepared)
            {
              op.emplace(problem.W,
                         settings.linear_algebra,
                         settings.sparse_fill,
                         settings.use_symmetry);
              op->sparse_flexibility(problem);
            }
          const auto start = Clock::now();
          r                = op ? solver.solve(problem, *op, ContactIterate()) :
                                  solver.solve(problem);
          const double ms  = milliseconds_since(start);
          spent += ms;
          ours.ms = std::min(ours.ms, ms);
        }
      ours.ran        = true;
      ours.iterations = r.iterations;
      ours.sweeps     = r.sweeps;
      ours.error      = fclib_error(problem, r.p);

      const bool    three = problem.n_components == 3;
      const Outcome nsn   = three ? run_siconos(scratch,
                                              problem,
                                              SICONOS_FRICTION_3D_NSN_AC,
                                              max_iterations) :
                                    Outcome();
      const Outcome nsgs =
        run_siconos(scratch,
                    problem,
                    three ? SICONOS_FRICTION_3D_NSGS : SICONOS_FRICTION_2D_NSGS,
                    10 * max_iterations);
      const Outcome prox = three ? run_siconos(scratch,
                                               problem,
                                               SICONOS_FRICTION_3D_PROX,
                                               max_iterations) :
                                   Outcome();

      // Speed against Siconos' fastest solver that solved it too.
      double best_siconos = std::numeric_limits<double>::max();
      for (const Outcome *o : {&nsn, &nsgs, &prox})
        if (o->ran && o->error <= 1e-8)
          best_siconos = std::min(best_siconos, o->ms);
      if (ours.error <= 1e-8 &&
          best_siconos < std::numeric_limits<double>::max())
        {
          ++both_solve;
          fastest += ours.ms <= best_siconos;
          within_two += ours.ms <= 2. * best_siconos;
        }
      solved[0] += ours.error <= 1e-8;
      solved[1] += nsn.error <= 1e-8;
      solved[2] += nsgs.error <= 1e-8;
      solved[3] += prox.error <= 1e-8;
      std::cout << "| " << name << " | " << problem.n_components << " | "
                << problem.n_contacts << " | " << cell(ours) << " | "
                << cell(nsn) << " | " << cell(nsgs) << " | " << cell(prox)
                << " |" << std::endl;
    }
  std::cout << "\nsolved (FCLIB error <= 1e-8) of " << attempted << ": igabde "
            << solved[0] << ", NSN-AC " << solved[1] << " (3D only), NSGS "
            << solved[2] << ", PROX " << solved[3] << " (3D only)\nleft out:\n";
  for (const std::string &s : skipped)
    std::cout << "  " << s << '\n';
  std::cout << "speed: of the " << both_solve
            << " problems igabde and a Siconos solver both solve, igabde is "
               "the fastest on "
            << fastest << " and within 2x of Siconos' fastest on " << within_two
            << '\n';
  return 0;
}
