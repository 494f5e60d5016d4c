#include <igabde/base/utilities.h>

#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_stage.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace igabde
{
  namespace contact
  {
    template <int dim>
    ContactStage<dim>::ContactStage(
      const ContactSettings                                         &settings,
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      std::unique_ptr<Obstacle<dim>>                                 obstacle,
      std::ostream                                                  &log)
      : settings(settings)
      , bodies(bodies)
      , obstacle(std::move(obstacle))
      , pairing(create_pairing_strategy<dim>(settings.pairing))
      , log(log)
    {
      AssertThrow(this->obstacle || bodies.size() == 2,
                  base::ExcInput(settings.context +
                                 ": contact needs Body 2 (deformable) or a "
                                 "rigid plane."));
    }



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
      return {p, alpha, u_rel, previous_external, w, status, has_previous};
    }



    template <int dim>
    void
    ContactStage<dim>::restore_state(const State &state)
    {
      p                 = state.p;
      alpha             = state.alpha;
      u_rel             = state.u_rel;
      previous_external = state.previous_external;
      w                 = state.w;
      status            = state.status;
      has_previous      = state.has_previous;
    }



    template <int dim>
    const ContactProblem &
    ContactStage<dim>::condensed_problem() const
    {
      return condensed.problem;
    }



    template <int dim>
    double
    ContactStage<dim>::flexibility_asymmetry() const
    {
      return condensed.asymmetry;
    }



    template <int dim>
    const Eigen::VectorXd &
    ContactStage<dim>::forces() const
    {
      return p;
    }



    template <int dim>
    unsigned int
    ContactStage<dim>::n_components() const
    {
      return m;
    }



    template <int dim>
    void
    ContactStage<dim>::build_pairs(TimerOutput &timer)
    {
      m = (settings.friction_coefficient > 0. ? dim : 1);
      TimerOutput::Scope t(timer, "contact: pairs");
      if (!obstacle)
        master_face =
          std::make_unique<BodyFace<dim>>(*bodies[1], settings.master_face);
      const ContactSurface<dim> &master =
        obstacle ? static_cast<const ContactSurface<dim> &>(*obstacle) :
                   *master_face;
      pair_list = pairing->make_pairs(*bodies[0],
                                      settings.slave_face,
                                      master,
                                      settings.context);

      // The path: penalty methods solve the full system (as ANSYS does);
      // the BDE takes the path asked for, or under auto the one the cost
      // model (path_cost.h) estimates cheaper.
      ContactSolverSettings solver_settings = settings.solver;
      if (settings.solver.algorithm != "bde")
        {
          resolved_path = "full";
          path_why      = settings.solver.algorithm + " solves the full system";
        }
      else if (settings.solver.path == "auto")
        {
          const PathCostEstimate e =
            estimate_path_costs(path_cost_inputs(),
                                PathCostConstants::measured());
          resolved_path               = e.path;
          path_why                    = e.reason;
          estimated_condensed_seconds = e.condensed_seconds;
          estimated_full_seconds      = e.full_seconds;
        }
      else
        {
          resolved_path = settings.solver.path;
          path_why      = "Contact/Path = " + settings.solver.path;
        }
      solver_settings.path = resolved_path;
      solver               = create_contact_solver(solver_settings);
      if (settings.log_solves)
        log << "  contact: " << solver->name() << " on the " << resolved_path
            << " path (" << path_why << ")" << std::endl;
    }



    template <int dim>
    PathCostInputs
    ContactStage<dim>::path_cost_inputs() const
    {
      PathCostInputs inputs;
      inputs.contact_unknowns = m * pair_list.size();
      // The unknowns the pair points move, per deformable body (the Schur
      // complement of the condensed path is formed on them).
      const unsigned int n_sides = obstacle ? 1u : 2u;
      for (unsigned int side = 0; side < n_sides; ++side)
        {
          std::vector<bool> touched(bodies[side]->n_dofs(), false);
          for (const auto &pair : pair_list)
            {
              const auto &op = side == 0 ? pair.op1 : pair.op2;
              for (unsigned int k = 0; k < op.weights.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  if (op.weights[k] != 0. &&
                      !bodies[side]->is_held(op.dofs[k][c]))
                    touched[op.dofs[k][c]] = true;
            }
          inputs.face_unknowns.push_back(
            std::count(touched.begin(), touched.end(), true));
        }
      inputs.factor_entries = settings.factor_entries;
      inputs.newton_iterations =
        PathCostConstants::measured().iterations_per_step *
        std::max(1u, settings.n_load_steps);
      return inputs;
    }



    template <int dim>
    const std::string &
    ContactStage<dim>::path() const
    {
      return resolved_path;
    }



    template <int dim>
    void
    ContactStage<dim>::set_coupled_factory(const CoupledFactory &factory)
    {
      coupled_factory = factory;
    }



    template <int dim>
    void
    ContactStage<dim>::prepare(TimerOutput &timer)
    {
      if (resolved_path == "full")
        couple(timer);
      else
        condense(timer);
    }



    template <int dim>
    void
    ContactStage<dim>::couple(TimerOutput &timer)
    {
      AssertThrow(coupled_factory,
                  ExcMessage("ContactStage::couple: no coupled-system "
                             "factory (set_coupled_factory())"));
      TimerOutput::Scope t(timer, "contact: coupled system");
      std::vector<const discretization::Body<dim> *> deformable;
      for (const auto &body : bodies)
        deformable.push_back(body.get());
      RigidModeColumns modes =
        rigid_mode_columns<dim>(pair_list, deformable, m, log);

      // Pairs whose points move with held unknowns only (and with no rigid
      // mode) carry no information; leave them out as condense() does.
      std::vector<unsigned int> keep;
      const double              max_g =
        modes.G.size() > 0 ? modes.G.cwiseAbs().maxCoeff() : 0.;
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          bool moves = false;
          for (unsigned int side = 0; side < (obstacle ? 1u : 2u); ++side)
            {
              const auto &op = side == 0 ? pair_list[i].op1 : pair_list[i].op2;
              for (unsigned int k = 0; k < op.weights.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  moves = moves || (op.weights[k] != 0. &&
                                    !bodies[side]->is_held(op.dofs[k][c]));
            }
          const double g_row =
            modes.G.cols() > 0 ? modes.G.row(m * i).cwiseAbs().maxCoeff() : 0.;
          if (moves || g_row > 1e-12 * max_g)
            keep.push_back(i);
        }
      condensed           = CondensedContact<dim>();
      condensed.n_dropped = pair_list.size() - keep.size();
      AssertThrow(!keep.empty(),
                  base::ExcInput(settings.context +
                                 ": every contact pair is held by supports on "
                                 "both sides; nothing can touch."));
      ContactProblem &problem = condensed.problem;
      problem.G.resize(m * keep.size(), modes.G.cols());
      for (unsigned int i = 0; i < keep.size(); ++i)
        {
          condensed.pairs.push_back(pair_list[keep[i]]);
          problem.G.middleRows(m * i, m) = modes.G.middleRows(m * keep[i], m);
        }
      condensed.alpha_modes              = modes.alpha_modes;
      condensed.rigid_mode_loads         = modes.loads;
      condensed.rigid_mode_history_loads = modes.history_loads;
      pair_list                          = condensed.pairs;
      problem.n_contacts                 = pair_list.size();
      problem.n_components               = m;
      problem.q = Eigen::VectorXd::Zero(m * pair_list.size());
      problem.mu.assign(pair_list.size(), settings.friction_coefficient);
      problem.name = settings.context;
      problem.b    = Eigen::VectorXd::Zero(modes.alpha_modes.size());
      coupled      = coupled_factory(pair_list, m, problem.G, bool(obstacle));
      problem.coupled = coupled;
      problem.check_consistency();

      log << "  contact: " << pair_list.size() << " pairs ("
          << (obstacle ? obstacle->kind() : std::string("two bodies")) << ", "
          << m * pair_list.size() << " contact unknowns"
          << (m == 1 ? ", frictionless: no tangential unknowns" : "") << ")"
          << std::endl;
      if (settings.log_solves)
        log << "  contact: coupled system of " << coupled->n_dofs()
            << " displacement and " << m * pair_list.size() + problem.n_alpha()
            << " contact unknowns, " << coupled->n_nonzeros()
            << " nonzeros in its Newton matrix" << std::endl;
      if (condensed.n_dropped > 0)
        log << "  contact: left out " << condensed.n_dropped
            << " pairs whose two points are both held by supports (zero "
               "flexibility, no information)"
            << std::endl;
      p                 = Eigen::VectorXd::Zero(problem.n_rows());
      alpha             = Eigen::VectorXd::Zero(problem.n_alpha());
      previous_external = Eigen::VectorXd::Zero(problem.n_rows());
      w                 = Eigen::VectorXd::Zero(coupled->n_dofs());
    }



    template <int dim>
    std::vector<discretization::PointOperator<dim>>
    ContactStage<dim>::contact_operators(const unsigned int b) const
    {
      std::vector<discretization::PointOperator<dim>> ops;
      for (const auto &pair : pair_list)
        ops.push_back(b == 0 ? pair.op1 : pair.op2);
      return ops;
    }



    template <int dim>
    void
    ContactStage<dim>::condense(TimerOutput &timer)
    {
      {
        TimerOutput::Scope t(timer, "contact: condensation");
        std::vector<const discretization::Body<dim> *> deformable;
        for (const auto &body : bodies)
          deformable.push_back(body.get());
        condensed = contact::condense<dim>(pair_list,
                                           deformable,
                                           m,
                                           settings.friction_coefficient,
                                           settings.context,
                                           log,
                                           settings.progress);
      }
      pair_list                     = condensed.pairs;
      const ContactProblem &problem = condensed.problem;
      log << "  contact: " << pair_list.size() << " pairs ("
          << (obstacle ? obstacle->kind() : std::string("two bodies")) << ", "
          << m * pair_list.size() << " contact unknowns"
          << (m == 1 ? ", frictionless: no tangential unknowns" : "") << ")"
          << std::endl;
      if (condensed.n_dropped > 0)
        log << "  contact: left out " << condensed.n_dropped
            << " pairs whose two points are both held by supports (zero "
               "flexibility, no information)"
            << std::endl;
      if (condensed.asymmetry > 1e-8)
        log << "  contact: warning: flexibility asymmetry "
            << condensed.asymmetry << std::endl;
      p                 = Eigen::VectorXd::Zero(problem.n_rows());
      alpha             = Eigen::VectorXd::Zero(problem.n_alpha());
      previous_external = Eigen::VectorXd::Zero(problem.n_rows());
    }



    template <int dim>
    Eigen::VectorXd
    ContactStage<dim>::relative_displacement(
      const std::vector<Vector<double>> &u) const
    {
      Eigen::VectorXd result(m * pair_list.size());
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          Tensor<1, dim> du = pair_list[i].op1.displacement(u[0]);
          if (!obstacle)
            du -= pair_list[i].op2.displacement(u[1]);
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
    std::pair<Eigen::VectorXd, Eigen::VectorXd>
    ContactStage<dim>::initial_guess() const
    {
      // Candidate 1, first step: no force, rigid modes placed so that the
      // closest pair just touches (with every pair open the alpha columns of
      // the Newton matrix vanish). Later steps: the previous step's forces
      // and rigid-mode amplitudes (warm start).
      const ContactProblem &problem = condensed.problem;
      const Eigen::VectorXd p0 =
        has_previous ? p : Eigen::VectorXd::Zero(problem.n_rows());
      const Eigen::VectorXd a0 = has_previous ? alpha :
                                 problem.n_alpha() > 0 ?
                                                touching_alpha(problem) :
                                                Eigen::VectorXd::Zero(0);

      // Candidate 2: a bilateral solve, W_cc p_c + G_c alpha = -q_c and
      // G_c^T p_c = b, over the pairs expected closed and sticking: in the
      // first step those that touch in the undeformed geometry, later those
      // closed at the end of the previous step. On flat matching surfaces
      // with zero gap every pair is at a tie of the min function, where the
      // first Newton matrix is a poor model, and after a load change the
      // warm start violates the equilibrium of floating bodies by the whole
      // change; this start is exact when the contact state does not change.
      // The better candidate by natural-map plus equilibrium residual is
      // used.
      std::vector<unsigned int> rows;
      // Directions held by supports on both sides (zero flexibility, no
      // rigid motion) carry no force and are left out of this start.
      const double max_diag = problem.W.diagonal().cwiseAbs().maxCoeff();
      const double max_g =
        (problem.G.size() > 0 ? problem.G.cwiseAbs().maxCoeff() : 0.);
      const std::vector<bool> closed = expected_closed();
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        if (closed[i])
          for (unsigned int s = 0; s < m; ++s)
            {
              const unsigned int r = m * i + s;
              const double       g =
                (problem.G.cols() > 0 ? problem.G.row(r).cwiseAbs().maxCoeff() :
                                        0.);
              if (problem.W(r, r) > 1e-12 * max_diag || g > 1e-12 * max_g)
                rows.push_back(r);
            }
      if (rows.empty())
        return {p0, a0};
      const unsigned int nr = rows.size(), na = problem.n_alpha();
      Eigen::MatrixXd    A = Eigen::MatrixXd::Zero(nr + na, nr + na);
      Eigen::VectorXd    rhs(nr + na);
      for (unsigned int i = 0; i < nr; ++i)
        {
          for (unsigned int j = 0; j < nr; ++j)
            A(i, j) = problem.W(rows[i], rows[j]);
          for (unsigned int k = 0; k < na; ++k)
            {
              A(i, nr + k) = problem.G(rows[i], k);
              A(nr + k, i) = problem.G(rows[i], k);
            }
          rhs(i) = -problem.q(rows[i]);
        }
      for (unsigned int k = 0; k < na; ++k)
        rhs(nr + k) = problem.b(k);
      // Forces that load held unknowns only, on both sides, move nothing:
      // they make A singular, and their share of p is not determined (point
      // pairs show them as zero rows, left out above; weighted-gap pairs,
      // whose operators spread over a face's mass-matrix row, mix them into
      // several pairs). The minimum-norm solution leaves them out, so that
      // no force goes into the supports without need; a regular A is
      // solved as before.
      Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
      lu.setThreshold(1e-12);
      Eigen::VectorXd x;
      if (lu.rank() < A.rows())
        {
          Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
          cod.setThreshold(1e-12);
          x = cod.solve(rhs);
        }
      else
        x = lu.solve(rhs);
      if (!x.allFinite())
        return {p0, a0};
      Eigen::VectorXd p1 = Eigen::VectorXd::Zero(problem.n_rows());
      for (unsigned int i = 0; i < nr; ++i)
        p1(rows[i]) = x(i);
      const Eigen::VectorXd a1 = x.tail(na);

      // Natural-map residual plus the equilibrium of floating bodies (the
      // natural map alone is zero for p = 0 with every pair open).
      const auto error = [&](const Eigen::VectorXd &pp,
                             const Eigen::VectorXd &aa) {
        double e =
          relative_natural_map_error(problem,
                                     pp,
                                     problem.relative_displacement(pp, aa));
        if (na > 0)
          e += (problem.G.transpose() * pp - problem.b).norm() /
               std::max(problem.b.norm(), 1e-300);
        return e;
      };
      if (error(p1, a1) < error(p0, a0))
        return {p1, a1};
      return {p0, a0};
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
    std::tuple<Eigen::VectorXd, Eigen::VectorXd, Eigen::VectorXd>
    ContactStage<dim>::initial_guess_full() const
    {
      // As initial_guess(), on the coupled system: the warm start, or the
      // bilateral solve with the expected-closed pairs glued (u_c = 0) and
      // the others free of force.
      const ContactProblem &problem = condensed.problem;
      const unsigned int    na      = problem.n_alpha();
      const Eigen::VectorXd p0 =
        has_previous ? p : Eigen::VectorXd::Zero(problem.n_rows());
      const Eigen::VectorXd a0 = has_previous ? alpha :
                                 na > 0       ? touching_alpha(problem) :
                                                Eigen::VectorXd::Zero(0);
      const Eigen::VectorXd w0 =
        has_previous ? w : Eigen::VectorXd::Zero(coupled->n_dofs());

      const std::vector<bool> closed = expected_closed();
      if (std::find(closed.begin(), closed.end(), true) == closed.end())
        return {p0, a0, w0};
      const Eigen::VectorXd       &k = coupled->pair_stiffness();
      std::vector<Eigen::Matrix3d> A(pair_list.size(), Eigen::Matrix3d::Zero()),
        B(pair_list.size(), Eigen::Matrix3d::Zero());
      Eigen::VectorXd r_p = Eigen::VectorXd::Zero(problem.n_rows());
      // Directions held by supports on both sides carry no force, as in the
      // solver: a glued one would be a zero row.
      const std::vector<bool> held = held_pair_directions(problem);
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        for (unsigned int s = 0; s < m; ++s)
          if (closed[i] && !held[m * i + s])
            {
              A[i](s, s)     = k[i];
              r_p[m * i + s] = -k[i] * problem.q[m * i + s];
            }
          else
            B[i](s, s) = 1.;
      Eigen::VectorXd w1, p1, a1;
      std::string     why;
      coupled->factorize(A, B);
      if (!coupled->solve(Eigen::VectorXd::Zero(coupled->n_dofs()),
                          r_p,
                          na > 0 ? Eigen::VectorXd(problem.b) :
                                   Eigen::VectorXd(),
                          w1,
                          p1,
                          a1,
                          why) ||
          !p1.allFinite() || !w1.allFinite())
        return {p0, a0, w0};

      const auto error = [&](const Eigen::VectorXd &pp,
                             const Eigen::VectorXd &aa,
                             const Eigen::VectorXd &ww) {
        Eigen::VectorXd u = coupled->apply_C(ww) + problem.q;
        if (na > 0)
          u += problem.G * aa;
        double e = relative_natural_map_error(problem, pp, u);
        if (na > 0)
          e += (problem.G.transpose() * pp - problem.b).norm() /
               std::max(problem.b.norm(), 1e-300);
        return e;
      };
      if (error(p1, a1, w1) < error(p0, a0, w0))
        return {p1, a1, w1};
      return {p0, a0, w0};
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
      ContactProblem       &problem = condensed.problem;
      const bool            full    = static_cast<bool>(coupled);
      const Eigen::VectorXd U       = relative_displacement(u);
      // What the previous step's contact forces contribute to the pair
      // displacements (subtracted from the tangential increments).
      Eigen::VectorXd carry =
        full ? coupled->apply_C(w) : Eigen::VectorXd(problem.W * p);
      if (problem.n_alpha() > 0)
        carry += problem.G * alpha;

      // Normal rows: total relative displacement, gap included. Tangential
      // rows: increments of this step (friction is incremental).
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          problem.q(m * i) = pair_list[i].gap + U(m * i);
          for (unsigned int s = 1; s < m; ++s)
            problem.q(m * i + s) =
              U(m * i + s) - previous_external(m * i + s) - carry(m * i + s);
        }
      // The loads floating bodies must balance: every history at its
      // factor.
      problem.b = Eigen::VectorXd::Zero(condensed.rigid_mode_loads.size());
      for (unsigned int h = 0;
           h < factors.size() && h < condensed.rigid_mode_history_loads.cols();
           ++h)
        problem.b -= factors[h] * condensed.rigid_mode_history_loads.col(h);

      problem.p_previous = p;

      ContactSolverResult solution;
      {
        TimerOutput::Scope t(timer,
                             full ? "contact: full-system solve" :
                                    "contact: B-Newton");
        if (full)
          {
            const auto [p0, alpha0, w0] = initial_guess_full();
            problem.w0                  = w0;
            solution                    = solver->solve(problem, p0, alpha0);
          }
        else
          {
            const auto [p0, alpha0] = initial_guess();
            solution                = solver->solve(problem, p0, alpha0);
          }
      }
      if (settings.log_solves)
        log << "  " << (solver->name() == "bde" ? "B-Newton" : solver->name())
            << (full ? " (full system)" : "") << ": " << solution.summary()
            << std::endl;
      if (full && solver->name() == "penalty")
        log << "  maximum penetration " << std::setprecision(6)
            << solution.max_penetration << std::endl;

      StepResult<dim> result;
      result.converged = solution.converged;
      result.diagnosis = solution.diagnosis;
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
              where << (k > 0 ? "," : "") << " pair " << i << " at (";
              for (unsigned int d = 0; d < dim; ++d)
                where << (d > 0 ? ", " : "") << pair_list[i].x1[d];
              where << ")";
            }
          result.diagnosis += where.str();
        }
      result.iterations      = solution.iterations;
      result.residual        = solution.residual;
      result.n_open          = solution.n_open;
      result.n_stick         = solution.n_stick;
      result.n_slip          = solution.n_slip;
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
      if (solver->name() == "penalty")
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

      p                 = solution.p;
      alpha             = solution.alpha;
      u_rel             = solution.u;
      status            = solution.status;
      previous_external = U;
      has_previous      = true;
      if (full)
        w = solution.w;

      // Contact forces back to the fields.
      {
        TimerOutput::Scope          t(timer, "contact: fields");
        std::vector<Vector<double>> loads;
        for (const auto &body : bodies)
          loads.emplace_back(body->n_dofs());
        for (unsigned int i = 0; i < pair_list.size(); ++i)
          {
            const Tensor<1, dim> f = global_force(i, p);
            result.contact_force += f;
            pair_list[i].op1.distribute(f, loads[0]);
            if (!obstacle)
              pair_list[i].op2.distribute(-f, loads[1]);
          }
        // The bodies' response: solved already on the full path, one solve
        // per body on the condensed one.
        unsigned int offset = 0;
        for (unsigned int b = 0; b < bodies.size(); ++b)
          {
            if (full)
              for (unsigned int i = 0; i < bodies[b]->n_dofs(); ++i)
                u[b][i] += w[offset + i];
            else
              {
                std::vector<Vector<double>> column(1, loads[b]);
                bodies[b]->solve(column);
                u[b] += column[0];
              }
            offset += bodies[b]->n_dofs();
          }
        for (unsigned int a = 0; a < condensed.alpha_modes.size(); ++a)
          {
            const auto [b, k] = condensed.alpha_modes[a];
            u[b].add(alpha(a), bodies[b]->free_rigid_modes()[k]);
          }
        log << "  total contact force on Body 1: " << std::setprecision(6)
            << result.contact_force << std::endl;
      }
      return result;
    }



    template <int dim>
    std::vector<PairState<dim>>
    ContactStage<dim>::pair_states() const
    {
      std::vector<PairState<dim>> states;
      if (status.empty())
        return states;
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          PairState<dim> s;
          s.location = pair_list[i].x1;
          s.area     = pair_list[i].area;
          for (unsigned int k = 0; k < m; ++k)
            {
              s.force_local.push_back(p(m * i + k));
              s.displacement_local.push_back(u_rel(m * i + k));
            }
          s.force = global_force(i, p);
          for (unsigned int k = 1; k < m; ++k)
            s.slip += u_rel(m * i + k) * pair_list[i].frame[k];
          s.status = status[i];
          states.push_back(s);
        }
      return states;
    }



    template <int dim>
    ContactSummary
    ContactStage<dim>::summary() const
    {
      ContactSummary s;
      for (const auto &pair : pair_list)
        s.initial_gaps = s.initial_gaps || pair.gap > 0.;
      s.n_pairs    = pair_list.size();
      s.n_unknowns = condensed.problem.n_rows() + condensed.problem.n_alpha();
      s.friction   = (m > 1);
      s.rigid_obstacle              = static_cast<bool>(obstacle);
      s.floating_rigid_modes        = condensed.alpha_modes.size();
      s.pairs_left_out              = condensed.n_dropped;
      s.algorithm                   = settings.solver.algorithm;
      s.path                        = resolved_path;
      s.path_reason                 = path_why;
      s.estimated_condensed_seconds = estimated_condensed_seconds;
      s.estimated_full_seconds      = estimated_full_seconds;
      s.cost_inputs                 = path_cost_inputs();
      s.coupled_nonzeros            = coupled ? coupled->n_nonzeros() : 0.;
      return s;
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
          const Tensor<1, dim> f = global_force(i, p);
          if (b == 0)
            pair_list[i].op1.distribute(f, load);
          else
            pair_list[i].op2.distribute(-f, load);
        }
      return load;
    }



    template class ContactStage<2>;
    template class ContactStage<3>;
  } // namespace contact
} // namespace igabde
