// siconos_comparison: see `usage` below (also printed by --help).

#include <igabde/contact/bnewton.h>
#include <igabde/contact/contact_law.h>
#include <igabde/contact/contact_operator.h>
#include <igabde/contact/contact_problem.h>
#include <igabde/contact/fclib_reader.h>

#include <deal.II/base/mpi.h>

#include <Eigen/Eigenvalues>

#include "../option_value.h"
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <siconos/numerics/FrictionContactProblem.h>
#include <siconos/numerics/Friction_cst.h>
#include <siconos/numerics/NonSmoothDrivers.h>
#include <siconos/numerics/NumericsMatrix.h>
#include <siconos/numerics/SolverOptions.h>
#include <siconos/numerics/SparseBlockMatrix.h>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>
#include <vector>

namespace
{
  const char *const usage =
    R"(igabde's B-Newton beside Siconos' FCLIB solvers, in one process and run,
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
                    (3D: PROX and NSN-AC; 2D: Lemke's pivoting method and
                    NSGS) at internal tolerance 1e-14 and compare their
                    forces with the solution stored in the file; exit
                    status 0 ("same answer") if the first of them to meet
                    FCLIB's measure at 1e-8 lies within TOL of the stored
                    one (relative), or without --agree within the distance
                    the two answers' FCLIB errors allow (the natural-map
                    error bound; where W is only semidefinite, if both
                    meet 1e-8); 1 ("DIFFERENT answer") if not, or if the
                    stored solution does not meet 1e-8; 3 ("no verdict")
                    when neither Siconos solver meets 1e-8, naming both;
                    2 for bad input; ctests with scenes from prm/ and the
                    FCLIB problems

Each problem is read once, by igabde's reader (a global problem condensed
through its sparse M, W = H^T M^-1 H), and handed to both: igabde's
B-Newton works on the dense W, Siconos' solvers on the same W in their
sparse-block storage (blocks of the contact's size, exact zeros left
out), the storage they are written for. (Debian's Siconos is built
without FCLIB, so it cannot read the HDF5 files itself.) Every answer r
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

  /// Whether a solve runs again after @p runs_done runs that took @p spent
  /// ms together, the fastest @p fastest ms (the largest double before the
  /// first run); the fastest run counts. A solve under a second runs at
  /// least twice, and runs again while its runs have taken under 20 ms
  /// together (at most 100 runs), so that a solve of microseconds is timed
  /// warm. A first call pays start-up costs (OpenBLAS' threads, first-touch
  /// page faults: 7.4 ms first against 2.6 ms after for igabde on
  /// Box_Stacks-i0122), and Siconos' solves run in forked children, after
  /// which the parent's (igabde's) next runs fault on pages again: in the
  /// full run GFC3D_Example1 took 0.036 ms (2 minor page faults), 0.016 ms
  /// (1), then 0.0016-0.0019 ms (none) from the third run on, and
  /// NESpheres_30_1 0.13 ms (9), 0.024 ms (1), then 0.009 ms (2026-11-29).
  /// Siconos and igabde are timed alike.
  bool
  run_again(const unsigned int runs_done,
            const double       fastest,
            const double       spent)
  {
    if (runs_done == 0)
      return true;
    if (runs_done == 1)
      return fastest < 1000.;
    return spent < 20. && runs_done < 100;
  }

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

  /// A Siconos problem owning @p W and copies of q and mu (Siconos frees
  /// them with the problem).
  FrictionContactProblem *
  with_q_and_mu(const ContactProblem &problem, NumericsMatrix *W)
  {
    const int n = problem.n_rows();
    auto     *q = static_cast<double *>(malloc(n * sizeof(double)));
    auto     *mu =
      static_cast<double *>(malloc(problem.n_contacts * sizeof(double)));
    std::copy(problem.q.data(), problem.q.data() + n, q);
    std::copy(problem.mu.begin(), problem.mu.end(), mu);
    return frictionContactProblem_new_with_data(problem.n_components,
                                                problem.n_contacts,
                                                W,
                                                q,
                                                mu);
  }



  /// The problem in Siconos' sparse-block storage (blocks of the
  /// contact's size, the exact zeros of W left out): the storage its local
  /// solvers are written for.
  FrictionContactProblem *
  siconos_problem(const ContactProblem &problem)
  {
    const int       d = problem.n_components, n = problem.n_rows();
    NumericsMatrix *triplets = NM_create(NM_SPARSE, n, n);
    NM_triplet_alloc(triplets, (W_nonzeros(problem.W)));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (problem.W(i, j) != 0.)
          NM_entry(triplets, i, j, problem.W(i, j));
    SparseBlockStructuredMatrix *blocks = SBM_new();
    SBM_from_csparse(d, NM_csc(triplets), blocks);
    NM_free(triplets);
    return with_q_and_mu(problem, NM_new_SBM(n, n, blocks));
  }

  /// The problem with W in Siconos' dense (column-major) storage.
  FrictionContactProblem *
  siconos_dense(const ContactProblem &problem)
  {
    const int       n      = problem.n_rows();
    NumericsMatrix *matrix = NM_create(NM_DENSE, n, n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        matrix->matrix0[i + static_cast<std::size_t>(j) * n] = problem.W(i, j);
    return with_q_and_mu(problem, matrix);
  }

  /// What a solve in the child process reports to the parent.
  struct Report
  {
    double error      = 1.;
    double ms         = 0.;
    int    iterations = 0;
    int    info       = -1;
  };

  /**
   * One Siconos solve at @p tolerance, in a child process with at most
   * 8 GiB of address space and 120 s: some solvers exhaust the memory
   * on some problems (NSN-AC on RockPile_tob1 took 24 GB) or abort, and
   * the table must go on. Returns false if the child did not report.
   */
  bool
  solve_isolated(FrictionContactProblem *fcp,
                 const ContactProblem   &problem,
                 const int               solver_id,
                 const int               max_iterations,
                 const double            tolerance,
                 Report                 &report,
                 std::string            &why)
  {
    int channel[2];
    if (pipe(channel) != 0)
      {
        why = "no pipe";
        return false;
      }
    // The child works in a scratch folder of its own, removed here
    // afterwards whatever became of the child: Siconos' solvers leave
    // empty Fortran unit files (fort.N, from their MUMPS calls) in the
    // working folder.
    std::string scratch =
      (std::filesystem::temp_directory_path() / "siconos-XXXXXX").string();
    const bool have_scratch = mkdtemp(scratch.data()) != nullptr;
    std::cout.flush();
    const pid_t child = fork();
    if (child == 0)
      {
        close(channel[0]);
        if (have_scratch && chdir(scratch.c_str()) != 0)
          _exit(1);
        const rlimit memory = {8ul << 30, 8ul << 30};
        setrlimit(RLIMIT_AS, &memory);
        alarm(120);
        const int           n = fcp->dimension * fcp->numberOfContacts;
        std::vector<double> r, u;
        Report              out;
        out.ms       = std::numeric_limits<double>::max();
        double spent = 0.;
        for (unsigned int run = 0; run_again(run, out.ms, spent); ++run)
          {
            r.assign(n, 0.);
            u.assign(n, 0.);
            SolverOptions *options = solver_options_create(solver_id);
            options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iterations;
            options->dparam[SICONOS_DPARAM_TOL]      = tolerance;
            const auto start                         = Clock::now();
            out.info                                 = fcp->dimension == 3 ?
                                                         fc3d_driver(fcp, r.data(), u.data(), options) :
                                                         fc2d_driver(fcp, r.data(), u.data(), options);
            const double ms = milliseconds_since(start);
            spent += ms;
            out.ms         = std::min(out.ms, ms);
            out.iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
            solver_options_delete(options);
          }
        out.error =
          fclib_error(problem, Eigen::Map<const Eigen::VectorXd>(r.data(), n));
        const ssize_t written = write(channel[1], &out, sizeof(out));
        _exit(written == sizeof(out) ? 0 : 1);
      }
    close(channel[1]);
    const bool read_all =
      child > 0 && read(channel[0], &report, sizeof(report)) ==
                     static_cast<ssize_t>(sizeof(report));
    close(channel[0]);
    int status = 0;
    if (child > 0)
      waitpid(child, &status, 0);
    if (have_scratch)
      {
        std::error_code ignored;
        std::filesystem::remove_all(scratch, ignored);
      }
    if (!read_all)
      why = WIFSIGNALED(status) ?
              (WTERMSIG(status) == SIGALRM ?
                 "time limit (120 s)" :
               WTERMSIG(status) == SIGABRT ?
                 "aborted (memory?)" :
                 "killed by signal " + std::to_string(WTERMSIG(status))) :
              "no answer";
    return read_all;
  }

  /// One Siconos solver on @p fcp, its tolerance tightened until our
  /// measure passes.
  Outcome
  run_siconos(FrictionContactProblem *fcp,
              const ContactProblem   &problem,
              const int               solver_id,
              const int               max_iterations)
  {
    Outcome best;
    for (const double tolerance : {1e-8, 1e-10, 1e-12, 1e-14})
      {
        Report      report;
        std::string why;
        if (!solve_isolated(fcp,
                            problem,
                            solver_id,
                            max_iterations,
                            tolerance,
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
        outcome.error      = report.error;
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
    const ContactProblem problem   = read_fclib_problem(file);
    const FclibSolution  reference = read_fclib_solution(file);
    if (!reference.available || reference.r.size() != problem.n_rows())
      {
        std::cerr << "siconos_comparison: " << file
                  << " stores no solution to compare with\n";
        return 2;
      }
    FrictionContactProblem *fcp = siconos_problem(problem);
    const int               n   = problem.n_rows();
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
    std::cout << "stored solution: FCLIB error " << std::scientific
              << std::setprecision(2) << reference_error;
    if (lambda_min > 1e-12 * std::abs(lambda_max))
      std::cout << "; |r - r*| / |r| <= " << amplification
                << " x (the FCLIB error)";
    else
      std::cout << "; W is not positive definite (smallest eigenvalue "
                << lambda_min << ")";
    std::cout << std::defaultfloat << '\n';
    // 3D: PROX (judged) and NSN-AC on the sparse-block storage; 2D:
    // Lemke's pivoting method on the equivalent LCP (judged: exact up to
    // round-off where it ends) and NSGS, both on a dense copy (Siconos'
    // 2D solvers other than NSGS take dense storage only).
    const bool              three = problem.n_components == 3;
    FrictionContactProblem *dense = three ? nullptr : siconos_dense(problem);
    const std::vector<std::pair<int, const char *>> solvers =
      three ?
        std::vector<std::pair<int, const char *>>{
          {SICONOS_FRICTION_3D_PROX, "PROX"},
          {SICONOS_FRICTION_3D_NSN_AC, "NSN-AC"}} :
        std::vector<std::pair<int, const char *>>{
          {SICONOS_FRICTION_2D_LEMKE, "Lemke"},
          {SICONOS_FRICTION_2D_NSGS, "NSGS"}};
    // The first solver that meets FCLIB's measure at 1e-8 judges; one that
    // does not is named, and if none does there is no verdict.
    std::string judge, failures;
    double      judged_difference = 0., judged_error = 0.;
    for (const auto &[id, label] : solvers)
      {
        std::vector<double> r(n, 0.), u(n, 0.);
        SolverOptions      *options              = solver_options_create(id);
        options->iparam[SICONOS_IPARAM_MAX_ITER] = 10000;
        options->dparam[SICONOS_DPARAM_TOL]      = 1e-14;
        const int info                           = three ?
                                                     fc3d_driver(fcp, r.data(), u.data(), options) :
                                                     fc2d_driver(dense, r.data(), u.data(), options);
        solver_options_delete(options);
        const Eigen::Map<const Eigen::VectorXd> rs(r.data(), n);
        const double error = fclib_error(problem, rs);
        const double difference =
          (rs - reference.r).norm() / std::max(reference.r.norm(), 1e-300);
        std::cout << label << ": info " << info << ", FCLIB error "
                  << std::scientific << std::setprecision(2) << error
                  << ", |r - r_file| / |r_file| " << difference
                  << std::defaultfloat << '\n';
        if (error > 1e-8)
          {
            std::ostringstream why;
            why << label << " (info " << info << ", FCLIB error "
                << std::scientific << std::setprecision(2) << error << ")";
            failures += (failures.empty() ? "" : ", ") + why.str();
          }
        else if (judge.empty())
          {
            judge             = label;
            judged_difference = difference;
            judged_error      = error;
          }
      }
    if (dense != nullptr)
      frictionContactProblem_free(dense);
    frictionContactProblem_free(fcp);

    // The verdict on the stored solution, by the judge's answer.
    const bool definite = lambda_min > 1e-12 * std::abs(lambda_max);
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
        std::cout << "DIFFERENT answer: the stored solution does not solve "
                     "the problem (FCLIB error "
                  << reference_error << " > 1e-8); " << judge
                  << " does (FCLIB error " << judged_error << ")\n";
        return 1;
      }
    if (agreement > 0.)
      {
        const bool same = judged_difference <= agreement;
        std::cout << (same ? "same answer" : "DIFFERENT answer") << ": "
                  << judge << " and the stored solution differ by "
                  << judged_difference << (same ? " <= " : " > ") << agreement
                  << " (--agree)\n";
        return same ? 0 : 1;
      }
    if (!definite)
      {
        // W only semidefinite: the solution need not be unique, and the
        // natural map bounds no distance; both answers solve the problem.
        std::cout << "same answer: " << judge
                  << " and the stored solution both solve the problem "
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
              << " and the stored solution differ by " << judged_difference
              << (same ? " <= " : " > ") << bound
              << ", the distance their FCLIB errors allow\n";
    return same ? 0 : 1;
  }
} // namespace



int
main(int argc, char **argv)
{
  igabde::benchmarks::answer_help(argc, argv, usage);
  // Siconos' sparse solvers call MUMPS, which in this process is the MPI
  // build igabde links (one dmumps_c serves both): MPI must be running.
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
      FrictionContactProblem *fcp = siconos_problem(problem);
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
      const Outcome nsn   = three ? run_siconos(fcp,
                                              problem,
                                              SICONOS_FRICTION_3D_NSN_AC,
                                              max_iterations) :
                                    Outcome();
      const Outcome nsgs =
        run_siconos(fcp,
                    problem,
                    three ? SICONOS_FRICTION_3D_NSGS : SICONOS_FRICTION_2D_NSGS,
                    10 * max_iterations);
      const Outcome prox =
        three ?
          run_siconos(fcp, problem, SICONOS_FRICTION_3D_PROX, max_iterations) :
          Outcome();
      frictionContactProblem_free(fcp);

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
