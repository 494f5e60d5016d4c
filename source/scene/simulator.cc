#include <igabde/base/files.h>
#include <igabde/base/utilities.h>

#include <igabde/contact/contact_stage.h>

#include <igabde/coupled/coupled_system.h>
#include <igabde/scene/body_factory.h>
#include <igabde/scene/checkpoint.h>
#include <igabde/scene/contact_setup.h>
#include <igabde/scene/finite_strain_steps.h>
#include <igabde/scene/geometry.h>
#include <igabde/scene/interrupt.h>
#include <igabde/scene/load_controller.h>
#include <igabde/scene/rank_split.h>
#include <igabde/scene/simulator.h>
#include <igabde/scene/size_estimate.h>
#include <igabde/scene/step_results.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>

namespace igabde
{
  namespace scene
  {
    template <int dim>
    Simulator<dim>::Simulator(const AllParameters &parameters,
                              const std::string   &scene_file,
                              const std::string   &output_directory,
                              std::ostream        &log)
      : parameters(parameters)
      , scene_file(scene_file)
      , output_directory(output_directory)
      , root(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      , pcout(log, root)
      , timer(timing_table, TimerOutput::never, TimerOutput::wall_times)
      , summary(run_summary.setup)
    {
      run_summary.scene            = parameters.name;
      run_summary.dim              = dim;
      run_summary.discretization   = to_string(parameters.discretization.type);
      run_summary.degree           = parameters.discretization.degree;
      run_summary.refinements      = parameters.discretization.refinements;
      run_summary.memory_allocator = base::memory_allocator();
      run_summary.mpi_ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    }



    template <int dim>
    std::ostream &
    Simulator<dim>::contact_log()
    {
      static std::ostream discard(nullptr);
      return root ? pcout.get_stream() : discard;
    }



    template <int dim>
    Simulator<dim>::~Simulator() = default;



    template <int dim>
    void
    Simulator<dim>::setup_bodies()
    {
      TimerOutput::Scope t(timer, "assembly");
      // Exact solution first: 'exact' tractions use it.
      exact  = make_exact_solution<dim>(parameters, scene_file);
      bodies = create_bodies<dim>(parameters, scene_file, exact);
      for (const auto &body : bodies)
        for (const std::string &note : body->description().notes)
          pcout << "  info: " << note << std::endl;
      postprocessors =
        make_postprocessors<dim>(parameters, bodies.size(), root, writer);
      for (auto &body : bodies)
        body->set_progress_stream(parameters.output.progress &&
                                      pcout.is_active() ?
                                    &pcout.get_stream() :
                                    nullptr);

      // Under MPI each body is assembled and factorised by its own group of
      // ranks (the groups at the same time); the others receive its loads.
      factorised_here =
        split_ranks_among_bodies<dim>(bodies,
                                      estimated_factor_entries,
                                      parameters.discretization.linear_solver ==
                                        discretization::LinearSolver::direct,
                                      body_groups,
                                      pcout);
      std::vector<double> seconds(bodies.size(), 0.);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          Timer clock;
          bodies[b]->setup_system();
          seconds[b] = clock.wall_time();
        }
      for (auto &body : bodies)
        body->share_assembly();
      {
        std::vector<double> largest(seconds.size());
        Utilities::MPI::max(seconds, MPI_COMM_WORLD, largest);
        seconds = largest;
      }

      types::global_dof_index n_dofs     = 0;
      unsigned int            n_elements = 0;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          const auto &body = bodies[b];
          if (parameters.output.progress)
            pcout << "  [progress] " << body->name() << ": space and assembly, "
                  << body->n_dofs() << " unknowns, " << std::setprecision(3)
                  << seconds[b] << " s" << std::setprecision(6) << std::endl;
          n_dofs += body->n_dofs();
          n_elements += body->n_elements();
          pcout << "  " << body->name() << ": " << body->n_elements()
                << " elements, " << body->n_dofs() << " unknowns ("
                << body->discretization_name() << ", degree "
                << parameters.discretization.degree << ")" << std::endl;
          std::string held;
          for (const auto &name : body->held_rigid_mode_names())
            held += (held.empty() ? "" : ", ") + name;
          if (body->description().hold_rotation_face >= 0)
            pcout << "    Hold rotation (face "
                  << body->description().hold_rotation_face << "): "
                  << (held.empty() ? "the supports hold every rotation" :
                                     held + " held")
                  << std::endl;
        }
      check_probe_points<dim>(parameters, scene_file, bodies);
      run_summary.n_dofs      = static_cast<unsigned long long>(n_dofs);
      run_summary.n_elements  = n_elements;
      nlohmann::json per_body = nlohmann::json::array();
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          per_body.push_back(body_record<dim>(
            parameters.bodies[parameters.deformable_bodies()[b]],
            parameters.discretization.degree,
            *bodies[b]));
          if (parameters.output.export_geometry && root)
            export_geometry(*bodies[b], output_directory);
        }
      summary["bodies"] = per_body;

      // Every body without supports that fix it must be held by contact
      // (a body with no Supports at all is refused when the scene is read).
      for (const auto &body : bodies)
        AssertThrow(body->free_rigid_modes().empty() ||
                      parameters.contact.enabled,
                    base::ExcInput(scene_file + ": " + body->name() +
                                   " is not held against " +
                                   body->free_rigid_mode_names()[0] +
                                   " and the scene has no contact; add "
                                   "Supports."));
    }



    template <int dim>
    void
    Simulator<dim>::record_factorization(
      const discretization::FactorizationReport &report)
    {
      const std::vector<double> &seconds = report.seconds;
      const std::vector<double> &flops   = report.flops;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          if (bodies[b]->factor_entries() > 0. && summary.contains("bodies") &&
              b < summary["bodies"].size())
            {
              summary["bodies"][b]["factor_entries"] =
                bodies[b]->factor_entries();
              summary["bodies"][b]["factorization_flops"] = flops[b];
            }
          if (parameters.output.progress && !bodies[b]->finite_strain())
            {
              pcout << "  [progress] " << bodies[b]->name()
                    << ": factorisation";
              if (bodies[b]->factor_entries() > 0.)
                pcout << " (" << std::setprecision(3)
                      << bodies[b]->factor_entries() << " factor entries, "
                      << flops[b] << " flops"
                      << (bodies[b]->has_schur_complement() ?
                            ", Schur complement on " +
                              std::to_string(bodies[b]->n_interface_dofs()) +
                              " face unknowns" :
                            std::string())
                      << ")";
              pcout << ", " << std::setprecision(3) << seconds[b] << " s";
              if (flops[b] > 0. && seconds[b] > 0.)
                pcout << " (" << flops[b] / seconds[b] / 1e9 << " GFlop/s)";
              pcout << std::setprecision(6) << std::endl;
            }
        }
    }



    template <int dim>
    void
    Simulator<dim>::setup_contact()
    {
      bool body_force = false;
      for (const auto &body : bodies)
        body_force = body_force || body->description().body_force.norm() > 0. ||
                     static_cast<bool>(body->description().body_force_field);
      if (!parameters.contact.enabled)
        {
          record_factorization(discretization::factorize_bodies(
            bodies,
            std::vector<discretization::FactorizationRequest<dim>>(
              bodies.size()),
            timer,
            MPI_COMM_WORLD));
          record_setup(parameters, nullptr, body_force, summary);
          return;
        }
      contact_stage = std::make_unique<contact::ContactStage<dim>>(
        make_contact_settings(parameters,
                              scene_file,
                              estimated_factor_entries,
                              memory_path_reason,
                              contact_log()),
        bodies,
        create_obstacles<dim>(parameters, scene_file),
        contact_log(),
        coupled::coupled_factory<dim>(parameters.contact.full_system_solver,
                                      parameters.contact.krylov_max_iterations,
                                      parameters.output.progress &&
                                          pcout.is_active() ?
                                        &pcout.get_stream() :
                                        nullptr,
                                      MPI_COMM_WORLD));
      contact_stage->setup(
        timer,
        [this](const discretization::FactorizationReport &report) {
          record_factorization(report);
        });
      const contact::ContactSummary s = contact_stage->summary();
      record_setup(parameters, &s, body_force, summary);
      run_summary.warnings.insert(run_summary.warnings.end(),
                                  s.warnings.begin(),
                                  s.warnings.end());
    }



    template <int dim>
    void
    Simulator<dim>::solve_load_steps()
    {
      const auto steps = parameters.load_path.steps();
      // Displacement of every body under the external loads alone.
      // (one factor per load history).
      // (Bodies at finite strain have none: their state is solved below.)
      const auto external = [&](const std::vector<double> &factors) {
        std::vector<Vector<double>> u(bodies.size());
        for (unsigned int b = 0; b < bodies.size(); ++b)
          if (!bodies[b]->finite_strain())
            u[b] = bodies[b]->external_solution(factors);
        return u;
      };
      // The displacement of each body at finite strain at the last
      // finished step: the start of the next step's Newton solve.
      std::vector<Vector<double>> finite_state(bodies.size());
      for (unsigned int b = 0; b < bodies.size(); ++b)
        if (bodies[b]->finite_strain())
          finite_state[b].reinit(bodies[b]->n_dofs());
      discretization::NewtonSettings newton;
      newton.tolerance      = parameters.nonlinear_solver.tolerance;
      newton.max_iterations = parameters.nonlinear_solver.max_iterations;
      newton.line_search    = parameters.nonlinear_solver.line_search;
      std::unique_ptr<LoadController<dim>> controller;
      static std::ostream                  discard(nullptr);
      if (contact_stage)
        controller = std::make_unique<LoadController<dim>>(
          *contact_stage,
          external,
          parameters.contact.max_step_cuts,
          scene_file,
          parameters.output.solver_details ? contact_log() : discard);

      const auto &histories       = parameters.load_path.histories;
      const auto  history_factors = parameters.load_path.history_factors();
      std::vector<double> previous(history_factors.front().size(), 0.);
      // The scene as a checkpoint keeps it (parameters.json, Output aside).
      const nlohmann::json scene = scene_parameters(output_directory);
      unsigned int         first = 0;
      if (parameters.output.restart)
        first = resume(scene, steps.size(), previous, finite_state);
      resumed_steps = first;
      for (unsigned int s = first; s < steps.size(); ++s)
        {
          const auto [load_factor, displacement_factor] = steps[s];
          const std::vector<double> &factors            = history_factors[s];
          // The finished steps stay with their files if this step fails
          // or the run is killed (write_summary()).
          run_phase = "load step " + std::to_string(s + 1) + " of " +
                      std::to_string(steps.size());
          {
            TimerOutput::Scope t(timer, "output");
            write_summary("running", "");
          }
          pcout << "Load step " << s + 1 << "/" << steps.size()
                << ": load factor " << load_factor << ", displacement factor "
                << displacement_factor;
          for (unsigned int k = 0; k < histories.size(); ++k)
            pcout << ", " << histories[k].first << " " << factors[2 + k];
          pcout << std::endl;
          std::vector<Vector<double>> u = external(factors);
          StepRecord                  record;
          record.step                = s + 1;
          record.load_factor         = load_factor;
          record.displacement_factor = displacement_factor;
          for (unsigned int k = 0; k < histories.size(); ++k)
            record.history_factors.emplace_back(histories[k].first,
                                                factors[2 + k]);
          if (controller)
            {
              // A step whose data no arithmetic can solve (loads past
              // double precision) names the step.
              typename LoadController<dim>::Outcome outcome;
              try
                {
                  outcome =
                    controller->advance(s + 1, previous, factors, u, timer);
                }
              catch (const base::ExcInput &e)
                {
                  AssertThrow(false,
                              base::ExcInput("load step " +
                                             std::to_string(s + 1) + ": " +
                                             base::exception_message(e)));
                }
              record_contact_outcome<dim>(outcome,
                                          parameters.contact.algorithm,
                                          record);
              if (record.failed)
                {
                  run_summary.load_steps.push_back(record);
                  AssertThrow(false,
                              ExcMessage(
                                scene_file + ": load step " +
                                std::to_string(s + 1) +
                                ": the contact solver did not converge: " +
                                record.diagnosis + ". " + record.advice));
                }
            }
          if (parameters.finite_strain() && contact_stage)
            {
              // The contact solve has solved the bodies at finite strain
              // too (one Newton iteration for both nonlinearities).
              NewtonRecord newton;
              newton.iterations       = record.newton_iterations;
              newton.solves           = record.contact_solves;
              newton.step_cuts        = record.step_cuts;
              newton.residual         = record.residual;
              newton.residual_history = record.residual_history;
              newton.min_det_F        = std::numeric_limits<double>::infinity();
              for (unsigned int b = 0; b < bodies.size(); ++b)
                if (bodies[b]->finite_strain())
                  {
                    finite_state[b] = u[b];
                    Vector<double> force(bodies[b]->n_dofs());
                    newton.min_det_F = std::min(
                      newton.min_det_F,
                      bodies[b]->internal_force(u[b],
                                                bodies[b]->finite_law(),
                                                force,
                                                nullptr));
                  }
              record.finite_strain = newton;
            }
          else if (parameters.finite_strain())
            {
              TimerOutput::Scope t(timer, "newton");
              solve_finite_strain_step(s + 1,
                                       previous,
                                       factors,
                                       newton,
                                       finite_state,
                                       u,
                                       record);
            }
          check_finite_displacements<dim>(bodies, u, s + 1);
          previous = factors;
          std::optional<std::vector<contact::PairState<dim>>> pairs;
          if (contact_stage)
            pairs = contact_stage->pair_states();
          const StepContext<dim> context{parameters,
                                         scene_file,
                                         output_directory,
                                         bodies,
                                         exact,
                                         contact_stage.get(),
                                         pairs ? &*pairs : nullptr,
                                         u,
                                         factors,
                                         s + 1,
                                         s + 1 == steps.size(),
                                         pcout,
                                         contact_log()};
          // The step's record joins run_summary first, so that a
          // postprocessor that fails leaves the figures it had gathered.
          run_summary.load_steps.push_back(record);
          for (auto &postprocessor : postprocessors)
            {
              TimerOutput::Scope t(timer, postprocessor->timer_section());
              postprocessor->execute(context,
                                     run_summary.load_steps.back(),
                                     run_summary);
            }
          if (parameters.output.checkpoint && root)
            {
              TimerOutput::Scope t(timer, "output");
              Checkpoint         checkpoint;
              checkpoint.step         = s + 1;
              checkpoint.factors      = factors;
              checkpoint.finite_state = finite_state;
              if (contact_stage)
                checkpoint.contact = contact_state_to_json(*contact_stage);
              checkpoint.records    = run_summary.load_steps;
              checkpoint.warnings   = run_summary.warnings;
              checkpoint.parameters = scene;
              write_checkpoint(output_directory, checkpoint);
            }
        }
    }



    template <int dim>
    unsigned int
    Simulator<dim>::resume(const nlohmann::json        &scene,
                           const unsigned int           n_steps,
                           std::vector<double>         &previous,
                           std::vector<Vector<double>> &finite_state)
    {
      const Checkpoint  checkpoint = read_checkpoint(output_directory);
      const std::string where =
        "--restart " + output_directory + ": " +
        checkpoint_file(output_directory, checkpoint.step);
      // The first parameter that differs, named.
      const nlohmann::json difference =
        nlohmann::json::diff(checkpoint.parameters, scene);
      AssertThrow(difference.empty(),
                  base::ExcInput(
                    where + " was written by another scene (" +
                    difference.front().value("path", std::string()) +
                    " differs); restart with the scene that wrote it (only "
                    "Output may change)."));
      AssertThrow(checkpoint.step < n_steps &&
                    checkpoint.factors.size() == previous.size() &&
                    checkpoint.finite_state.size() == bodies.size() &&
                    checkpoint.contact.has_value() == bool(contact_stage),
                  base::ExcInput(where + " holds step " +
                                 std::to_string(checkpoint.step) + " of " +
                                 std::to_string(n_steps) +
                                 ": nothing is left to continue (or the "
                                 "file does not belong to this scene)."));
      for (unsigned int b = 0; b < bodies.size(); ++b)
        AssertThrow(checkpoint.finite_state[b].size() ==
                      (bodies[b]->finite_strain() ? bodies[b]->n_dofs() : 0),
                    base::ExcInput(where + ": " + bodies[b]->name() +
                                   "'s state does not fit its unknowns."));
      previous     = checkpoint.factors;
      finite_state = checkpoint.finite_state;
      if (contact_stage)
        restore_contact_state(*contact_stage, *checkpoint.contact);
      run_summary.load_steps = checkpoint.records;
      for (const std::string &w : checkpoint.warnings)
        if (std::find(run_summary.warnings.begin(),
                      run_summary.warnings.end(),
                      w) == run_summary.warnings.end())
          run_summary.warnings.push_back(w);
      std::vector<std::string> names;
      for (const auto &body : bodies)
        names.push_back(body->name());
      for (auto &postprocessor : postprocessors)
        postprocessor->resume(checkpoint.step,
                              output_directory,
                              names,
                              contact_stage != nullptr);
      summary["restarted_after_step"] = checkpoint.step;
      pcout << "Restart after step " << checkpoint.step << " of " << n_steps
            << " (" << checkpoint_file(output_directory, checkpoint.step) << ")"
            << std::endl;
      return checkpoint.step;
    }



    template <int dim>
    void
    Simulator<dim>::solve_finite_strain_step(
      const unsigned int                    step,
      const std::vector<double>            &previous,
      const std::vector<double>            &factors,
      const discretization::NewtonSettings &settings,
      std::vector<Vector<double>>          &state,
      std::vector<Vector<double>>          &u,
      StepRecord                           &record)
    {
      NewtonRecord newton;
      newton.min_det_F = std::numeric_limits<double>::infinity();
      std::string failure;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          if (!bodies[b]->finite_strain())
            continue;
          if (parameters.output.solver_details)
            contact_log() << "  " << bodies[b]->name()
                          << ": Newton at finite strain" << std::endl;
          const FiniteStrainOutcome outcome =
            advance_finite_strain(*bodies[b],
                                  bodies[b]->finite_law(),
                                  previous,
                                  factors,
                                  settings,
                                  parameters.nonlinear_solver.max_step_cuts,
                                  state[b],
                                  parameters.output.solver_details ?
                                    &contact_log() :
                                    nullptr);
          newton.iterations += outcome.iterations;
          newton.solves += outcome.solves;
          newton.step_cuts += outcome.cuts;
          newton.residual_history = outcome.residuals;
          if (!outcome.residuals.empty())
            newton.residual =
              std::max(newton.residual, outcome.residuals.back());
          newton.min_det_F = std::min(newton.min_det_F, outcome.min_J);
          if (!outcome.success && failure.empty())
            failure = bodies[b]->name() +
                      ": Newton's method did not "
                      "converge (" +
                      outcome.diagnosis + ") after " +
                      std::to_string(outcome.cuts) + " step cuts";
          u[b] = state[b];
        }
      record.finite_strain = newton;
      if (failure.empty())
        return;
      record.failed    = true;
      record.diagnosis = failure;
      record.advice =
        "use more load steps (Load path/Number of steps) or raise "
        "Nonlinear solver/Max step cuts";
      run_summary.load_steps.push_back(record);
      AssertThrow(false,
                  ExcMessage(scene_file + ": load step " +
                             std::to_string(step) + ": " + failure + "; " +
                             record.advice + "."));
    }



    template <int dim>
    void
    Simulator<dim>::run()
    {
      pcout << "Scene " << parameters.name << " (" << dim << "D, "
            << to_string(parameters.discretization.type) << ", degree "
            << parameters.discretization.degree << ", "
            << parameters.discretization.refinements << " refinements)"
            << std::endl;
      // Mark the folder: until this run ends, summary.json says 'running'
      // (and steps.csv, timing.txt start empty), so that the results of an
      // earlier run in the same folder are never taken for this one's, even
      // if this run is killed.
      run_phase = "the set-up (no load step finished)";
      write_summary("running", "");
      {
        SizeEstimate size = estimate_size(parameters, scene_file);
        memory_path_reason =
          size.choose_path_for_memory(available_memory_bytes());
        run_summary.size_estimate = size.to_json();
        estimated_factor_entries.clear();
        for (const auto &body : size.bodies)
          estimated_factor_entries.push_back(body.factor_entries);
        if (parameters.output.progress)
          pcout << "  [progress] size estimate: " << size.describe() << " ("
                << std::setprecision(3)
                << available_memory_bytes() / std::pow(2., 30) << " GiB free)"
                << std::setprecision(6) << std::endl;
      }
      setup_bodies();
      setup_contact();
      solve_load_steps();
      {
        // The last files: the run waits for them, and that is output time.
        TimerOutput::Scope t(timer, "output");
        writer.wait();
      }
      std::vector<base::MemoryItem> held;
      for (const auto &body : bodies)
        for (auto &item : body->memory_record())
          held.push_back(std::move(item));
      if (contact_stage)
        for (auto &item : contact_stage->memory_record())
          held.push_back(std::move(item));
      std::tie(final_timing, run_summary.ranks) =
        gather_rank_figures(timer, factorised_here, held);
      write_summary("ok", "");
    }



    template <int dim>
    nlohmann::json
    Simulator<dim>::get_summary() const
    {
      return to_json(run_summary);
    }



    template <int dim>
    void
    Simulator<dim>::write_failed_summary(const std::string &message)
    {
      write_summary("failed", message);
    }



    template class Simulator<2>;
    template class Simulator<3>;
  } // namespace scene
} // namespace igabde
