#include <igabde/contact/newton_driver.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <iostream>
#include <limits>

namespace igabde
{
  namespace contact
  {
    namespace
    {
      using Vec = Eigen::VectorXd;

      /// "pairs 3, 17, 40" (at most eight named, then "+N more").
      std::string
      pair_list_text(const std::vector<unsigned int> &pairs)
      {
        std::string text = pairs.size() == 1 ? "pair " : "pairs ";
        for (unsigned int k = 0; k < pairs.size() && k < 8; ++k)
          text += (k > 0 ? ", " : "") + std::to_string(pairs[k]);
        if (pairs.size() > 8)
          text += " (+" + std::to_string(pairs.size() - 8) + " more)";
        return text;
      }



      /// The piece of each pair (status and closed normal), for comparing
      /// active sets between iterations.
      std::vector<int>
      active_set(const NewtonBlocks &pieces)
      {
        std::vector<int> set;
        set.reserve(pieces.size());
        for (const PairPiece &piece : pieces)
          set.push_back(2 * static_cast<int>(piece.status) +
                        (piece.closed ? 1 : 0));
        return set;
      }



      /**
       * The number of distinct active sets among the last @p w of @p sets
       * when they cycle: at least two, each revisited on average (at most
       * w / 2 of them); 0 otherwise.
       */
      unsigned int
      cycle_length(const std::vector<std::vector<int>> &sets,
                   const unsigned int                   w)
      {
        std::vector<std::vector<int>> distinct(sets.end() - w, sets.end());
        std::sort(distinct.begin(), distinct.end());
        distinct.erase(std::unique(distinct.begin(), distinct.end()),
                       distinct.end());
        return distinct.size() >= 2 && 2 * distinct.size() <= w ?
                 distinct.size() :
                 0;
      }



      /**
       * What a failed phase involves, for its diagnosis: pairs with
       * non-finite forces or residuals; else, if the last active sets of
       * the phase repeat (fewer distinct sets than half the window), a cycle
       * and the pairs whose piece changes in it; else the three pairs with
       * the largest residual.
       */
      std::string
      describe_failure(const std::vector<std::vector<int>> &sets,
                       const unsigned int                   window,
                       const Vec                           &p,
                       const Vec                           &H,
                       const unsigned int                   n_contacts,
                       const unsigned int                   d,
                       std::vector<unsigned int>           &involved)
      {
        involved.clear();
        for (unsigned int c = 0; c < n_contacts; ++c)
          if (!p.segment(c * d, d).allFinite() ||
              (H.size() >= (c + 1) * d && !H.segment(c * d, d).allFinite()))
            involved.push_back(c);
        if (!involved.empty())
          return "; non-finite at " + pair_list_text(involved);

        const unsigned int w =
          std::min<unsigned int>(window,
                                 static_cast<unsigned int>(sets.size()));
        if (w >= 4)
          {
            if (const unsigned int n_distinct = cycle_length(sets, w);
                n_distinct > 0)
              {
                const std::vector<std::vector<int>> last(sets.end() - w,
                                                         sets.end());
                for (unsigned int c = 0; c < n_contacts; ++c)
                  for (const auto &set : last)
                    if (c < set.size() && set[c] != last.front()[c])
                      {
                        involved.push_back(c);
                        break;
                      }
                return "; cycling between " + std::to_string(n_distinct) +
                       " active sets in the last " + std::to_string(w) +
                       " iterations, changing the state of " +
                       pair_list_text(involved);
              }
          }
        if (H.size() < n_contacts * d || n_contacts == 0)
          return "";
        std::vector<unsigned int> order(n_contacts);
        for (unsigned int c = 0; c < n_contacts; ++c)
          order[c] = c;
        const unsigned int k = std::min(3u, n_contacts);
        std::partial_sort(order.begin(),
                          order.begin() + k,
                          order.end(),
                          [&](const unsigned int a, const unsigned int b) {
                            return H.segment(a * d, d).norm() >
                                   H.segment(b * d, d).norm();
                          });
        involved.assign(order.begin(), order.begin() + k);
        return "; largest residual at " + pair_list_text(involved);
      }



      double
      squared_norm(const ContactIterate &v)
      {
        return v.p.squaredNorm() + v.alpha.squaredNorm() + v.w.squaredNorm();
      }



      double
      dot(const ContactIterate &a, const ContactIterate &b)
      {
        return a.p.dot(b.p) + a.alpha.dot(b.alpha) +
               (a.w.size() > 0 ? a.w.dot(b.w) : 0.);
      }



      // x + t d
      ContactIterate
      axpy(const ContactIterate &x, const double t, const ContactIterate &d)
      {
        ContactIterate y;
        y.p     = x.p + t * d.p;
        y.alpha = x.alpha + t * d.alpha;
        y.w     = x.w.size() > 0 ? Vec(x.w + t * d.w) : Vec();
        return y;
      }



      bool
      all_finite(const ContactIterate &x)
      {
        return x.p.allFinite() && x.alpha.allFinite() && x.w.allFinite();
      }



      // The accuracy of an iterative solve of the Newton system (an
      // inexact Newton method, Eisenstat and Walker's forcing term
      // eta = c |F_k| / |F_0|): the linear residual at most eta times the
      // Newton residual |F_k|, with eta = 1e-2 min(1, |F_k| / |F_0|) and
      // not below 1e-12. Far from the solution a rough direction is
      // enough (the pair states still change); near it eta falls with the
      // residual, so the Newton residual falls as |F_k|^2 / |F_0| per
      // iteration once the states are settled (1 -> 1e-2 -> 1e-6 ->
      // 1e-14), the direct path's answer to the same stopping test.
      double
      krylov_tolerance(const double norm, const double first_norm)
      {
        const double ratio = first_norm > 0. ? norm / first_norm : 1.;
        return std::max(1e-12, 1e-2 * std::min(1., ratio));
      }
    } // namespace



    // ------------------------------------------------------------------
    // The driver

    bool
    held_pair_directions(const ContactData     &data,
                         const ContactOperator &op,
                         std::vector<bool>     &held)
    {
      const unsigned int d   = data.n_components;
      bool               any = false;
      held.assign(data.n_rows(), false);
      for (unsigned int row = 0; row < data.n_rows(); ++row)
        {
          held[row] = row % d != 0 && op.pair_row_is_held(row) &&
                      (data.n_alpha() == 0 || data.G.row(row).isZero());
          any = any || held[row];
        }
      return any;
    }



    void
    count_status(ContactSolverResult &result)
    {
      result.n_open = result.n_stick = result.n_slip = result.n_closed = 0;
      for (const ContactStatus s : result.status)
        ++(s == ContactStatus::open  ? result.n_open :
           s == ContactStatus::stick ? result.n_stick :
           s == ContactStatus::slip  ? result.n_slip :
                                       result.n_closed);
    }



    NewtonDriver::NewtonDriver(const ContactData     &original,
                               ContactOperator       &op,
                               const BNewtonSettings &settings,
                               ContactSolverResult   &result,
                               NewtonWorkspace       *workspace)
      : own(workspace ? std::nullopt : std::make_optional<NewtonWorkspace>())
      , op(op)
      , settings(settings)
      , result(result)
      , start(std::chrono::steady_clock::now())
      , ws(workspace ? *workspace : *own)
      , held(ws.held)
      , any_held(held_pair_directions(original, op, held))
      , best_x(ws.best_x)
      , converged_x(ws.converged_x)
    {
      // What the buffers hold from an earlier solve is storage only.
      ws.accepted.law = nullptr;
    }



    std::ostream &
    NewtonDriver::log() const
    {
      return settings.log_stream ? *settings.log_stream : std::cout;
    }



    ContactIterate
    NewtonDriver::finish(const ContactData    &data,
                         const PairLawModel   &law,
                         const ContactIterate &x,
                         const bool            measures) const
    {
      ContactIterate F;
      evaluate(data, law, x, result.u, F, &ws.pieces_scratch);
      record_answer(data, x);
      if (measures)
        {
          result.residual = relative_natural_map_error(data, x.p, result.u);
          result.balanced_residual =
            balanced_natural_map_error(data,
                                       op.weights(data, 1.),
                                       x.p,
                                       result.u);
          double absolute;
          result.equilibrium_residual =
            relative_equilibrium_error(data, x.p, absolute);
        }
      return F;
    }



    void
    NewtonDriver::record_answer(const ContactData    &data,
                                const ContactIterate &x) const
    {
      result.p     = x.p;
      result.alpha = data.n_alpha() > 0 ? x.alpha : Vec();
      result.w     = x.w;
      result.status.resize(ws.pieces_scratch.size());
      for (unsigned int c = 0; c < ws.pieces_scratch.size(); ++c)
        result.status[c] = ws.pieces_scratch[c].status;
      count_status(result);
      result.max_penetration = 0.;
      for (unsigned int c = 0; c < data.n_contacts; ++c)
        result.max_penetration =
          std::max(result.max_penetration, -result.u[c * data.n_components]);
    }



    void
    NewtonDriver::accept(const ContactData    &data,
                         const PairLawModel   &law,
                         const ContactIterate &x,
                         Vec                 &&u,
                         ContactIterate      &&F,
                         const StopMeasures   &measures)
    {
      converged_x          = x;
      ws.accepted.law      = &law;
      ws.accepted.data     = &data;
      ws.accepted.u        = std::move(u);
      ws.accepted.F        = std::move(F);
      ws.accepted.measures = measures;
    }



    void
    NewtonDriver::accept(const ContactIterate &x)
    {
      converged_x     = x;
      ws.accepted.law = nullptr;
    }



    bool
    NewtonDriver::answer(const ContactData    &data,
                         const PairLawModel   &law,
                         const ContactIterate &x,
                         const double          tolerance) const
    {
      if (&x == &converged_x && ws.accepted.law == &law &&
          ws.accepted.data == &data)
        {
          // The pieces (the pairs' status) at x from the kept u.
          result.u.swap(ws.accepted.u);
          residual(data, law, x, result.u, ws.accepted.F, &ws.pieces_scratch);
          record_answer(data, x);
          result.residual             = ws.accepted.measures.err;
          result.balanced_residual    = ws.accepted.measures.balanced;
          result.equilibrium_residual = ws.accepted.measures.eq;
          ws.accepted.law             = nullptr;
          return true;
        }
      const ContactIterate F = finish(data, law, x, false);
      StopMeasures         measures;
      const bool           passed =
        stopping_test(data, law, x, tolerance, false, measures, &result.u, &F);
      result.residual             = measures.err;
      result.balanced_residual    = measures.balanced;
      result.equilibrium_residual = measures.eq;
      return passed;
    }



    bool
    NewtonDriver::out_of_time() const
    {
      if (settings.max_wall_seconds <= 0.)
        return false;
      const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      return elapsed > settings.max_wall_seconds;
    }



    bool
    NewtonDriver::out_of_iterations() const
    {
      return result.iterations >= settings.max_iterations;
    }



    void
    NewtonDriver::offer_best(const ContactIterate &x,
                             const StopMeasures   &measures)
    {
      const double score = std::max(measures.balanced, measures.eq);
      if (!std::isfinite(score))
        return;
      if (!have_best || score < best_score)
        {
          have_best  = true;
          best_score = score;
          best_x     = x;
        }
    }



    double
    NewtonDriver::evaluate(const ContactData    &data,
                           const PairLawModel   &law,
                           const ContactIterate &x,
                           Vec                  &u,
                           ContactIterate       &F,
                           NewtonBlocks         *pieces) const
    {
      op.update_geometry(x);
      u = op.displacement(x.p, x.w) + data.q;
      if (const Vec *offset = op.displacement_offset())
        u += *offset;
      if (data.n_alpha() > 0)
        u += data.G * x.alpha;
      F.w = op.equilibrium_residual(x.p, x.w);
      return residual(data, law, x, u, F, pieces);
    }



    double
    NewtonDriver::residual(const ContactData    &data,
                           const PairLawModel   &law,
                           const ContactIterate &x,
                           Vec                  &u,
                           ContactIterate       &F,
                           NewtonBlocks         *pieces) const
    {
      const unsigned int d = data.n_components, m = data.n_rows(),
                         na = data.n_alpha();
      for (unsigned int row = 0; any_held && row < m; ++row)
        if (held[row])
          u[row] = 0.;
      F.p.resize(m);
      if (pieces)
        pieces->resize(data.n_contacts);
      for (unsigned int c = 0; c < data.n_contacts; ++c)
        law.evaluate(data,
                     c,
                     x.p.data() + c * d,
                     u.data() + c * d,
                     F.p.data() + c * d,
                     pieces ? &(*pieces)[c] : nullptr);
      for (unsigned int row = 0; any_held && row < m; ++row)
        if (held[row])
          {
            F.p[row] = x.p[row];
            if (pieces)
              {
                PairPiece &piece = (*pieces)[row / d];
                piece.A.row(row % d).setZero();
                piece.B.row(row % d).setZero();
                piece.B(row % d, row % d) = 1.;
              }
          }
      F.alpha = na > 0 ? Vec(data.G.transpose() * x.p - data.b) : Vec();
      return 0.5 * squared_norm(F);
    }



    bool
    NewtonDriver::stopping_test(const ContactData    &data,
                                const PairLawModel   &law,
                                const ContactIterate &x,
                                const double          tolerance,
                                const bool            at_rounding_floor,
                                StopMeasures         &measures,
                                const Vec            *u_at_x,
                                const ContactIterate *F_at_x) const
    {
      const bool given = (u_at_x != nullptr && F_at_x != nullptr);
      if (!given)
        evaluate(data, law, x, ws.u_scratch, ws.F_scratch, nullptr);
      const Vec            &u         = given ? *u_at_x : ws.u_scratch;
      const ContactIterate &F         = given ? *F_at_x : ws.F_scratch;
      auto &[err, balanced, eq, disp] = measures;
      law.errors(data, x.p, u, F.p, err, balanced);
      double absolute;
      eq               = relative_equilibrium_error(data, x.p, absolute);
      const double den = op.equilibrium_scale(x.p, x.w);
      disp             = den > 0. ? F.w.norm() / den : 0.;
      // At the rounding floor the law's own factor applies: the BDE asks
      // for a balanced error 1000 times below the tolerance when the FCLIB
      // error is out of reach, the penalty accepts its residuals up to
      // 1000 times the tolerance (its floor grows with the penalty). With
      // FCLIB stopping the FCLIB error is the one test, floor or not
      // (LMGC_100_PR_PerioBox with one OpenBLAS thread: accepted at the
      // floor with the FCLIB error at 1.6e-7, then reported unsolved).
      const double floor = law.floor_factor() * tolerance;
      const double rows  = std::max(floor, tolerance);
      return ((balanced <= tolerance || settings.fclib_stopping) &&
              err <= tolerance && eq <= tolerance && disp <= tolerance) ||
             (at_rounding_floor && !settings.fclib_stopping &&
              balanced <= floor && eq <= rows && disp <= rows);
    }



    PhaseOutcome
    NewtonDriver::newton(const ContactData  &data,
                         const PairLawModel &law,
                         ContactIterate     &x,
                         const double        tolerance,
                         const std::string  &phase,
                         const bool          on_original,
                         const unsigned int  budget,
                         const bool          leave_when_singular_at_start,
                         const bool          leave_when_cycling,
                         const bool          leave_when_crawling)
    {
      // Iterations without progress among a few revisited active sets
      // after which a phase with leave_when_cycling ends.
      const unsigned int cycling_window = 10;
      // A phase with leave_when_crawling ends when the best theta fell by
      // less than 10 % in cycling_window iterations. Newton near a solution
      // gains far more per iteration; a crawl is a merit whose scale the
      // line search cannot follow (the load-history block on the full path
      // with Contact/r scale = 1e6: steps of 1e-3 to 1e-6 for 100
      // iterations; now 14 of them, then 3 at the scale 1). Not a rule for
      // every phase another follows: after the first radius of the rigid
      // stacks of FCLIB, such stretches end in convergence
      // (spheres-in-a-box: 69 iterations; with the rule the other radius
      // takes over and fails in 300).
      const double crawl_factor = 0.9;
      // best_theta after each iteration's test (kept with leave_when_crawling)
      std::vector<double> best_thetas;
      const double        sigma = settings.armijo_sigma;
      const double        beta  = settings.armijo_beta;
      const unsigned int  m = data.n_rows(), na = data.n_alpha();
      const unsigned int  d                  = data.n_components;
      const bool          equilibrium_linear = op.equilibrium_is_linear();

      std::deque<double> theta_memory;
      NewtonBlocks       pieces;
      Vec                u;
      ContactIterate     F;
      double             best_theta      = std::numeric_limits<double>::max();
      unsigned int       last_progress   = 0;
      unsigned int       local_it        = 0;
      unsigned int       singular_streak = 0;
      double             last_theta = 0., first_norm = 0.;
      // The adaptive sliding tangent's rule: the previous iteration's |H|
      // and how many of the ratios after the first exceeded 1/20.
      double       previous_norm     = 0.;
      unsigned int slow_contractions = 0;
      op.want_exact_tangent(false);

      // The active set of every iteration of this phase, and how a failure
      // is reported: the iteration, and the pairs involved.
      std::vector<std::vector<int>> sets;
      const auto                    fail = [&](const std::string &what) {
        const std::string pairs =
          describe_failure(sets,
                           std::max(4u, settings.stall_iterations),
                           x.p,
                           F.p,
                           data.n_contacts,
                           d,
                           result.pairs_involved);
        return PhaseOutcome{false,
                            what + " at iteration " +
                              std::to_string(result.iterations) + pairs};
      };

      // u_raw: u before the held directions are zeroed (the line search
      // updates it linearly).
      Vec u_raw;
      // With finite sliding the pairs are formed again at x first (the
      // line search below moves on their linearisation at x).
      const auto raw_displacement = [&]() {
        op.update_geometry(x);
        u_raw = op.displacement(x.p, x.w) + data.q;
        if (const Vec *offset = op.displacement_offset())
          u_raw += *offset;
        if (na > 0)
          u_raw += data.G * x.alpha;
        F.w = op.equilibrium_residual(x.p, x.w);
        u   = u_raw;
      };
      raw_displacement();
      double theta = residual(data, law, x, u, F, &pieces);
      for (;;)
        {
          sets.push_back(active_set(pieces));
          if (sets.size() > std::max(4u, settings.stall_iterations))
            sets.erase(sets.begin());
          if (!std::isfinite(theta) || !all_finite(x))
            return fail("non-finite values (NaN/inf) in H");
          // The FCLIB error may be out of reach in floating point when
          // forces and displacements have very different scales: accept
          // the balanced error alone once Newton stops converging
          // quadratically (|F| decreased less than 2x in the last step), or
          // once F is exactly zero: no step can lower it further (B1 with
          // degree-1 NURBS reaches H = 0 at its ninth step while the FCLIB
          // error is held at 1.4e-9 by the forces' rounding, and stalled).
          const bool at_floor =
            local_it > 0 && (theta == 0. || theta > 0.25 * last_theta);
          last_theta = theta;
          StopMeasures measures;
          const bool   done =
            stopping_test(data, law, x, tolerance, at_floor, measures, &u, &F);
          if (on_original)
            offer_best(x, measures);

          ContactIterationRecord rec;
          rec.phase             = phase;
          rec.h_norm            = std::sqrt(2. * theta);
          rec.residual          = measures.err;
          rec.balanced_residual = measures.balanced;
          if (settings.on_iteration)
            settings.on_iteration(result.iterations, measures.err);
          {
            result.status.resize(pieces.size());
            for (unsigned int c = 0; c < pieces.size(); ++c)
              result.status[c] = pieces[c].status;
            count_status(result);
            rec.n_open   = result.n_open;
            rec.n_stick  = result.n_stick;
            rec.n_slip   = result.n_slip;
            rec.n_closed = result.n_closed;
          }

          if (done)
            {
              // The last line of the history holds the final residual.
              rec.iteration = result.iterations;
              rec.note      = "converged";
              result.history.push_back(rec);
              if (settings.log)
                rec.print(log());
              if (on_original)
                accept(data, law, x, std::move(u), std::move(F), measures);
              return {true, "converged"};
            }
          if (local_it >= budget || out_of_iterations())
            return fail("iteration limit");
          if (out_of_time())
            return fail("time limit");
          if (theta < best_theta * (1. - 1e-3))
            {
              best_theta    = theta;
              last_progress = local_it;
            }
          else if (local_it - last_progress >= settings.stall_iterations)
            return fail("stall (no decrease of |H| in " +
                        std::to_string(settings.stall_iterations) +
                        " iterations)");
          else if (leave_when_cycling &&
                   local_it - last_progress >= cycling_window &&
                   sets.size() >= cycling_window)
            {
              if (const unsigned int n_distinct =
                    cycle_length(sets, cycling_window);
                  n_distinct > 0)
                return fail("stall (cycling between " +
                            std::to_string(n_distinct) +
                            " active sets without progress in " +
                            std::to_string(cycling_window) + " iterations)");
            }
          if (leave_when_crawling && local_it >= cycling_window &&
              best_theta >
                crawl_factor * best_thetas[local_it - cycling_window])
            return fail(
              "stall (the merit fell by less than " +
              std::to_string(std::lround(100. * (1. - crawl_factor))) +
              " % in " + std::to_string(cycling_window) + " iterations)");
          if (leave_when_crawling)
            best_thetas.push_back(best_theta);

          ++local_it;
          ++result.iterations;
          rec.iteration = result.iterations;

          // --- direction
          law.tie_rule(data, x.p, u, pieces);
          // Levenberg-Marquardt parameter relative to max diag J^T J: the
          // square of the relative residual (Yamashita and Fukushima: fast
          // local convergence without a nonsingular Newton matrix, the
          // rigid stacks of FCLIB), between 1e-10 far from the solution and
          // 1e-14, below which it would sink under the rounding of J^T J
          // and leave its null space to noise.
          const double lm_relative =
            std::isfinite(measures.err) ?
              std::clamp(measures.err * measures.err, 1e-14, 1e-10) :
              1e-10;
          // After a singular Newton matrix (a hyperstatic stack of rigid
          // bodies: every iteration's, KaplasTower's 14) the LU is tried
          // only every fifth iteration until one is regular again: its
          // failure costs as much as the Levenberg-Marquardt step itself.
          // (Waiting for two singular ones in a row changed no iteration
          // count on FCLIB and cost Box_Stacks-i0122 time.) After twenty
          // singular ones in a row, every twentieth (Capsules-i100-1090:
          // singular at all 56 iterations, its 11 LU attempts a small part
          // of the solve; doc/architecture.md).
          const unsigned int lu_every = singular_streak < 20 ? 5 : 20;
          const bool try_lu = singular_streak == 0 || local_it % lu_every == 0;
          const double F_norm = std::sqrt(2. * theta);
          if (local_it == 1)
            first_norm = F_norm;
          // A tangent that converges fast cuts |H| by far more than 20x
          // per iteration; one that cuts it by less twice after the first
          // iteration (whose ratio the change of the active set dominates)
          // asks for the exact one for the rest of the phase
          // (Contact/Sliding tangent = auto; doc/studies.md, "the two
          // Newton tangents", has the measured contraction factors).
          if (local_it >= 3 && F_norm > 0.05 * previous_norm)
            ++slow_contractions;
          previous_norm = F_norm;
          if (slow_contractions >= 2)
            op.want_exact_tangent(true);
          ContactIterate              dx;
          ContactOperator::StepReport report;
          // At finite strain the tangent of the current iterate.
          op.linearize(x);
          const bool solved =
            op.newton_step(data,
                           pieces,
                           F,
                           dx,
                           report,
                           lm_relative,
                           try_lu,
                           krylov_tolerance(F_norm, first_norm)) &&
            all_finite(dx);
          rec.n_reduced         = report.n_reduced;
          rec.linear_iterations = report.linear_iterations;
          rec.note += report.note;
          if (!solved && !report.why.empty())
            {
              // The path's linear solver failed (a singular coupled matrix,
              // GMRES at its limit): say so, as it said.
              result.history.push_back(rec);
              if (settings.log)
                rec.print(log());
              return fail("the Newton system could not be solved (" +
                          report.why + ")");
            }
          if (!solved || report.note.find("lm") != std::string::npos)
            {
              ++singular_iterations;
              ++singular_streak;
            }
          else
            singular_streak = 0;
          if (leave_when_singular_at_start && local_it == 1 &&
              singular_streak == 1 && op.proximal_for_singular_start())
            {
              // No step taken: the iteration is not counted.
              --result.iterations;
              --singular_iterations;
              left_singular_at_start = true;
              return fail("singular Newton matrix at the start");
            }

          // J dx and J^T F from the operator's products (the law's blocks,
          // G, the displacement equations).
          const auto apply_J = [&](const ContactIterate &v, Vec &dv_u) {
            ContactIterate Jv;
            dv_u = op.displacement_derivative(v.p, v.w);
            if (na > 0)
              dv_u += data.G * v.alpha;
            Jv.p.resize(m);
            for (unsigned int c = 0; c < data.n_contacts; ++c)
              for (unsigned int k = 0; k < d; ++k)
                {
                  double s = 0.;
                  for (unsigned int l = 0; l < d; ++l)
                    s += pieces[c].A(k, l) * dv_u[c * d + l] +
                         pieces[c].B(k, l) * v.p[c * d + l];
                  Jv.p[c * d + k] = s;
                }
            Jv.alpha = na > 0 ? Vec(data.G.transpose() * v.p) : Vec();
            // The displacement equations' derivative (E(v) itself where
            // they are linear).
            Jv.w = op.equilibrium_derivative(v.p, v.w);
            return Jv;
          };
          const auto apply_JT = [&](const ContactIterate &h) {
            Vec y(m), bt(m);
            for (unsigned int c = 0; c < data.n_contacts; ++c)
              for (unsigned int l = 0; l < d; ++l)
                {
                  double sa = 0., sb = 0.;
                  for (unsigned int k = 0; k < d; ++k)
                    {
                      sa += pieces[c].A(k, l) * h.p[c * d + k];
                      sb += pieces[c].B(k, l) * h.p[c * d + k];
                    }
                  y[c * d + l]  = sa;
                  bt[c * d + l] = sb;
                }
            ContactIterate g;
            Vec            y_w;
            op.displacement_adjoint(y, g.p, y_w);
            g.p += bt;
            g.alpha = na > 0 ? Vec(data.G.transpose() * y) : Vec();
            if (na > 0)
              g.p += data.G * h.alpha;
            g.w = y_w;
            if (h.w.size() > 0)
              {
                Vec h_p, h_w;
                op.equilibrium_adjoint(h.w, h_p, h_w);
                g.p += h_p;
                g.w += h_w;
              }
            return g;
          };

          Vec            du;
          ContactIterate Jdx;
          double         slope         = 0.;
          bool           gradient_step = false;
          // Steepest descent -J^T F, taken at most once per iteration and
          // formed only then (one product with W^T saved in every
          // iteration that keeps the Newton direction).
          const auto take_gradient_step = [&]() {
            const ContactIterate grad = apply_JT(F);
            dx.p                      = -grad.p;
            dx.alpha                  = -grad.alpha;
            dx.w                      = -grad.w;
            Jdx                       = apply_J(dx, du);
            slope                     = -squared_norm(grad);
            gradient_step             = true;
            rec.note += "gradient ";
          };
          if (solved)
            {
              Jdx   = apply_J(dx, du);
              slope = dot(F, Jdx);
            }
          // A descent direction: the angle between J dx and -F (in the
          // residual space, whose rows the law balances: force rows
          // against stiffness-weighted displacement rows) below 90 degrees
          // by a margin. The exact Newton direction has J dx = -F.
          if (!solved || (settings.line_search &&
                          !(slope < -1e-8 * std::sqrt(2. * theta) *
                                      std::sqrt(squared_norm(Jdx)))))
            take_gradient_step();

          // --- line search (non-monotone Armijo)
          theta_memory.push_back(theta);
          while (theta_memory.size() >
                 std::max(1u, settings.nonmonotone_memory))
            theta_memory.pop_front();
          const double theta_ref =
            *std::max_element(theta_memory.begin(), theta_memory.end());

          bool           accepted = !settings.line_search;
          double         step     = accepted ? 1. : 0.;
          ContactIterate F_trial;
          for (int attempt = 0; attempt < 2 && !accepted; ++attempt)
            {
              double t = 1., best_t = 0.,
                     best_trial = std::numeric_limits<double>::max();
              while (t >= settings.min_step)
                {
                  // u is linear in x, and E at small strain: updated, not
                  // recomputed (E at finite strain is).
                  const ContactIterate xt = axpy(x, t, dx);
                  Vec                  ut = u_raw + t * du;
                  F_trial.w =
                    F.w.size() == 0    ? Vec() :
                    equilibrium_linear ? Vec(F.w + t * Jdx.w) :
                                         op.equilibrium_residual(xt.p, xt.w);
                  const double th =
                    residual(data, law, xt, ut, F_trial, nullptr);
                  if (std::isfinite(th) && th < best_trial)
                    {
                      best_trial = th;
                      best_t     = t;
                    }
                  if (std::isfinite(th) && th <= theta_ref + sigma * t * slope)
                    {
                      accepted = true;
                      step     = t;
                      break;
                    }
                  t *= beta;
                }
              if (!accepted && best_t > 0. && best_trial < theta)
                {
                  accepted = true;
                  step     = best_t;
                  rec.note += "best-trial ";
                }
              if (!accepted && law.full_step_on_failure())
                {
                  accepted = true;
                  step     = 1.;
                  rec.note += "full-step ";
                }
              if (!accepted && !gradient_step)
                take_gradient_step();
              else
                break;
            }
          rec.step = step;
          result.history.push_back(rec);
          if (settings.log)
            rec.print(log());
          if (!accepted)
            {
              // No step reduces theta: at the rounding floor, where the
              // balanced error already meets the tolerance by far, this is
              // convergence.
              if (stopping_test(data, law, x, tolerance, true, measures))
                {
                  if (on_original)
                    accept(x);
                  return {true, "converged (at the rounding floor)"};
                }
              return fail("line-search failure (no decrease along the "
                          "Newton and the steepest-descent directions)");
            }

          x = axpy(x, step, dx);
          raw_displacement();
          theta = residual(data, law, x, u, F, &pieces);
        }
    }
  } // namespace contact
} // namespace igabde
