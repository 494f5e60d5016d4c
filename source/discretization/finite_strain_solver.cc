#include <igabde/base/utilities.h>

#include <igabde/discretization/body_description.h>
#include <igabde/discretization/finite_strain_solver.h>

#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace igabde
{
  namespace discretization
  {
    namespace
    {
      /// ||v|| over the unknowns @p held leaves free.
      double
      free_norm(const Vector<double> &v, const std::vector<bool> &held)
      {
        double sum = 0.;
        for (unsigned int i = 0; i < v.size(); ++i)
          if (!held[i])
            sum += v[i] * v[i];
        return std::sqrt(sum);
      }
    } // namespace



    template <int dim>
    NewtonResult
    solve_finite_strain(const Body<dim>                             &body,
                        const elasticity::HyperelasticMaterial<dim> &material,
                        const std::vector<double>                   &factors,
                        const NewtonSettings                        &settings,
                        Vector<double>                              &u,
                        std::ostream                                *log,
                        const Vector<double> *additional_load)
    {
      AssertThrow(body.free_rigid_modes().empty(),
                  ExcMessage("Body '" + body.name() +
                             "': finite strain needs supports that hold "
                             "every rigid motion (free: " +
                             body.free_rigid_mode_names().front() + ")."));
      const types::global_dof_index    n        = body.n_dofs();
      const AffineConstraints<double> &supports = body.support_constraints();
      std::vector<bool>                held(n, false);
      for (types::global_dof_index i = 0; i < n; ++i)
        held[i] = supports.is_constrained(i);

      // The supports' values at this step. The first iteration moves the
      // supports there and the inside with them (the tangent's prediction):
      // moving the supports alone would distort the elements next to them.
      const Vector<double> g = body.prescribed_values(factors);
      const double         g_scale =
        std::max({g.linfty_norm(), u.linfty_norm(), 1e-300});
      const auto supports_reached = [&]() {
        for (types::global_dof_index i = 0; i < n; ++i)
          if (held[i] && std::abs(u[i] - g[i]) > 1e-12 * g_scale)
            return false;
        return true;
      };
      Vector<double> f_ext = body.external_load_vector(factors);
      if (additional_load != nullptr)
        f_ext += *additional_load;

      NewtonResult         result;
      SparseMatrix<double> K(body.sparsity_pattern());
      // The force the residual is measured against: the largest external
      // load or internal force (with the reactions) this solve has seen, so
      // that a state of zero stress (a rigid rotation) is still judged
      // against the forces on the way to it.
      double         reference = 1e-300;
      Vector<double> f_int(n), f_follower(n), R(n), du(n), trial(n);
      const bool     with_followers = !body.follower_pressures(factors).empty();
      // Residual and its relative norm at @p w; the tangent too when asked.
      const auto evaluate = [&](const Vector<double> &w,
                                SparseMatrix<double> *tangent,
                                double               &min_J) {
        f_int = 0.;
        if (tangent != nullptr)
          *tangent = 0.;
        min_J = body.internal_force(w, material, f_int, tangent);
        if (!(min_J > 0.))
          return std::numeric_limits<double>::infinity();
        // The follower pressures on the current surface, with their load
        // stiffness.
        f_follower = 0.;
        if (with_followers)
          body.add_follower_pressure(w, factors, f_follower, tangent);
        R = f_int;
        R -= f_ext;
        R += f_follower;
        reference = std::max(
          {reference, f_ext.l2_norm(), f_int.l2_norm(), f_follower.l2_norm()});
        return free_norm(R, held) / reference;
      };

      double min_J    = 0.;
      double residual = evaluate(u, &K, min_J);
      result.residuals.push_back(residual);
      AssertThrow(std::isfinite(residual),
                  ExcMessage("Body '" + body.name() +
                             "': the start of the step has det F <= 0 (an "
                             "inverted element); start from a smaller load "
                             "step."));
      SparseDirectUMFPACK lu;
      bool                reached = supports_reached();
      while ((residual > settings.tolerance || !reached) &&
             result.iterations < settings.max_iterations)
        {
          // K du = -R on the free unknowns, du = g - u on the held ones.
          AffineConstraints<double> increments;
          for (types::global_dof_index i = 0; i < n; ++i)
            if (held[i])
              {
                increments.add_line(i);
                increments.set_inhomogeneity(i, g[i] - u[i]);
              }
          increments.close();
          for (types::global_dof_index i = 0; i < n; ++i)
            du[i] = held[i] ? 0. : -R[i];
          increments.condense(K, du);
          lu.initialize(K);
          lu.solve(du);
          increments.distribute(du);
          ++result.iterations;

          // The full step, halved while it inverts an element; with the
          // line search, once the supports are in place, also while it
          // does not decrease ||R|| (backtracking).
          double step = 1., next = 0., trial_min_J = 0.;
          bool   accepted = false;
          for (unsigned int h = 0; h <= settings.max_halvings && !accepted;
               ++h, step /= 2.)
            {
              trial = u;
              trial.add(step, du);
              next     = evaluate(trial, nullptr, trial_min_J);
              accepted = std::isfinite(next) &&
                         (!reached || !settings.line_search ||
                          next < residual || next <= settings.tolerance);
            }
          step *= 2.;
          if (!accepted)
            {
              result.diagnosis =
                std::isfinite(next) ?
                  "no step along the Newton direction decreases the "
                  "residual" :
                  "every step along the Newton direction inverts an element";
              break;
            }
          // The accepted trial's residual stands; the tangent is assembled
          // only for another iteration.
          u        = trial;
          reached  = supports_reached();
          residual = next;
          min_J    = trial_min_J;
          if ((residual > settings.tolerance || !reached) &&
              result.iterations < settings.max_iterations)
            evaluate(u, &K, min_J);
          result.residuals.push_back(residual);
          if (log != nullptr)
            {
              *log << "    Newton " << result.iterations << ": residual "
                   << std::setprecision(3) << std::scientific << residual
                   << std::defaultfloat;
              const auto  &r = result.residuals;
              const size_t k = r.size() - 1;
              // From the third residual on: the first is measured before
              // the supports moved.
              if (k >= 3 && r[k] > 0. && r[k - 1] < r[k - 2])
                *log << ", rate " << std::setprecision(3)
                     << std::log(r[k] / r[k - 1]) /
                          std::log(r[k - 1] / r[k - 2]);
              if (step < 1.)
                *log << ", line search " << step;
              *log << std::setprecision(6) << std::endl;
            }
        }
      result.min_J     = min_J;
      result.converged = (residual <= settings.tolerance && reached);
      if (!result.converged && result.diagnosis.empty())
        {
          std::ostringstream text;
          text << std::setprecision(3) << "the residual is " << residual
               << " after " << result.iterations << " iterations (tolerance "
               << settings.tolerance << ")";
          result.diagnosis = text.str();
        }
      return result;
    }



    template NewtonResult
    solve_finite_strain<2>(const Body<2> &,
                           const elasticity::HyperelasticMaterial<2> &,
                           const std::vector<double> &,
                           const NewtonSettings &,
                           Vector<double> &,
                           std::ostream *,
                           const Vector<double> *);
    template NewtonResult
    solve_finite_strain<3>(const Body<3> &,
                           const elasticity::HyperelasticMaterial<3> &,
                           const std::vector<double> &,
                           const NewtonSettings &,
                           Vector<double> &,
                           std::ostream *,
                           const Vector<double> *);
  } // namespace discretization
} // namespace igabde
