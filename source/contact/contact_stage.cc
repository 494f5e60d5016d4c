#include <igabde/base/nearest_points.h>
#include <igabde/base/utilities.h>

#include <igabde/discretization/finite_strain_solver.h>

#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_stage.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <sstream>

namespace igabde
{
  namespace contact
  {
    template <int dim>
    ContactStage<dim>::ContactStage(
      const ContactSettings                                         &settings,
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      std::vector<std::unique_ptr<Obstacle<dim>>>                    obstacles,
      std::ostream                                                  &log,
      const CoupledFactory<dim> &coupled_factory)
      : settings(settings)
      , bodies(bodies)
      , obstacles(std::move(obstacles))
      , coupled_factory(coupled_factory)
      , log(log)
    {
      AssertThrow(!settings.interactions.empty(),
                  ExcMessage("contact needs at least one interaction"));
      for (const ContactInteraction &c : settings.interactions)
        {
          // The scene reader refuses these with the fix; here they are
          // internal errors.
          AssertThrow(c.slave_body < bodies.size() &&
                        (c.master_body < bodies.size() ?
                           c.master_body != c.slave_body :
                           c.obstacle < this->obstacles.size()),
                      base::ExcInput(settings.context + ": " + c.name +
                                     " needs a deformable slave body and a "
                                     "master that is another deformable body "
                                     "or a rigid obstacle."));
          pairings.push_back(create_pairing_strategy<dim>(c.pairing));
          pairings.back()->set_search_distance(c.search_distance);
        }
      finite_u.resize(bodies.size());
    }



    template <int dim>
    const Obstacle<dim> *
    ContactStage<dim>::obstacle_of(const ContactPair<dim> &pair) const
    {
      return pair.master_body < bodies.size() ? nullptr :
                                                obstacles[pair.obstacle].get();
    }



    template <int dim>
    std::string
    ContactStage<dim>::body_label(const unsigned int b) const
    {
      return b < settings.body_labels.size() ? settings.body_labels[b] :
                                               "Body " + std::to_string(b + 1);
    }



    template <int dim>
    ContactStage<dim>::~ContactStage() = default;



    template <int dim>
    const std::vector<ContactPair<dim>> &
    ContactStage<dim>::pairs() const
    {
      return pair_list;
    }



    template <int dim>
    typename ContactStage<dim>::State
    ContactStage<dim>::save_state() const
    {
      return {x,
              u_rel,
              previous_external,
              status,
              has_previous,
              finite_u,
              sliding_u,
              x_keys,
              sliding_factors};
    }



    template <int dim>
    void
    ContactStage<dim>::restore_state(const State &state)
    {
      x                 = state.x;
      u_rel             = state.u_rel;
      previous_external = state.previous_external;
      status            = state.status;
      has_previous      = state.has_previous;
      finite_u          = state.finite_u;
      finite_u.resize(bodies.size());
      sliding_u       = state.sliding_u;
      x_keys          = state.keys;
      sliding_factors = state.sliding_factors;
    }



    template <int dim>
    bool
    ContactStage<dim>::finite_strain() const
    {
      for (const auto &body : bodies)
        if (body->finite_strain())
          return true;
      return false;
    }



    template <int dim>
    const ContactProblem &
    ContactStage<dim>::condensed_problem() const
    {
      return contact.problem;
    }



    template <int dim>
    double
    ContactStage<dim>::flexibility_asymmetry() const
    {
      return contact.asymmetry;
    }



    template <int dim>
    const Eigen::VectorXd &
    ContactStage<dim>::forces() const
    {
      return x.p;
    }



    template <int dim>
    unsigned int
    ContactStage<dim>::n_components() const
    {
      return m;
    }



    template <int dim>
    Eigen::VectorXd
    ContactStage<dim>::relative_displacement(
      const std::vector<Vector<double>> &u,
      const std::vector<double>         &factors) const
    {
      Eigen::VectorXd result(m * pair_list.size());
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          const ContactPair<dim> &pair = pair_list[i];
          Tensor<1, dim> du = pair.op1.displacement(u[pair.slave_body]);
          if (const Obstacle<dim> *obstacle = obstacle_of(pair))
            {
              if (obstacle->moves())
                du -= obstacle->displacement(pair.x2, factors);
            }
          else
            du -= pair.op2.displacement(u[pair.master_body]);
          for (unsigned int s = 0; s < m; ++s)
            result(m * i + s) = pair_list[i].frame[s] * du;
        }
      return result;
    }



    template <int dim>
    Tensor<1, dim>
    ContactStage<dim>::global_force(const unsigned int     i,
                                    const Eigen::VectorXd &forces) const
    {
      Tensor<1, dim> f;
      for (unsigned int s = 0; s < m; ++s)
        f += forces(m * i + s) * pair_list[i].frame[s];
      return f;
    }



    template <int dim>
    ContactIterate
    ContactStage<dim>::initial_guess() const
    {
      // Candidate 1, first step: no force, rigid modes placed so that the
      // closest pair just touches (with every pair open the alpha columns of
      // the Newton matrix vanish). Later steps: the previous step's forces,
      // rigid-mode amplitudes and contact displacement (warm start).
      const ContactProblem &problem = contact.problem;
      ContactOperator      &op      = contact_path->op();
      // First step with floating bodies: the rigid bodies' rest position
      // (resting_alpha()), else the closest pair just touching.
      ContactIterate            x0;
      std::vector<bool>         closed = expected_closed();
      std::vector<unsigned int> resting;
      x0.p = has_previous ? x.p : Eigen::VectorXd::Zero(problem.n_rows());
      if (has_previous)
        x0.alpha = x.alpha;
      else if (problem.n_alpha() > 0 &&
               !resting_alpha(problem, x0.alpha, resting))
        x0.alpha = touching_alpha(problem);
      x0.w = has_previous ? x.w : Eigen::VectorXd::Zero(op.n_dofs());
      // Nothing touches in the undeformed geometry: the pairs on which the
      // rigid bodies rest are the ones expected closed.
      if (std::find(closed.begin(), closed.end(), true) == closed.end())
        for (const unsigned int i : resting)
          closed[i] = true;

      // Candidate 2: the path's bilateral solve over the pairs expected
      // closed and sticking: in the first step those that touch in the
      // undeformed geometry, later those closed at the end of the previous
      // step. On flat matching surfaces with zero gap every pair is at a
      // tie of the min function, where the first Newton matrix is a poor
      // model, and after a load change the warm start violates the
      // equilibrium of floating bodies by the whole change; this start is
      // exact when the contact state does not change. The better candidate
      // by natural-map plus equilibrium residual is used.
      ContactIterate x1;
      if (!op.bilateral_start(problem, closed, x1))
        return x0;

      // Natural-map residual plus the equilibrium of floating bodies (the
      // natural map alone is zero for p = 0 with every pair open).
      const unsigned int na    = problem.n_alpha();
      const auto         error = [&](const ContactIterate &y) {
        op.update_geometry(y);
        Eigen::VectorXd u = op.displacement(y.p, y.w) + problem.q;
        if (const Eigen::VectorXd *offset = op.displacement_offset())
          u += *offset;
        if (na > 0)
          u += problem.G * y.alpha;
        double e = relative_natural_map_error(problem, y.p, u);
        if (na > 0)
          e += (problem.G.transpose() * y.p - problem.b).norm() /
               std::max(problem.b.norm(), 1e-300);
        return e;
      };
      if (error(x1) < error(x0))
        return x1;
      return x0;
    }



    template <int dim>
    std::vector<bool>
    ContactStage<dim>::expected_closed() const
    {
      double size = 0.;
      for (const auto &pair : pair_list)
        size = std::max(size, (pair.x1 - pair_list[0].x1).norm());
      std::vector<bool> closed(pair_list.size());
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        closed[i] = has_previous ?
                      status[i] != ContactStatus::open :
                      pair_list[i].gap <= 1e-12 * std::max(size, 1e-300);
      return closed;
    }



    template <int dim>
    StepResult<dim>
    ContactStage<dim>::solve_step(const double                 load_factor,
                                  std::vector<Vector<double>> &u,
                                  TimerOutput                 &timer)
    {
      return solve_step(std::vector<double>{load_factor}, u, timer);
    }



    template <int dim>
    StepResult<dim>
    ContactStage<dim>::solve_step(const std::vector<double>   &factors,
                                  std::vector<Vector<double>> &u,
                                  TimerOutput                 &timer)
    {
      // Finite sliding: the step's pairs on the last step's configuration
      // (the operator built on them again).
      if (settings.finite_sliding)
        form_step_pairs(timer);
      ContactProblem  &problem = contact.problem;
      ContactOperator &op      = contact_path->op();
      // Bodies at finite strain: the step starts from the predictor, one
      // Newton step of each body alone from its last state with the last
      // contact forces held (the tangent's prediction of this step's loads
      // and support moves, halved while it inverts an element); the
      // supports that step did not reach move there during the solve (u
      // holds the start, U sees them moved), and the correction w starts
      // from zero.
      const bool      finite = finite_strain();
      Eigen::VectorXd U;
      if (finite)
        {
          std::vector<Vector<double>> moved(bodies.size());
          for (unsigned int b = 0; b < bodies.size(); ++b)
            if (bodies[b]->finite_strain())
              {
                if (finite_u[b].size() != bodies[b]->n_dofs())
                  finite_u[b].reinit(bodies[b]->n_dofs());
                u[b] = finite_u[b];
                discretization::NewtonSettings predictor;
                predictor.tolerance      = 0.;
                predictor.max_iterations = 1;
                const Vector<double> held_load =
                  has_previous ? contact_load(b) : Vector<double>();
                discretization::solve_finite_strain(*bodies[b],
                                                    bodies[b]->finite_law(),
                                                    factors,
                                                    predictor,
                                                    u[b],
                                                    nullptr,
                                                    has_previous ? &held_load :
                                                                   nullptr);
                moved[b]               = u[b];
                const Vector<double> g = bodies[b]->prescribed_values(factors);
                for (unsigned int i = 0; i < g.size(); ++i)
                  if (bodies[b]->is_held(i))
                    moved[b][i] = g[i];
              }
            else
              moved[b] = u[b];
          U = relative_displacement(from_paired_configuration(moved), factors);
          // The size of the pairs' displacements from the reference
          // configuration (q holds those from the predictor only).
          double sum = 0.;
          for (const auto &pair : pair_list)
            for (const unsigned int b : {pair.slave_body, pair.master_body})
              {
                if (b >= bodies.size())
                  continue;
                double      sign = 0.;
                const auto &op   = *pair.operator_on(b, sign);
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    double v = 0.;
                    for (unsigned int k = 0; k < op.weights.size(); ++k)
                      v += op.weights[k] * moved[b][op.dofs[k][c]];
                    sum += v * v;
                  }
              }
          problem.displacement_scale = std::sqrt(sum);
        }
      else
        U = relative_displacement(from_paired_configuration(u), factors);
      // What the previous step's contact forces contribute to the pair
      // displacements (subtracted from the tangential increments).
      Eigen::VectorXd carry = op.displacement(x.p, x.w);
      if (problem.n_alpha() > 0)
        carry += problem.G * x.alpha;
      if (finite)
        {
          contact_path->set_reference(u, factors);
          unsigned int offset = 0;
          for (const auto &body : bodies)
            {
              if (body->finite_strain() && x.w.size() > 0)
                x.w.segment(offset, body->n_dofs()).setZero();
              offset += body->n_dofs();
            }
        }

      // Normal rows: total relative displacement, gap included. Tangential
      // rows: increments of this step (friction is incremental).
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          problem.q(m * i) = pair_list[i].gap + U(m * i);
          for (unsigned int s = 1; s < m; ++s)
            problem.q(m * i + s) =
              U(m * i + s) - previous_external(m * i + s) - carry(m * i + s);
        }
      problem.b = rigid_mode_load(factors);
      // Loads or load factors past double arithmetic: the solver's norms
      // would overflow and no answer exists (base::largest_squarable_entry).
      {
        const double largest =
          std::max(base::largest_magnitude(problem.q.data(), problem.q.size()),
                   base::largest_magnitude(problem.b.data(), problem.b.size()));
        const double limit =
          base::largest_squarable_entry(problem.q.size() + problem.b.size());
        std::string factor_list;
        for (const double f : factors)
          factor_list +=
            (factor_list.empty() ? "" : ", ") + base::number_text(f);
        AssertThrow(
          largest <= limit,
          base::ExcInput(
            "the contact problem at the history factors (" + factor_list +
            ") " +
            (std::isfinite(largest) ?
               "reaches " + base::number_text(largest) + ", past the " +
                 base::number_text(limit) +
                 " whose square double precision can hold" :
               "is not finite") +
            " (the pairs' displacements under the loads and the floating "
            "bodies' loads): check the magnitudes (and units) of the loads "
            "and of Load path/Load factors"));
      }

      // What the solve's corrections w add to (finite sliding's pairs_at()).
      if (settings.finite_sliding)
        {
          sliding_base  = u;
          solve_factors = factors;
          op.forget_geometry();
        }
      ContactSolverResult solution;
      {
        TimerOutput::Scope t(timer, "contact: " + solver_section);
        solution = solver->solve(problem, op, initial_guess(), x.p);
      }
      if (settings.log_solves)
        log << "  " << solver_label << ": " << solution.summary() << std::endl;
      if (!solver->exact())
        log << "  maximum penetration " << std::setprecision(6)
            << solution.max_penetration << std::endl;

      StepResult<dim> result;
      result.converged = solution.converged;
      result.diagnosis = solution.diagnosis;
      // One of the BDE's two measures (the relative and the balanced
      // natural-map residual) meets the tolerance and rounding holds the
      // other above it, where forces and displacements are of very
      // different scales: a tolerance below what double precision reaches
      // here. A cut of the load scales both alike; a looser tolerance
      // accepts this solution.
      const double tolerance = settings.solver.bnewton.tolerance;
      const double stuck =
        std::max(solution.residual, solution.balanced_residual);
      if (!solution.converged && settings.solver.algorithm == Algorithm::bde &&
          std::min(solution.residual, solution.balanced_residual) <=
            tolerance &&
          stuck > tolerance && solution.equilibrium_residual <= tolerance)
        {
          std::ostringstream advice;
          advice << std::setprecision(2) << "Contact/Tolerance = " << tolerance
                 << " is below what rounding lets this problem reach: the "
                 << (solution.residual > tolerance ? "relative" : "balanced")
                 << " natural-map residual stays at " << stuck
                 << " while the other meets it; a Contact/Tolerance above "
                 << stuck << " accepts this solution";
          result.advice = advice.str();
        }
      // Where the pairs the failure involves are (numbered as in the
      // contact CSV files).
      if (!solution.converged && !solution.pairs_involved.empty())
        {
          std::ostringstream where;
          where << std::setprecision(4) << "; where:";
          for (unsigned int k = 0; k < solution.pairs_involved.size() && k < 8;
               ++k)
            {
              const unsigned int i = solution.pairs_involved[k];
              if (i >= pair_list.size())
                continue;
              where << (k > 0 ? "," : "") << " pair " << i << " at ("
                    << base::to_string(pair_list[i].x1) << ")";
            }
          result.diagnosis += where.str();
        }
      result.iterations      = solution.iterations;
      result.residual        = solution.residual;
      result.n_open          = solution.n_open;
      result.n_stick         = solution.n_stick;
      result.n_slip          = solution.n_slip;
      result.n_closed        = solution.n_closed;
      result.max_penetration = std::max(solution.max_penetration, 0.);
      result.updates         = solution.updates;
      for (const auto &rec : solution.history)
        {
          result.residual_history.push_back(rec.residual);
          if (rec.linear_iterations > 0)
            result.linear_iterations.push_back(rec.linear_iterations);
        }
      if (!solution.converged)
        return result;

      // The penalty answer penetrates by design (about p / k_n): it is
      // reported, not checked against the exact conditions.
      if (!solver->exact())
        result.conditions_passed = true;
      else
        {
          const ConditionReport report =
            check_contact_conditions(problem,
                                     solution.p,
                                     solution.u,
                                     settings.check_tolerance);
          for (const auto &c : report.conditions)
            result.condition_check_max_violation =
              std::max(result.condition_check_max_violation, c.max_violation);
          result.conditions_passed = report.passed();
          if (!result.conditions_passed)
            {
              result.first_violation = report.first_violation();
              return result;
            }
        }

      x.p               = solution.p;
      x.alpha           = solution.alpha.size() > 0 ?
                            solution.alpha :
                            Eigen::VectorXd::Zero(problem.n_alpha());
      x.w               = solution.w;
      u_rel             = solution.u;
      status            = solution.status;
      previous_external = U;
      has_previous      = true;
      // Finite sliding: the pairs at the solution's configuration, on
      // which its forces act.
      if (settings.finite_sliding)
        {
          x_keys    = pair_keys();
          pair_list = pairs_at(x.w);
        }

      // Contact forces back to the fields.
      {
        TimerOutput::Scope          t(timer, "contact: fields");
        std::vector<Vector<double>> loads;
        for (const auto &body : bodies)
          loads.emplace_back(body->n_dofs());
        result.interaction_forces.resize(settings.interactions.size());
        for (unsigned int i = 0; i < pair_list.size(); ++i)
          {
            const ContactPair<dim> &pair = pair_list[i];
            const Tensor<1, dim>    f    = global_force(i, x.p);
            result.contact_force += f;
            result.interaction_forces[pair.interaction] += f;
            pair.op1.distribute(f, loads[pair.slave_body]);
            if (pair.master_body < bodies.size())
              pair.op2.distribute(-f, loads[pair.master_body]);
          }
        // The bodies' response (the path: solved already on the full
        // path, one solve per body on the condensed one).
        contact_path->add_response(loads, x, u);
        const Eigen::VectorXd amplitudes = contact.alpha_basis * x.alpha;
        for (unsigned int a = 0; a < contact.alpha_modes.size(); ++a)
          {
            const auto [b, k] = contact.alpha_modes[a];
            u[b].add(amplitudes(a), bodies[b]->free_rigid_modes()[k]);
          }
        // The next step at finite strain starts here; with finite sliding
        // its pairs are formed on this configuration.
        for (unsigned int b = 0; b < bodies.size(); ++b)
          if (bodies[b]->finite_strain())
            finite_u[b] = u[b];
        if (settings.finite_sliding)
          {
            sliding_u       = u;
            sliding_factors = factors;
          }
      }
      return result;
    }



    template <int dim>
    Eigen::VectorXd
    ContactStage<dim>::rigid_mode_load(const std::vector<double> &factors) const
    {
      // The loads floating bodies must balance: every history at its
      // factor.
      Eigen::VectorXd b =
        Eigen::VectorXd::Zero(contact.rigid_mode_loads.size());
      for (unsigned int h = 0;
           h < factors.size() && h < contact.rigid_mode_history_loads.cols();
           ++h)
        b -= factors[h] * contact.rigid_mode_history_loads.col(h);
      return b;
    }



    template <int dim>
    std::string
    ContactStage<dim>::unbalanceable_load(
      const std::vector<double> &factors) const
    {
      const ContactProblem &problem = contact.problem;
      if (problem.n_alpha() == 0)
        return "";
      const Eigen::VectorXd b     = rigid_mode_load(factors);
      double                scale = 0.;
      for (unsigned int h = 0;
           h < factors.size() && h < contact.rigid_mode_history_loads.cols();
           ++h)
        scale +=
          std::abs(factors[h]) * contact.rigid_mode_history_loads.col(h).norm();
      for (unsigned int a = 0; a < problem.n_alpha(); ++a)
        {
          if (!(std::abs(b(a)) > 1e-8 * scale))
            continue;
          // The work of pair i's force on mode a ranges over
          // p_n [G_n - mu |G_t|, G_n + mu |G_t|] for p_n >= 0.
          double lowest = 0., highest = 0., largest = 0.;
          for (unsigned int i = 0; i < problem.n_contacts; ++i)
            {
              const double normal     = problem.G(m * i, a);
              double       tangential = 0.;
              for (unsigned int s = 1; s < m; ++s)
                tangential += problem.G(m * i + s, a) * problem.G(m * i + s, a);
              tangential = problem.mu[i] * std::sqrt(tangential);
              lowest     = std::min(lowest, normal - tangential);
              highest    = std::max(highest, normal + tangential);
              largest    = std::max(largest, std::abs(normal) + tangential);
            }
          const double negligible = 1e-12 * largest;
          if ((b(a) > 0. && highest > negligible) ||
              (b(a) < 0. && lowest < -negligible))
            continue;
          Eigen::Index main = 0;
          contact.alpha_basis.col(a).cwiseAbs().maxCoeff(&main);
          const auto [body, k] = contact.alpha_modes[main];
          return "the load drives " + body_label(body) +
                 "'s free rigid mode '" +
                 bodies[body]->free_rigid_mode_names()[k] +
                 "' in a direction no contact pair can resist (pairs only "
                 "push: along their normals, with friction inside Coulomb's "
                 "cone), so no equilibrium exists; the body is pulled off "
                 "the surface it rests on. Reverse the load (Load path), "
                 "hold the mode with a support (Supports) or change the "
                 "contact faces";
        }
      return "";
    }



    template <int dim>
    Vector<double>
    ContactStage<dim>::contact_load(const unsigned int b) const
    {
      Vector<double> load(bodies[b]->n_dofs());
      if (status.empty())
        return load;
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          double      sign = 0.;
          const auto *op   = pair_list[i].operator_on(b, sign);
          if (op != nullptr)
            op->distribute(sign * global_force(i, x.p), load);
        }
      return load;
    }



    template class ContactStage<2>;
    template class ContactStage<3>;
  } // namespace contact
} // namespace igabde
