// Seconds per B-Newton iteration on large contact problems (issue #8:
// "2 000 pairs iterate well under a second per Newton step").
//
// The problem is an elastic half-space (E, nu) under a rigid indenter, with
// the pairs on an n x n grid of square patches (side h) on its surface.
// W is the Boussinesq-Cerruti flexibility of the half-space: point-force
// kernels between distinct patches, the exact centre displacement of a
// uniformly loaded square patch on the diagonal (normal: (1-nu) L F /
// (pi G a), tangential: (2-nu) L F / (2 pi G a), L = ln(1+sqrt 2), a =
// h/2). It is dense, symmetric and positive definite, like the F^L of a
// condensed elastic body. Cases:
//   hertz-mindlin     sphere (R = 2) pressed by delta = 0.04 and shifted
//                     tangentially by 0.2 delta: contact disc of radius
//                     ~0.28 inside the unit grid, partial slip
//                     (Cattaneo-Mindlin), open pairs outside
//   flat-punch        flat punch pressed by 1e-4, mu = 0.3: every pair
//                     closed; nu = 0.3 couples normal and tangential
//                     displacements, so the rim slips (the LU path)
//   flat-punch-stick  the same punch with mu = 10: every pair closed and
//                     sticking (the Cholesky path)
//
// Usage: bnewton_scaling [pairs] [repetitions]   (default 2025 pairs, 1)
// Prints one table row per case: pairs, rows, final open/stick/slip,
// iterations, the largest reduced system, seconds of the solve and seconds
// per iteration, for the default linear algebra (LAPACK dense Cholesky/LU
// here, W being full) and, for comparison, Eigen's dense PartialPivLU of
// the same largest reduced size (the factorisation used before).

#include <igabde/contact/bnewton.h>
#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_problem.h>

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <limits>
#include <string>

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



int
main(int argc, char **argv)
{
  const unsigned int pairs       = argc > 1 ? std::atoi(argv[1]) : 2025;
  const unsigned int repetitions = argc > 2 ? std::atoi(argv[2]) : 1;
  const unsigned int n           = std::ceil(std::sqrt(double(pairs)) - 1e-12);
  const unsigned int nc          = n * n;
  const double       E = 210e3, nu = 0.3, h = 1. / n, mu = 0.3;

  const auto      t0 = std::chrono::steady_clock::now();
  Eigen::MatrixXd W  = half_space_flexibility(n, h, E, nu);
  // Exactly symmetric (the kernels are, up to the rounding of x and y).
  W = 0.5 * (W + W.transpose()).eval();
  const double t_w =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
      .count();
  std::cout << "half-space flexibility: " << nc << " pairs, " << 3 * nc
            << " rows, built in " << std::setprecision(3) << t_w << " s\n\n";

  std::cout << "| case | pairs | rows | open/stick/slip | iterations | largest "
               "reduced system | solve s | s per iteration | Eigen LU of the "
               "largest reduced system s | converged |\n"
            << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const std::string name :
       {"hertz-mindlin", "flat-punch", "flat-punch-stick"})
    {
      ContactProblem problem;
      problem.n_components = 3;
      problem.n_contacts   = nc;
      problem.W            = W;
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
      for (const auto &rec : r.history)
        largest = std::max(largest, rec.n_reduced);
      // What the factorisation used before would cost on that size.
      double t_eigen = 0.;
      if (largest > 0)
        {
          const Eigen::MatrixXd K =
            W.topLeftCorner(largest, largest) +
            Eigen::MatrixXd::Identity(largest, largest) * W(0, 0);
          const auto t2 = std::chrono::steady_clock::now();
          const Eigen::PartialPivLU<Eigen::MatrixXd> lu(K);
          t_eigen =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t2)
              .count();
          if (!(lu.rcond() > 0.))
            std::cout << "(unexpected singular comparison matrix)\n";
        }
      const bool checks =
        check_contact_conditions(problem, r.p, r.u, 1e-6).passed();
      std::cout << "| " << name << " | " << nc << " | " << 3 * nc << " | "
                << r.n_open << "/" << r.n_stick << "/" << r.n_slip << " | "
                << r.iterations << " | " << largest << " | " << std::fixed
                << std::setprecision(2) << best << " | " << std::setprecision(3)
                << (r.iterations > 0 ? best / r.iterations : 0.) << " | "
                << std::setprecision(2) << t_eigen << " | "
                << (r.converged && checks ? "yes" : "NO") << " |"
                << std::defaultfloat << std::endl;
    }
  return 0;
}
