// bnewton_scaling: see `usage` below (also printed by --help).

#include <igabde/contact/bnewton.h>
#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_problem.h>
#include <igabde/contact/fclib_reader.h>

#include <deal.II/lac/lapack_templates.h>

#include <Eigen/Dense>

#include "option_value.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  const char *const usage =
    R"(The B-Newton alone against the number of contact unknowns, measured
against the floor of its algorithm: each iteration factorises the reduced
Newton matrix (the pairs that carry unknowns in the current piece; open
pairs drop out) densely through LAPACK, so the solve cannot be faster
than the sum over its iterations of one factorisation of that size.

Problems:
 - an elastic half-space (E, nu) under a rigid indenter, the pairs on an
   n x n grid of square patches (side h) on its surface. W is the
   Boussinesq-Cerruti flexibility of the half-space: point-force kernels
   between distinct patches, the exact centre displacement of a
   uniformly loaded square patch on the diagonal (normal: (1-nu) L F /
   (pi G a), tangential: (2-nu) L F / (2 pi G a), L = ln(1+sqrt 2), a =
   h/2). It is dense, symmetric and positive definite, like the W of a
   condensed elastic body. Cases:
     hertz-mindlin     sphere (R = 2) pressed by delta = 0.04 and shifted
                       tangentially by 0.2 delta: contact disc of radius
                       ~0.28 inside the unit grid, partial slip
                       (Cattaneo-Mindlin), open pairs outside
     flat-punch        flat punch pressed by 1e-4, mu = 0.3: every pair
                       closed; nu = 0.3 couples normal and tangential
                       displacements, so the rim slips (the LU path)
     flat-punch-stick  the same punch with mu = 10: every pair closed and
                       sticking (the Cholesky path)
 - any FCLIB or Siconos problem file (--fclib), e.g. the condensed
   problem of a scene written with Output/FCLIB export = true (B2's
   curved beams: a flexibility from the bodies' Schur complements).

Usage: bnewton_scaling [--pairs 169,441,900,2025,3364]
                       [--cases hertz-mindlin,flat-punch,flat-punch-stick]
                       [--fclib FILE]... [--repeat 1]
(a single number as first argument is --pairs with that one size). Prints
one Markdown row per problem: rows, final open/stick/slip, iterations,
the largest reduced system, the factorisation flops summed over the
iterations (n^3/3 for a Cholesky iteration, every pair closed or open
and none slipping; 2 n^3/3 for an LU), the solve's seconds (best of
--repeat), the flop rate they imply, and the rate of LAPACK's LU
(dgetrf) alone on a matrix of the largest reduced size: the floor.
)";
} // namespace

using namespace igabde::contact;

namespace
{
  constexpr double pi = 3.14159265358979323846;

  // Half-space surface flexibility on an n x n grid of side h, local frames
  // (n = z into the body: compression p_n > 0 pushes the surface down, u_n
  // is the gap change, so the normal block enters with the sign that makes
  // W positive definite; a, b = x, y).
  Eigen::MatrixXd
  half_space_flexibility(const unsigned int n,
                         const double       h,
                         const double       E,
                         const double       nu)
  {
    const double       G  = E / (2. * (1. + nu));
    const double       L  = std::log(1. + std::sqrt(2.));
    const double       a  = h / 2.;
    const unsigned int nc = n * n;
    Eigen::MatrixXd    W(3 * nc, 3 * nc);
    const double       c = 1. / (4. * pi * G);
    for (unsigned int i = 0; i < nc; ++i)
      for (unsigned int j = 0; j < nc; ++j)
        {
          auto block = W.block<3, 3>(3 * i, 3 * j);
          if (i == j)
            {
              block.setZero();
              block(0, 0) = (1. - nu) * L / (pi * G * a);
              block(1, 1) = block(2, 2) = (2. - nu) * L / (2. * pi * G * a);
              continue;
            }
          const double x   = h * (double(i % n) - double(j % n));
          const double y   = h * (double(i / n) - double(j / n));
          const double rho = std::sqrt(x * x + y * y);
          // rows/columns: 0 = normal (z), 1 = x, 2 = y
          block(0, 0) = c * 2. * (1. - nu) / rho;
          block(1, 1) =
            c * (2. * (1. - nu) / rho + 2. * nu * x * x / std::pow(rho, 3));
          block(2, 2) =
            c * (2. * (1. - nu) / rho + 2. * nu * y * y / std::pow(rho, 3));
          block(1, 2) = block(2, 1) = c * 2. * nu * x * y / std::pow(rho, 3);
          // normal-tangential coupling (1 - 2 nu) x / rho^2: odd in x, so
          // antisymmetric within the block and W symmetric (reciprocity)
          block(0, 1) = c * (1. - 2. * nu) * x / (rho * rho);
          block(1, 0) = -block(0, 1);
          block(0, 2) = c * (1. - 2. * nu) * y / (rho * rho);
          block(2, 0) = -block(0, 2);
        }
    return W;
  }
} // namespace



namespace
{
  using dealii::types::blas_int;

  ContactProblem
  half_space_problem(const std::string &name, const unsigned int pairs)
  {
    const unsigned int n  = std::ceil(std::sqrt(double(pairs)) - 1e-12);
    const unsigned int nc = n * n;
    const double       E = 210e3, nu = 0.3, h = 1. / n, mu = 0.3;
    ContactProblem     problem;
    problem.n_components = 3;
    problem.n_contacts   = nc;
    problem.W            = half_space_flexibility(n, h, E, nu);
    // Exactly symmetric (the kernels are, up to the rounding of x and y).
    problem.W = 0.5 * (problem.W + problem.W.transpose()).eval();
    problem.q.resize(3 * nc);
    const bool hertz = name == "hertz-mindlin";
    problem.mu.assign(nc, name == "flat-punch-stick" ? 10. : mu);
    const double delta = hertz ? 0.04 : 1e-4, R = 2.;
    for (unsigned int i = 0; i < nc; ++i)
      {
        const double x       = h * (double(i % n) + 0.5) - 0.5;
        const double y       = h * (double(i / n) + 0.5) - 0.5;
        const double gap     = hertz ? (x * x + y * y) / (2. * R) : 0.;
        problem.q[3 * i]     = gap - delta;
        problem.q[3 * i + 1] = hertz ? 0.2 * delta : 0.;
        problem.q[3 * i + 2] = hertz ? 0.1 * delta : 0.;
      }
    problem.name = name;
    return problem;
  }



  // GFlop/s of LAPACK's dgetrf on an n x n diagonally dominant matrix (best
  // of two).
  double
  lapack_lu_rate(const unsigned int n)
  {
    if (n == 0)
      return 0.;
    double best = std::numeric_limits<double>::max();
    for (unsigned int k = 0; k < 2; ++k)
      {
        Eigen::MatrixXd A = Eigen::MatrixXd::Random(n, n);
        A.diagonal().array() += n;
        std::vector<blas_int> pivots(n);
        const blas_int        nn   = n;
        blas_int              info = 0;
        const auto            t0   = std::chrono::steady_clock::now();
        dealii::getrf(&nn, &nn, A.data(), &nn, pivots.data(), &info);
        best = std::min(best,
                        std::chrono::duration<double>(
                          std::chrono::steady_clock::now() - t0)
                          .count());
      }
    return 2. / 3. * std::pow(double(n), 3) / best * 1e-9;
  }



  std::vector<std::string>
  split(const std::string &list)
  {
    std::vector<std::string> out;
    std::stringstream        in(list);
    for (std::string item; std::getline(in, item, ',');)
      if (!item.empty())
        out.push_back(item);
    return out;
  }



  void
  run(const ContactProblem &problem,
      const std::string    &label,
      const unsigned int    repetitions)
  {
    BNewtonSolver::Settings settings;
    settings.tolerance      = 1e-10;
    settings.max_iterations = 200;
    const BNewtonSolver   solver(settings);
    double                best = std::numeric_limits<double>::max();
    BNewtonSolver::Result r;
    for (unsigned int k = 0; k < std::max(1u, repetitions); ++k)
      {
        const auto t1 = std::chrono::steady_clock::now();
        r             = solver.solve(problem);
        best          = std::min(best,
                        std::chrono::duration<double>(
                          std::chrono::steady_clock::now() - t1)
                          .count());
      }
    unsigned int largest = 0;
    double       flops   = 0.;
    for (const auto &rec : r.history)
      {
        largest        = std::max(largest, rec.n_reduced);
        const double n = rec.n_reduced;
        flops += (rec.n_slip == 0 ? 1. : 2.) / 3. * n * n * n;
      }
    const bool checks =
      check_contact_conditions(problem, r.p, r.u, 1e-6).passed();
    std::cout << "| " << label << " | " << problem.n_rows() << " | " << r.n_open
              << "/" << r.n_stick << "/" << r.n_slip << " | " << r.iterations
              << " | " << largest << " | " << std::fixed << std::setprecision(2)
              << flops * 1e-9 << " | " << std::setprecision(2) << best << " | "
              << std::setprecision(3)
              << (r.iterations > 0 ? best / r.iterations : 0.) << " | "
              << std::setprecision(1) << flops * 1e-9 / best << " | "
              << lapack_lu_rate(largest) << " | "
              << (r.converged && checks ? "yes" : "NO") << " |"
              << std::defaultfloat << std::endl;
  }
} // namespace



int
main(int argc, char **argv)
{
  igabde::benchmarks::answer_help(argc, argv, usage);
  using igabde::benchmarks::option_value;
  const std::string         tool  = "bnewton_scaling";
  std::vector<unsigned int> pairs = {169, 441, 900, 2025, 3364};
  std::vector<std::string>  cases = {"hertz-mindlin",
                                     "flat-punch",
                                     "flat-punch-stick"};
  std::vector<std::string>  files;
  unsigned int              repetitions = 1;
  for (int i = 1; i < argc; ++i)
    {
      const std::string arg  = argv[i];
      const bool        more = i + 1 < argc;
      if (arg == "--pairs" && more)
        {
          pairs.clear();
          for (const std::string &p : split(argv[++i]))
            pairs.push_back(option_value<unsigned int>(tool, arg, p));
        }
      else if (arg == "--cases" && more)
        cases = split(argv[++i]);
      else if (arg == "--fclib" && more)
        files.push_back(argv[++i]);
      else if (arg == "--repeat" && more)
        repetitions = option_value<unsigned int>(tool, arg, argv[++i]);
      else if (i == 1 && !arg.empty() &&
               arg.find_first_not_of("0123456789") == std::string::npos)
        pairs = {option_value<unsigned int>(tool, "pairs", arg)};
      else
        {
          std::cerr << "bnewton_scaling: unknown argument '" << arg
                    << "' (usage: bnewton_scaling [--pairs N,...] [--cases "
                       "NAME,...] [--fclib FILE]... [--repeat N])\n";
          return 2;
        }
    }
  if (!files.empty() &&
      std::find(argv + 1, argv + argc, std::string("--pairs")) == argv + argc)
    pairs.clear();

  std::cout << "| problem | rows | open/stick/slip | iterations | largest "
               "reduced system | factorisation GFlop | solve s | s per "
               "iteration | GFlop/s | LAPACK LU GFlop/s at the largest size "
               "| converged |\n"
            << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const unsigned int np : pairs)
    for (const std::string &name : cases)
      {
        const ContactProblem problem = half_space_problem(name, np);
        run(problem,
            name + " " + std::to_string(problem.n_contacts) + " pairs",
            repetitions);
      }
  for (const std::string &file : files)
    {
      const ContactProblem problem = read_fclib_problem(file);
      std::string          label   = file;
      const std::size_t    slash   = label.find_last_of('/');
      if (slash != std::string::npos && slash > 0)
        {
          const std::size_t before = label.find_last_of('/', slash - 1);
          label = label.substr(before == std::string::npos ? 0 : before + 1);
        }
      run(problem, label, repetitions);
    }
  return 0;
}
