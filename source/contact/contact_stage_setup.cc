#include <igabde/base/nearest_points.h>
#include <igabde/base/utilities.h>

#include <igabde/contact/contact_stage.h>

#include <algorithm>
#include <iomanip>
#include <numeric>
#include <sstream>

// The contact stage's set-up: the pairs of every interaction, the path,
// the bodies' factorisations as the path asks, the contact problem.

namespace igabde
{
  namespace contact
  {
    template <int dim>
    void
    ContactStage<dim>::build_pairs(TimerOutput &timer)
    {
      m = 1;
      for (const ContactInteraction &c : settings.interactions)
        if (c.friction_coefficient > 0.)
          m = dim;
      TimerOutput::Scope t(timer, "contact: pairs");
      // The pairs of every interaction, in order.
      pair_list.clear();
      master_faces.clear();
      std::vector<std::string> repairs;
      for (unsigned int k = 0; k < settings.interactions.size(); ++k)
        {
          const ContactInteraction &c          = settings.interactions[k];
          const bool                deformable = c.master_body < bodies.size();
          master_faces.push_back(
            deformable ? std::make_unique<BodyFace<dim>>(*bodies[c.master_body],
                                                         c.master_faces) :
                         nullptr);
          const ContactSurface<dim> &master =
            deformable ?
              *master_faces.back() :
              static_cast<const ContactSurface<dim> &>(*obstacles[c.obstacle]);
          const std::string context = settings.interactions.size() == 1 ?
                                        settings.context :
                                        settings.context + " (" + c.name + ")";
          std::vector<ContactPair<dim>> pairs;
          try
            {
              pairs = pairings[k]->make_pairs(*bodies[c.slave_body],
                                              c.slave_faces,
                                              master,
                                              context);
            }
          catch (const ExcNonPositiveTributaryArea &e)
            {
              // The stated repair: point pairs cannot carry a pressure
              // where the collocation gives a point no area; the weighted
              // gap integrates over the face (areas int N_j dGamma >= 0)
              // and transmits a uniform pressure exactly.
              const std::string note =
                c.name + "/Pairing = " + to_string(c.pairing) + ": " +
                e.what() +
                "; this interaction is paired by the weighted gap instead";
              repairs.push_back(note);
              pairings[k] = create_pairing_strategy<dim>(Pairing::weighted_gap);
              pairings[k]->set_search_distance(c.search_distance);
              pairs = pairings[k]->make_pairs(*bodies[c.slave_body],
                                              c.slave_faces,
                                              master,
                                              context);
            }
          append_pairs(std::move(pairs), k, pair_list);
        }
      cost_inputs    = compute_path_cost_inputs();
      setup_warnings = repairs;
      // More contact unknowns than the face unknowns the pairs move: the
      // flexibility's rank is at most the latter, so the contact rows are
      // redundant and the pair forces not unique (their resultant is). A
      // sufficient condition only (Gauss placement: p + 1 pairs a span).
      // Directions held on both sides are zero rows the solvers leave
      // out, and do not count.
      const double face_unknowns =
        std::accumulate(cost_inputs.face_unknowns.begin(),
                        cost_inputs.face_unknowns.end(),
                        0.);
      const unsigned int moving = n_moving_contact_unknowns();
      if (moving > face_unknowns + 0.5)
        setup_warnings.push_back(
          std::to_string(moving) + " contact unknowns on " +
          std::to_string(static_cast<long>(face_unknowns)) +
          " face unknowns: the contact rows are redundant, so the pair "
          "forces are not unique (their resultant is) and the pair "
          "pressures may oscillate; Contact/Pair placement = greville "
          "gives one pair per face control point");

      // The path: penalty methods solve the full system (as ANSYS does);
      // the BDE takes the path asked for, or under auto the one the cost
      // model (path_cost.h) estimates cheaper.
      Path path = settings.solver.path;
      if (settings.solver.algorithm != Algorithm::bde)
        {
          path = Path::full;
          path_why =
            to_string(settings.solver.algorithm) + " solves the full system";
        }
      else if (path == Path::automatic &&
               std::any_of(bodies.begin(), bodies.end(), [](const auto &b) {
                 return !b->held_rigid_mode_names().empty();
               }))
        {
          // The coupled system has no rows for a held rotation's
          // constraint; the condensed path projects it in every solve.
          path     = Path::condensed;
          path_why = "a body holds a rotation (Hold rotation), which only "
                     "the condensed path models";
        }
      else if (path == Path::automatic && settings.finite_sliding)
        {
          path     = Path::full;
          path_why = "finite sliding (Contact/Sliding = finite) forms the "
                     "pairs at every Newton iterate, which only the full "
                     "path follows";
        }
      else if (path == Path::automatic && finite_strain())
        {
          // The condensation would take a constant stiffness.
          path     = Path::full;
          path_why = "a body is at finite strain (Kinematics = finite), "
                     "whose tangent only the full path follows";
        }
      else if (path == Path::automatic && !settings.memory_path_reason.empty())
        {
          path     = Path::full;
          path_why = settings.memory_path_reason;
        }
      else if (path == Path::automatic)
        {
          const PathCostEstimate e =
            estimate_path_costs(cost_inputs, PathCostConstants::measured());
          path                        = e.path;
          path_why                    = e.reason;
          estimated_condensed_seconds = e.condensed_seconds;
          estimated_full_seconds      = e.full_seconds;
        }
      else
        path_why = "Contact/Path = " + to_string(path);
      resolved_path = path;
      // The names of the phases in the timing table and the log.
      const bool full = (path == Path::full);
      prepare_section =
        full ? "contact: coupled system" : "contact: condensation";
      solver_section = full ? "full-system solve" : "B-Newton";
      solver_label   = (settings.solver.algorithm == Algorithm::bde ?
                          std::string("B-Newton") :
                          to_string(settings.solver.algorithm)) +
                     (full ? " (full system)" : "");

      std::vector<const discretization::Body<dim> *> deformable;
      for (const auto &body : bodies)
        deformable.push_back(body.get());
      if (full)
        contact_path = std::make_unique<CoupledPath<dim>>(deformable,
                                                          m,
                                                          coupled_factory,
                                                          settings.context,
                                                          log);
      else
        contact_path =
          std::make_unique<CondensedPath<dim>>(deformable,
                                               m,
                                               settings.schur_condensation,
                                               settings.context,
                                               log,
                                               settings.progress);
      if (settings.finite_sliding)
        {
          FiniteSliding<dim> sliding;
          sliding.pairs_at = [this](const Eigen::VectorXd &w) {
            return pairs_at(w);
          };
          sliding.pairs_of = [this](const Eigen::VectorXd           &w,
                                    const std::vector<unsigned int> &indices) {
            return pairs_of(w, indices);
          };
          sliding.linearization_of =
            [this](const Eigen::VectorXd               &w,
                   const std::vector<unsigned int>     &indices,
                   std::vector<PairLinearization<dim>> &result) {
              return linearization_of(w, indices, result);
            };
          sliding.tangent = settings.sliding_tangent;
          contact_path->set_finite_sliding(sliding);
        }
      // The full path's merit adds the displacement equations, which the
      // first Newton step satisfies to rounding: its line search is
      // monotone (the non-monotone rule lets |H| grow for steps that the
      // coupled system's rounding then pays for).
      ContactSolverSettings solver_settings = settings.solver;
      if (full)
        solver_settings.bnewton.nonmonotone_memory = 1;
      solver = create_contact_solver(solver_settings);
      if (settings.log_solves)
        log << "  contact: " << solver->name() << " on the "
            << to_string(resolved_path) << " path (" << path_why << ")"
            << std::endl;
    }



    template <int dim>
    void
    ContactStage<dim>::append_pairs(std::vector<ContactPair<dim>> &&pairs,
                                    const unsigned int              k,
                                    std::vector<ContactPair<dim>>  &list) const
    {
      const ContactInteraction &c          = settings.interactions[k];
      const bool                deformable = c.master_body < bodies.size();
      for (ContactPair<dim> &pair : pairs)
        {
          pair.slave_body = c.slave_body;
          pair.master_body =
            deformable ? c.master_body : numbers::invalid_unsigned_int;
          pair.obstacle =
            deformable ? numbers::invalid_unsigned_int : c.obstacle;
          pair.interaction          = k;
          pair.friction_coefficient = c.friction_coefficient;
          list.push_back(std::move(pair));
        }
    }



    template <int dim>
    PathCostInputs
    ContactStage<dim>::compute_path_cost_inputs() const
    {
      PathCostInputs inputs;
      inputs.contact_unknowns = m * pair_list.size();
      // The unknowns the pair points move, per deformable body that a pair
      // touches (the Schur complement of the condensed path is formed on
      // them).
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          std::vector<bool> touched(bodies[b]->n_dofs(), false);
          bool              any = false;
          for (const auto &pair : pair_list)
            {
              double      sign = 0.;
              const auto *op   = pair.operator_on(b, sign);
              if (op == nullptr)
                continue;
              any = true;
              for (unsigned int k = 0; k < op->weights.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  if (op->weights[k] != 0. &&
                      !bodies[b]->is_held(op->dofs[k][c]))
                    touched[op->dofs[k][c]] = true;
            }
          if (any)
            inputs.face_unknowns.push_back(
              std::count(touched.begin(), touched.end(), true));
        }
      inputs.factor_entries = settings.factor_entries;
      inputs.dimension      = dim;
      inputs.newton_iterations =
        PathCostConstants::measured().iterations_per_step *
        std::max(1u, settings.n_load_steps);
      return inputs;
    }



    template <int dim>
    unsigned int
    ContactStage<dim>::n_moving_contact_unknowns() const
    {
      unsigned int moving = 0;
      for (const auto &pair : pair_list)
        for (unsigned int k = 0; k < m; ++k)
          {
            bool moves = false;
            for (const unsigned int b : {pair.slave_body, pair.master_body})
              {
                double      sign = 0.;
                const auto *op =
                  b < bodies.size() ? pair.operator_on(b, sign) : nullptr;
                if (op == nullptr || moves)
                  continue;
                for (unsigned int j = 0; j < op->weights.size() && !moves; ++j)
                  for (unsigned int c = 0; c < dim; ++c)
                    if (op->weights[j] != 0. &&
                        std::abs(pair.frame[k][c]) > 1e-12 &&
                        !bodies[b]->is_held(op->dofs[j][c]))
                      moves = true;
              }
            moving += moves;
          }
      return moving;
    }



    template <int dim>
    Path
    ContactStage<dim>::path() const
    {
      return resolved_path;
    }



    template <int dim>
    std::vector<base::MemoryItem>
    ContactStage<dim>::memory_record() const
    {
      const auto pair_bytes = [](const std::vector<ContactPair<dim>> &pairs) {
        double bytes = base::vector_bytes(pairs);
        for (const auto &pair : pairs)
          for (const auto *op : {&pair.op1, &pair.op2})
            bytes +=
              base::vector_bytes(op->weights) + base::vector_bytes(op->dofs);
        return bytes;
      };
      std::vector<base::MemoryItem> items;
      items.push_back({"contact: pairs",
                       pair_bytes(pair_list) + pair_bytes(contact.pairs) +
                         base::vector_bytes(pair_spacing),
                       false});
      const ContactProblem &problem = contact.problem;
      items.push_back({"contact: condensed problem (W, rigid-mode columns)",
                       double(problem.W.size() + problem.G.size() +
                              contact.alpha_basis.size() +
                              contact.rigid_mode_history_loads.size()) *
                         sizeof(double),
                       false});
      if (contact_path)
        for (auto &item : contact_path->op().memory_record())
          items.push_back(std::move(item));
      return items;
    }



    template <int dim>
    void
    ContactStage<dim>::setup(
      TimerOutput &timer,
      const std::function<void(const discretization::FactorizationReport &)>
        &factorized)
    {
      build_pairs(timer);
      std::vector<discretization::FactorizationRequest<dim>> requests;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        requests.push_back(contact_path->factorization_request(b, pair_list));
      const discretization::FactorizationReport report =
        discretization::factorize_bodies(bodies,
                                         requests,
                                         timer,
                                         bodies[0]->parallel_layout().world);
      if (factorized)
        factorized(report);
      Timer clock;
      prepare(timer);
      if (settings.progress)
        log << "  [progress] "
            << (resolved_path == Path::full ? "coupled system" : "condensation")
            << ", " << std::setprecision(3) << clock.wall_time() << " s"
            << std::setprecision(6) << std::endl;
    }



    template <int dim>
    void
    ContactStage<dim>::prepare(TimerOutput &timer)
    {
      Assert(contact_path, ExcMessage("build_pairs() first"));
      {
        TimerOutput::Scope t(timer, prepare_section);
        contact_path->prepare(pair_list, contact);
      }
      pair_list = contact.pairs;
      {
        std::vector<Point<dim>> points;
        for (const auto &pair : pair_list)
          points.push_back(pair.x1);
        const base::NearestPoints<dim> nearest(std::move(points));
        pair_spacing.resize(pair_list.size());
        for (unsigned int i = 0; i < pair_list.size(); ++i)
          pair_spacing[i] = nearest.spacing(i);
      }
      const ContactProblem &problem        = contact.problem;
      const unsigned int    n_interactions = settings.interactions.size();
      {
        std::string what;
        if (n_interactions == 1)
          {
            const ContactInteraction &c = settings.interactions[0];
            what                        = c.master_body < bodies.size() ?
                                            "two bodies" :
                                            obstacles[c.obstacle]->kind();
          }
        else
          what = std::to_string(bodies.size()) + " bodies" +
                 (obstacles.empty() ?
                    std::string() :
                    " and " + std::to_string(obstacles.size()) +
                      (obstacles.size() == 1 ? " obstacle" : " obstacles")) +
                 " in " + std::to_string(n_interactions) + " interactions";
        log << "  contact: " << pair_list.size() << " pairs (" << what << ", "
            << m * pair_list.size() << " contact unknowns"
            << (m == 1 ? ", frictionless: no tangential unknowns" : "") << ")"
            << std::endl;
        if (n_interactions > 1)
          {
            std::vector<unsigned int> count(n_interactions, 0);
            for (const auto &pair : pair_list)
              ++count[pair.interaction];
            for (unsigned int k = 0; k < n_interactions; ++k)
              {
                const ContactInteraction &c = settings.interactions[k];
                log << "  contact: " << c.name << ": " << count[k] << " pairs, "
                    << body_label(c.slave_body) << " on "
                    << (c.master_body < bodies.size() ?
                          body_label(c.master_body) :
                          obstacles[c.obstacle]->description())
                    << std::endl;
              }
          }
      }
      const std::string formed = contact_path->description(contact);
      if (settings.log_solves && !formed.empty())
        log << "  contact: " << formed << std::endl;
      for (unsigned int k = 0; k < n_interactions; ++k)
        {
          const PairingExclusions<dim> &e = pairings[k]->exclusions();
          if (e.n_left_out() == 0)
            continue;
          log << "  contact: "
              << (n_interactions > 1 ? settings.interactions[k].name + ": " :
                                       std::string())
              << "left out " << e.n_left_out() << " of " << e.candidates
              << " slave "
              << (e.quadrature_points ? "quadrature points" : "points")
              << " at set-up:";
          const auto where = [&](const Point<dim> &x) {
            std::ostringstream o;
            o << " (the first at (" << x << "))";
            return o.str();
          };
          std::string separator = " ";
          if (e.not_facing > 0)
            {
              log << separator << e.not_facing << " turn away from the master"
                  << where(e.first_not_facing);
              separator = ", ";
            }
          if (e.outside > 0)
            {
              log << separator << e.outside << " lie beyond its extent"
                  << where(e.first_outside);
              separator = ", ";
            }
          if (e.beyond > 0)
            {
              log << separator << e.beyond << " lie beyond the search distance "
                  << e.search_distance << where(e.first_beyond);
              separator = ", ";
            }
          if (e.degenerate > 0)
            {
              log << separator << e.degenerate
                  << " have a degenerate normal (a collapsed edge)"
                  << where(e.first_degenerate);
              separator = ", ";
            }
          if (e.unprojected > 0)
            log << separator << e.unprojected
                << " whose closest-point projection did not settle"
                << where(e.first_unprojected);
          log << std::endl;
        }
      if (contact.n_dropped > 0)
        log << "  contact: left out " << contact.n_dropped
            << " pairs whose two points are both held by supports (zero "
               "flexibility, no information)"
            << std::endl;
      if (contact.asymmetry > 1e-8)
        log << "  contact: warning: flexibility asymmetry " << contact.asymmetry
            << std::endl;
      for (const std::string &w : setup_warnings)
        log << "  warning: " << w << std::endl;
      x.p               = Eigen::VectorXd::Zero(problem.n_rows());
      x.alpha           = Eigen::VectorXd::Zero(problem.n_alpha());
      x.w               = Eigen::VectorXd::Zero(contact_path->op().n_dofs());
      previous_external = Eigen::VectorXd::Zero(problem.n_rows());
    }


    template void
    ContactStage<2>::build_pairs(TimerOutput &);
    template void
    ContactStage<2>::append_pairs(std::vector<ContactPair<2>> &&,
                                  const unsigned int,
                                  std::vector<ContactPair<2>> &) const;
    template void
    ContactStage<3>::append_pairs(std::vector<ContactPair<3>> &&,
                                  const unsigned int,
                                  std::vector<ContactPair<3>> &) const;
    template PathCostInputs
    ContactStage<2>::compute_path_cost_inputs() const;
    template unsigned int
    ContactStage<2>::n_moving_contact_unknowns() const;
    template Path
    ContactStage<2>::path() const;
    template std::vector<base::MemoryItem>
    ContactStage<2>::memory_record() const;
    template void
    ContactStage<2>::setup(
      TimerOutput &,
      const std::function<void(const discretization::FactorizationReport &)> &);
    template void
    ContactStage<2>::prepare(TimerOutput &);
    template void
    ContactStage<3>::build_pairs(TimerOutput &);
    template PathCostInputs
    ContactStage<3>::compute_path_cost_inputs() const;
    template unsigned int
    ContactStage<3>::n_moving_contact_unknowns() const;
    template Path
    ContactStage<3>::path() const;
    template std::vector<base::MemoryItem>
    ContactStage<3>::memory_record() const;
    template void
    ContactStage<3>::setup(
      TimerOutput &,
      const std::function<void(const discretization::FactorizationReport &)> &);
    template void
    ContactStage<3>::prepare(TimerOutput &);
  } // namespace contact
} // namespace igabde
