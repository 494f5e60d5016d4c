// siconos_solver: one Siconos solve of a problem siconos_comparison wrote;
// see `usage` below (also printed by --help). Linked with Siconos alone
// (its sequential MUMPS), never with igabde's library (the MPI MUMPS).

#include "protocol.h"
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <siconos/numerics/FrictionContactProblem.h>
#include <siconos/numerics/Friction_cst.h>
#include <siconos/numerics/NonSmoothDrivers.h>
#include <siconos/numerics/NumericsMatrix.h>
#include <siconos/numerics/SolverOptions.h>
#include <siconos/numerics/SparseBlockMatrix.h>
#include <string>
#include <vector>

namespace
{
  const char *const usage =
    R"(One Siconos friction-contact solve, for siconos_comparison (which runs it
in a process of its own, with a memory and time limit).

Usage: siconos_solver PROBLEM REPORT SOLVER TOLERANCE MAX_ITERATIONS
                      [--dense] [--once]
  PROBLEM         the problem file siconos_comparison wrote (protocol.h)
  REPORT          where the report goes (Siconos' info, iterations, the
                  fastest run in ms, the forces r)
  SOLVER          Siconos' solver id (Friction_cst.h), e.g. the 3D PROX
  TOLERANCE       Siconos' internal tolerance (SICONOS_DPARAM_TOL)
  MAX_ITERATIONS  its iteration budget (SICONOS_IPARAM_MAX_ITER)
  --dense         W in Siconos' dense storage (its 2D solvers other than
                  NSGS take no other); otherwise sparse-block storage with
                  blocks of the contact's size, the storage its local
                  solvers are written for
  --once          one run (by default repeated for the timing, as
                  siconos_comparison times igabde)
Exit status 0 when the report is written, 2 for bad arguments or files.
)";

  using Clock = std::chrono::steady_clock;

  /// A Siconos problem owning copies of W, q and mu.
  FrictionContactProblem *
  siconos_problem(const siconos_protocol::Problem &p, const bool dense)
  {
    const int       n = p.n();
    NumericsMatrix *W = nullptr;
    if (dense)
      {
        W = NM_create(NM_DENSE, n, n);
        std::fill(W->matrix0, W->matrix0 + static_cast<std::size_t>(n) * n, 0.);
        for (std::size_t k = 0; k < p.values.size(); ++k)
          W->matrix0[p.rows[k] + static_cast<std::size_t>(p.columns[k]) * n] =
            p.values[k];
      }
    else
      {
        NumericsMatrix *triplets = NM_create(NM_SPARSE, n, n);
        NM_triplet_alloc(triplets, std::max<long>(1, p.values.size()));
        for (std::size_t k = 0; k < p.values.size(); ++k)
          NM_entry(triplets, p.rows[k], p.columns[k], p.values[k]);
        SparseBlockStructuredMatrix *blocks = SBM_new();
        SBM_from_csparse(p.dimension, NM_csc(triplets), blocks);
        NM_free(triplets);
        W = NM_new_SBM(n, n, blocks);
      }
    auto *q  = static_cast<double *>(malloc(n * sizeof(double)));
    auto *mu = static_cast<double *>(malloc(p.contacts * sizeof(double)));
    std::copy(p.q.begin(), p.q.end(), q);
    std::copy(p.mu.begin(), p.mu.end(), mu);
    return frictionContactProblem_new_with_data(p.dimension,
                                                p.contacts,
                                                W,
                                                q,
                                                mu);
  }
} // namespace



int
main(int argc, char **argv)
{
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0)
      {
        std::cout << usage;
        return 0;
      }
  if (argc < 6)
    {
      std::cerr << "siconos_solver: needs PROBLEM REPORT SOLVER TOLERANCE "
                   "MAX_ITERATIONS (see --help)\n";
      return 2;
    }
  bool dense = false, once = false;
  for (int i = 6; i < argc; ++i)
    {
      if (std::strcmp(argv[i], "--dense") == 0)
        dense = true;
      else if (std::strcmp(argv[i], "--once") == 0)
        once = true;
      else
        {
          std::cerr << "siconos_solver: unknown option " << argv[i]
                    << " (see --help)\n";
          return 2;
        }
    }
  siconos_protocol::Problem problem;
  try
    {
      problem = siconos_protocol::read_problem(argv[1]);
    }
  catch (const std::exception &e)
    {
      std::cerr << "siconos_solver: " << e.what() << '\n';
      return 2;
    }
  const int    solver_id      = std::atoi(argv[3]);
  const double tolerance      = std::atof(argv[4]);
  const int    max_iterations = std::atoi(argv[5]);

  FrictionContactProblem  *fcp = siconos_problem(problem, dense);
  const int                n   = problem.n();
  siconos_protocol::Report report;
  report.ms                 = std::numeric_limits<double>::max();
  double              spent = 0.;
  std::vector<double> u;
  for (unsigned int run = 0;
       once ? run == 0 : siconos_protocol::run_again(run, report.ms, spent);
       ++run)
    {
      report.r.assign(n, 0.);
      u.assign(n, 0.);
      SolverOptions *options = solver_options_create(solver_id);
      options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iterations;
      options->dparam[SICONOS_DPARAM_TOL]      = tolerance;
      const auto start                         = Clock::now();
      report.info                              = problem.dimension == 3 ?
                                                   fc3d_driver(fcp, report.r.data(), u.data(), options) :
                                                   fc2d_driver(fcp, report.r.data(), u.data(), options);
      const double ms =
        std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      spent += ms;
      report.ms         = std::min(report.ms, ms);
      report.iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
      solver_options_delete(options);
    }
  frictionContactProblem_free(fcp);
  siconos_protocol::write(argv[2], report);
  return 0;
}
