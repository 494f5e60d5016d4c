#include <igabde/base/utilities.h>

#include <igabde/discretization/body_description.h>

#include <igabde/elasticity/stress_measures.h>

#include <igabde/contact/contact_stage.h>

#include <igabde/coupled/coupled_system.h>
#include <igabde/postprocess/contact_checks.h>
#include <igabde/postprocess/contact_output.h>
#include <igabde/postprocess/exact_solutions.h>
#include <igabde/scene/geometry.h>
#include <igabde/scene/load_controller.h>
#include <igabde/scene/simulator.h>
#include <igabde/scene/size_estimate.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <unistd.h>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /**
       * What a SIGINT or SIGTERM leaves behind. While a run goes on, the
       * simulator keeps here, rendered in advance, the summary.json it would
       * end with if interrupted now (the finished load steps, status
       * 'interrupted' and the reason) and the line for the screen; the
       * handler only writes them out (open/write/close are
       * async-signal-safe) and ends the process with 128 + the signal. Two
       * buffers: the simulator renders into the one the handler does not
       * read, then publishes it.
       */
      struct InterruptRecord
      {
        /// Set by run_scene: only the command-line run handles signals.
        bool        enabled = false;
        std::string summary_path;
        std::string log_path;
        /// [buffer][0: SIGINT, 1: SIGTERM]: the summary and the screen line.
        std::array<std::array<std::string, 2>, 2> summary;
        std::array<std::array<std::string, 2>, 2> line;
        std::atomic<int>                          published{-1};
      };

      InterruptRecord interrupt_record;

      extern "C" void
      write_interrupted_summary_and_exit(int signal)
      {
        const int b = interrupt_record.published.load();
        const int s = (signal == SIGINT ? 0 : 1);
        if (b >= 0)
          {
            const std::string &text = interrupt_record.summary[b][s];
            const int fd = ::open(interrupt_record.summary_path.c_str(),
                                  O_WRONLY | O_CREAT | O_TRUNC,
                                  0644);
            if (fd >= 0)
              {
                [[maybe_unused]] const auto n =
                  ::write(fd, text.data(), text.size());
                ::close(fd);
              }
            const std::string          &line = interrupt_record.line[b][s];
            [[maybe_unused]] const auto n =
              ::write(STDERR_FILENO, line.data(), line.size());
            const int log =
              ::open(interrupt_record.log_path.c_str(), O_WRONLY | O_APPEND);
            if (log >= 0)
              {
                [[maybe_unused]] const auto m =
                  ::write(log, line.data(), line.size());
                ::close(log);
              }
          }
        ::_exit(128 + signal);
      }



      /// Writes to two streams at once (screen and log.txt).
      class TeeBuffer : public std::streambuf
      {
      public:
        TeeBuffer(std::streambuf *a, std::streambuf *b)
          : a(a)
          , b(b)
        {}

      protected:
        int
        overflow(int c) override
        {
          if (c == EOF)
            return !EOF;
          const int r1 = a->sputc(c), r2 = b->sputc(c);
          return (r1 == EOF || r2 == EOF) ? EOF : c;
        }

        int
        sync() override
        {
          return (a->pubsync() == 0 && b->pubsync() == 0) ? 0 : -1;
        }

      private:
        std::streambuf *a, *b;
      };



      /**
       * Writes @p text to @p path through a neighbouring temporary file and
       * a rename, so a reader (or an interrupted run) finds either the old
       * file or the new one, never half of one.
       */
      void
      write_file_atomically(const std::string &path, const std::string &text)
      {
        const std::string part = path + ".part";
        {
          std::ofstream out(part);
          out << text;
        }
        std::filesystem::rename(part, path);
      }
    } // namespace



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
      , step_records(nlohmann::json::array())
    {
      summary["scene"]          = parameters.name;
      summary["status"]         = "running";
      summary["dim"]            = dim;
      summary["discretization"] = parameters.discretization.type;
      summary["degree"]         = parameters.discretization.degree;
      summary["refinements"]    = parameters.discretization.refinements;
      // The seconds below depend on it (doc/performance.md).
      summary["memory_allocator"] = base::memory_allocator();
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
    discretization::BodyDescription<dim>
    Simulator<dim>::make_description(const BodyParameters &body,
                                     const std::string    &name) const
    {
      const std::string where = scene_file + ": " + name + "/";
      discretization::BodyDescription<dim> d;
      d.name                    = (name == "Body 1" ? "body1" : "body2");
      d.material.youngs_modulus = body.youngs_modulus;
      d.material.poisson_ratio  = body.poisson_ratio;
      d.material.plane_model    = (parameters.plane_model == "plane stress" ?
                                     elasticity::PlaneModel::plane_stress :
                                     elasticity::PlaneModel::plane_strain);
      d.material.validate(scene_file + ": " + name);

      d.geometry =
        make_geometry<dim>(body, where, parameters.discretization.degree);

      // The body grammar was read and checked with the parameters
      // (BodyParameters::parse_parameters); here it only becomes
      // dim-dimensional.
      const auto tensor = [](const std::vector<double> &v) {
        Tensor<1, dim> t;
        for (unsigned int i = 0; i < dim; ++i)
          t[i] = v[i];
        return t;
      };
      for (const SupportParameters &support : body.supports)
        {
          discretization::DirichletCondition<dim> bc;
          bc.boundary_id = static_cast<types::boundary_id>(support.face);
          for (unsigned int c = 0; c < dim; ++c)
            {
              bc.components[c] = support.components[c];
              bc.value[c]      = support.values[c];
            }
          bc.history = parameters.load_path.history_index(support.history, 1);
          d.dirichlet.push_back(bc);
        }
      for (const TractionParameters &traction : body.tractions)
        {
          discretization::NeumannCondition<dim> bc;
          bc.boundary_id = static_cast<types::boundary_id>(traction.face);
          bc.history = parameters.load_path.history_index(traction.history, 0);
          switch (traction.kind)
            {
              case TractionParameters::Kind::pressure:
                {
                  const double p = traction.values[0];
                  bc.traction    = [p](const Point<dim> &,
                                    const Tensor<1, dim> &n) {
                    return -p * n;
                  };
                  break;
                }
              case TractionParameters::Kind::vector:
                {
                  const Tensor<1, dim> t = tensor(traction.values);
                  bc.traction            = [t](const Point<dim> &,
                                    const Tensor<1, dim> &) {
                    return t;
                  };
                  break;
                }
              case TractionParameters::Kind::exact:
                {
                  Assert(exact.has_value(), ExcInternalError());
                  const auto stress = exact->stress;
                  bc.traction       = [stress](const Point<dim>     &x,
                                         const Tensor<1, dim> &n) {
                    return stress(x) * n;
                  };
                  break;
                }
            }
          d.tractions.push_back(bc);
        }
      for (const PointLoadParameters &load : body.point_loads)
        {
          discretization::PointLoad<dim> point_load;
          point_load.location = Point<dim>(tensor(load.location));
          point_load.force    = tensor(load.force);
          point_load.history =
            parameters.load_path.history_index(load.history, 0);
          d.point_loads.push_back(point_load);
        }
      d.body_force = tensor(body.body_force);
      return d;
    }



    template <int dim>
    void
    Simulator<dim>::setup_bodies()
    {
      TimerOutput::Scope t(timer, "assembly");
      // Exact solution first: 'exact' tractions use it.
      {
        elasticity::IsotropicMaterial<dim> material;
        material.youngs_modulus = parameters.body1.youngs_modulus;
        material.poisson_ratio  = parameters.body1.poisson_ratio;
        material.plane_model    = (parameters.plane_model == "plane stress" ?
                                     elasticity::PlaneModel::plane_stress :
                                     elasticity::PlaneModel::plane_strain);
        const auto &e           = parameters.exact;
        if (e.type == "kirsch")
          {
            AssertThrow(dim == 2,
                        base::ExcInput(scene_file +
                                       ": Exact solution/Type = kirsch is a "
                                       "2D solution; set Dimension = 2."));
            if constexpr (dim == 2)
              exact = postprocess::kirsch_solution(e.remote_tension,
                                                   e.hole_radius,
                                                   material);
          }
        else if (e.type == "lame")
          exact = postprocess::lame_solution<dim>(e.inner_radius,
                                                  e.outer_radius,
                                                  e.pressure,
                                                  material);
      }

      const discretization::DiscretizationSettings &settings =
        parameters.discretization;
      bodies.push_back(discretization::create_body<dim>(
        make_description(parameters.body1, "Body 1"),
        settings));
      if (parameters.body2.type == "deformable")
        bodies.push_back(discretization::create_body<dim>(
          make_description(parameters.body2, "Body 2"),
          settings));
      pvd_records.resize(bodies.size());

      types::global_dof_index n_dofs     = 0;
      unsigned int            n_elements = 0;
      for (auto &body : bodies)
        {
          Timer clock;
          body->setup_system();
          if (parameters.output.progress)
            pcout << "  [progress] " << body->name() << ": space and assembly, "
                  << body->n_dofs() << " unknowns, " << std::setprecision(3)
                  << clock.wall_time() << " s" << std::setprecision(6)
                  << std::endl;
          n_dofs += body->n_dofs();
          n_elements += body->n_elements();
          pcout << "  " << body->name() << ": " << body->n_elements()
                << " elements, " << body->n_dofs() << " unknowns ("
                << body->discretization_name() << ", degree "
                << parameters.discretization.degree << ")" << std::endl;
          for (const auto &name : body->free_rigid_mode_names())
            pcout << "    free rigid mode left by the supports: " << name
                  << " (closed by the contact equilibrium)" << std::endl;
        }
      summary["n_dofs"]       = static_cast<unsigned long long>(n_dofs);
      summary["n_elements"]   = n_elements;
      nlohmann::json per_body = nlohmann::json::array();
      for (const auto &body : bodies)
        per_body.push_back(nlohmann::json{
          {"name", body->name()},
          {"n_dofs", static_cast<unsigned long long>(body->n_dofs())},
          {"n_elements", body->n_elements()},
          {"matrix_entries", body->stiffness_matrix().n_nonzero_elements()},
          {"free_rigid_modes", body->free_rigid_mode_names()}});
      summary["bodies"] = per_body;

      // Every body without supports that fix it must be held by contact.
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
    Simulator<dim>::factorize_bodies(const contact::ContactStage<dim> *stage)
    {
      TimerOutput::Scope t(timer, "factorization");
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          Timer clock;
          // What the contact path needs of the body (a Schur interface on
          // the contact face, or nothing).
          bodies[b]->factorize(
            stage != nullptr ?
              stage->factorization_interface(b) :
              std::vector<discretization::PointOperator<dim>>());
          if (bodies[b]->factor_entries() > 0. && summary.contains("bodies") &&
              b < summary["bodies"].size())
            summary["bodies"][b]["factor_entries"] =
              bodies[b]->factor_entries();
          if (parameters.output.progress)
            {
              pcout << "  [progress] " << bodies[b]->name()
                    << ": factorisation";
              if (bodies[b]->factor_entries() > 0.)
                pcout << " (" << std::setprecision(3)
                      << bodies[b]->factor_entries() << " factor entries"
                      << (bodies[b]->has_schur_complement() ?
                            ", Schur complement on " +
                              std::to_string(bodies[b]->n_interface_dofs()) +
                              " face unknowns" :
                            std::string())
                      << ")";
              pcout << ", " << std::setprecision(3) << clock.wall_time() << " s"
                    << std::setprecision(6) << std::endl;
            }
        }
    }



    template <int dim>
    void
    Simulator<dim>::solve_load_steps()
    {
      const auto steps      = parameters.load_path.steps();
      bool       body_force = false;
      for (const auto &body : bodies)
        body_force = body_force || body->description().body_force.norm() > 0.;
      nlohmann::json effects;
      if (parameters.contact.enabled)
        {
          contact::ContactSettings cs;
          const auto              &c = parameters.contact;
          cs.friction_coefficient    = c.friction_coefficient;
          cs.slave_face              = c.slave_face;
          cs.master_face             = c.master_face;
          cs.pairing                 = c.pairing;
          cs.solver.algorithm        = c.algorithm;
          cs.solver.path             = c.path;
          cs.schur_condensation =
            c.condensation == "schur" &&
            parameters.discretization.linear_solver == "direct";
          cs.solver.penalty.normal_factor     = c.penalty_factor;
          cs.solver.penalty.tangential_factor = c.tangential_penalty_factor;
          cs.solver.penalty.line_search       = c.penalty_line_search;
          cs.solver.bnewton.tolerance         = c.tolerance;
          cs.solver.bnewton.max_iterations    = c.max_iterations;
          cs.solver.bnewton.r_factor          = c.r_scale;
          cs.solver.bnewton.log               = c.verbose;
          cs.solver.bnewton.log_stream        = &contact_log();
          cs.context                          = scene_file;
          cs.progress                         = parameters.output.progress;
          cs.log_solves = parameters.output.solver_details;
          for (const auto &b : estimate_size(parameters, scene_file).bodies)
            cs.factor_entries.push_back(b.factor_entries);
          cs.n_load_steps = steps.size();

          // The obstacle Body 2 stands for, if it is not deformable.
          std::unique_ptr<contact::Obstacle<dim>> obstacle;
          if (parameters.body2.type == "rigid plane")
            {
              const std::string    where = scene_file + ": Body 2/";
              const Tensor<1, dim> normal =
                base::parse_tensor<dim>(parameters.body2.plane_normal,
                                        where + "Plane normal");
              AssertThrow(normal.norm() > 0.,
                          base::ExcInput(where + "Plane normal must not be "
                                                 "zero."));
              obstacle = std::make_unique<contact::RigidPlane<dim>>(
                base::parse_point<dim>(parameters.body2.plane_point,
                                       where + "Plane point"),
                normal);
            }
          contact_stage = std::make_unique<contact::ContactStage<dim>>(
            cs,
            bodies,
            std::move(obstacle),
            contact_log(),
            coupled::coupled_factory<dim>(c.full_system_solver,
                                          c.krylov_max_iterations));
          contact_stage->build_pairs(timer);
          factorize_bodies(contact_stage.get());
          {
            Timer clock;
            contact_stage->prepare(timer);
            if (parameters.output.progress)
              pcout << "  [progress] "
                    << (contact_stage->path() == contact::Path::full ?
                          "coupled system" :
                          "condensation")
                    << ", " << std::setprecision(3) << clock.wall_time() << " s"
                    << std::setprecision(6) << std::endl;
          }
          const contact::ContactSummary s     = contact_stage->summary();
          effects["contact"]                  = true;
          effects["friction"]                 = s.friction;
          effects["tangential_unknowns"]      = s.friction;
          effects["rigid_obstacle"]           = s.rigid_obstacle;
          effects["initial_gaps"]             = s.initial_gaps;
          effects["body_force"]               = body_force;
          effects["floating_rigid_modes"]     = s.floating_rigid_modes;
          effects["pairs_left_out_supported"] = s.pairs_left_out;
          effects["load_steps"]               = steps.size();
          summary["effects"]                  = effects;
          summary["n_contact_pairs"]          = s.n_pairs;
          summary["n_contact_unknowns"]       = s.n_unknowns;
          summary["contact_algorithm"]        = contact::to_string(s.algorithm);
          summary["contact_path"]             = contact::to_string(s.path);
          summary["contact_path_reason"]      = s.path_reason;
          if (s.estimated_condensed_seconds > 0. ||
              s.estimated_full_seconds > 0.)
            summary["contact_path_estimated_seconds"] = {
              {"condensed", s.estimated_condensed_seconds},
              {"full", s.estimated_full_seconds}};
          summary["contact_path_cost_inputs"] = {
            {"contact_unknowns", s.cost_inputs.contact_unknowns},
            {"face_unknowns", s.cost_inputs.face_unknowns},
            {"factor_entries", s.cost_inputs.factor_entries},
            {"newton_iterations", s.cost_inputs.newton_iterations}};
          const bool full = (s.path == contact::Path::full);
          if (c.full_system_solver != "mumps" && full)
            summary["full_system_solver"] = c.full_system_solver;
          if (full)
            summary["coupled_matrix_nonzeros"] = s.coupled_nonzeros;
          if (s.algorithm != contact::Algorithm::bde)
            {
              summary["penalty_factor_fkn"] = c.penalty_factor;
              summary["tangential_penalty_factor_fkt"] =
                c.tangential_penalty_factor;
            }
        }
      else
        {
          factorize_bodies(nullptr);
          effects["contact"]    = false;
          effects["friction"]   = false;
          effects["body_force"] = body_force;
          effects["load_steps"] = steps.size();
          summary["effects"]    = effects;
        }

      // Displacement of every body under the external loads alone.
      // (one factor per load history).
      const auto external = [&](const std::vector<double> &factors) {
        std::vector<Vector<double>> u(bodies.size());
        for (unsigned int b = 0; b < bodies.size(); ++b)
          u[b] = bodies[b]->external_solution(factors);
        return u;
      };
      std::unique_ptr<LoadController<dim>> controller;
      static std::ostream                  discard(nullptr);
      if (contact_stage)
        controller = std::make_unique<LoadController<dim>>(
          *contact_stage,
          external,
          parameters.contact.max_step_cuts,
          scene_file,
          parameters.output.solver_details ? pcout.get_stream() : discard);

      const auto history_factors = parameters.load_path.history_factors();
      std::vector<double> previous(history_factors.front().size(), 0.);
      for (unsigned int s = 0; s < steps.size(); ++s)
        {
          const auto [load_factor, displacement_factor] = steps[s];
          const std::vector<double> &factors            = history_factors[s];
          // Steps 1..s are written: summary.json, steps.csv and the fields
          // stay with them if this step fails or the run is killed.
          run_phase = "load step " + std::to_string(s + 1) + " of " +
                      std::to_string(steps.size()) + " (" +
                      (s == 0 ? std::string("no step finished") :
                                "steps 1.." + std::to_string(s) +
                                  " finished and written") +
                      ")";
          write_summary("running", "");
          pcout << "Load step " << s + 1 << "/" << steps.size()
                << ": load factor " << load_factor << ", displacement factor "
                << displacement_factor;
          for (unsigned int k = 0; k < parameters.load_path.histories.size();
               ++k)
            pcout << ", " << parameters.load_path.histories[k].first << " "
                  << factors[2 + k];
          pcout << std::endl;
          std::vector<Vector<double>> u = external(factors);
          nlohmann::json              record;
          record["step"]                = s + 1;
          record["load_factor"]         = load_factor;
          record["displacement_factor"] = displacement_factor;
          if (!parameters.load_path.histories.empty())
            {
              nlohmann::json named;
              for (unsigned int k = 0;
                   k < parameters.load_path.histories.size();
                   ++k)
                named[parameters.load_path.histories[k].first] = factors[2 + k];
              record["history_factors"] = named;
            }
          if (controller)
            {
              const auto outcome =
                controller->advance(s + 1, previous, factors, u, timer);
              const auto &last            = outcome.last;
              record["newton_iterations"] = outcome.iterations;
              record["contact_solves"]    = outcome.contact_solves;
              record["step_cuts"]         = outcome.cuts;
              record["residual"]          = last.residual;
              record["n_open"]            = last.n_open;
              record["n_stick"]           = last.n_stick;
              record["n_slip"]            = last.n_slip;
              if (parameters.contact.algorithm != contact::Algorithm::bde)
                record["max_penetration"] = last.max_penetration;
              if (parameters.contact.algorithm ==
                  contact::Algorithm::augmented_lagrange)
                record["multiplier_updates"] = last.updates;
              record["residual_history"] = last.residual_history;
              if (!last.linear_iterations.empty())
                record["krylov_iterations"] = last.linear_iterations;
              if (!outcome.success)
                {
                  record["diagnosis"] = last.diagnosis;
                  // Keep the failed step's figures next to the finished
                  // steps.
                  record["status"] = "failed";
                  step_records.push_back(record);
                  summary["load_steps"] = step_records;
                  AssertThrow(
                    false,
                    ExcMessage(
                      scene_file + ": load step " + std::to_string(s + 1) +
                      ": the contact solver did not converge: " +
                      last.diagnosis +
                      ". Try more load steps (Load path/Number of steps) or "
                      "step cuts (Contact/Max step cuts), a larger "
                      "Contact/Max iterations, or check that the bodies are "
                      "supported."));
                }
              record["condition_check_max_violation"] =
                last.condition_check_max_violation;
            }
          // Overflow or underflow (a load factor of 1e308, E = 1e-308)
          // gives inf/NaN without any solver noticing: never report it.
          for (unsigned int b = 0; b < bodies.size(); ++b)
            AssertThrow(std::all_of(u[b].begin(),
                                    u[b].end(),
                                    [](const double v) {
                                      return std::isfinite(v);
                                    }),
                        ExcMessage(
                          "load step " + std::to_string(s + 1) +
                          ": the displacement of " + bodies[b]->name() +
                          " is not finite (overflow: check the load and "
                          "displacement factors, the loads and Young's "
                          "modulus of the scene)."));
          record_forces(u, factors, record);
          previous = factors;
          step_records.push_back(record);
          summary["load_steps"] = step_records;
          if (contact_stage)
            summary["total_contact_force"] = record["total_contact_force"];
          output_step(s + 1, u);
          if (s + 1 == steps.size())
            postprocess_final(u);
        }
    }



    template <int dim>
    void
    Simulator<dim>::record_forces(const std::vector<Vector<double>> &u,
                                  const std::vector<double>         &factors,
                                  nlohmann::json &record) const
    {
      const auto to_json = [](const Tensor<1, dim> &t) {
        std::vector<double> v(dim);
        for (unsigned int c = 0; c < dim; ++c)
          v[c] = t[c];
        return v;
      };
      nlohmann::json per_body = nlohmann::json::array();
      Tensor<1, dim> on_body1;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          Vector<double> applied = bodies[b]->external_load_vector(factors);
          Tensor<1, dim> contact_force;
          if (contact_stage)
            {
              const Vector<double> f = contact_stage->contact_load(b);
              applied += f;
              for (unsigned int i = 0; i < f.size(); ++i)
                contact_force[bodies[b]->dof_component(i)] += f[i];
            }
          if (b == 0)
            on_body1 = contact_force;
          per_body.push_back(nlohmann::json{
            {"name", bodies[b]->name()},
            {"contact_force", to_json(contact_force)},
            {"support_reaction",
             to_json(bodies[b]->support_reaction(u[b], applied))}});
        }
      if (contact_stage)
        {
          record["total_contact_force"] = to_json(on_body1);
          if (bodies.size() == 1)
            per_body.push_back(
              nlohmann::json{{"name", "obstacle"},
                             {"contact_force", to_json(-on_body1)}});
        }
      record["bodies"] = per_body;
    }



    template <int dim>
    void
    Simulator<dim>::output_step(const unsigned int                 step,
                                const std::vector<Vector<double>> &u)
    {
      TimerOutput::Scope t(timer, "output");
      if (!root)
        return;
      std::ostringstream number;
      number << std::setw(4) << std::setfill('0') << step;
      // The pair table every step; fields only with Write vtu.
      if (contact_stage)
        {
          const auto pairs = contact_stage->pair_states();
          postprocess::write_pair_csv<dim>(pairs,
                                           output_directory + "/contact-" +
                                             number.str() + ".csv");
          if (parameters.output.write_vtu)
            postprocess::write_pair_vtu<dim>(pairs,
                                             output_directory + "/contact-" +
                                               number.str() + ".vtu");
        }
      if (!parameters.output.write_vtu)
        return;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          const std::string name =
            "solution-" + bodies[b]->name() + "-" + number.str() + ".vtu";
          bodies[b]->write_vtu(u[b], output_directory + "/" + name);
          pvd_records[b].emplace_back(double(step), name);
          std::ofstream pvd(output_directory + "/solution-" +
                            bodies[b]->name() + ".pvd");
          DataOutBase::write_pvd_record(pvd, pvd_records[b]);
        }
    }



    template <int dim>
    void
    Simulator<dim>::postprocess_final(const std::vector<Vector<double>> &u)
    {
      TimerOutput::Scope t(timer, "postprocess");
      nlohmann::json     checks   = nlohmann::json::object();
      nlohmann::json     warnings = nlohmann::json::array();
      if (exact)
        {
          const auto norms = bodies[0]->compute_errors(u[0], *exact);
          AssertThrow(std::isfinite(norms.l2_relative) &&
                        std::isfinite(norms.energy_relative),
                      ExcMessage("the error norms are not finite (overflow "
                                 "in the exact solution or the field: check "
                                 "the loads and Young's modulus of the "
                                 "scene)."));
          checks["l2_error"]     = norms.l2_relative;
          checks["energy_error"] = norms.energy_relative;
          pcout << "  relative L2 error " << std::setprecision(4)
                << std::scientific << norms.l2_relative
                << ", relative energy error " << norms.energy_relative
                << std::defaultfloat << std::setprecision(6) << std::endl;
        }

      if (contact_stage)
        {
          const auto pairs = contact_stage->pair_states();
          if (parameters.checks.uniform_pressure > 0.)
            {
              const double worst = postprocess::pressure_uniformity<dim>(
                pairs,
                parameters.checks.uniform_pressure);
              checks["pressure_uniformity"] = worst;
              pcout << "  pressure uniformity max |p_i/p - 1| = "
                    << std::setprecision(3) << std::scientific << worst
                    << std::defaultfloat << std::setprecision(6) << std::endl;
            }
          if (parameters.checks.hertz_line_load > 0.)
            {
              if constexpr (dim == 2)
                {
                  postprocess::HertzCheck hertz;
                  hertz.line_load         = parameters.checks.hertz_line_load;
                  hertz.radius            = parameters.body1.radius;
                  hertz.effective_modulus = postprocess::effective_modulus<dim>(
                    bodies[0]->material(),
                    bodies.size() > 1 ? &bodies[1]->material() : nullptr);
                  hertz.axis_point =
                    base::parse_point<dim>(parameters.checks.hertz_axis_point,
                                           scene_file +
                                             ": Checks/Hertz axis point");
                  hertz.axis_direction = base::parse_tensor<dim>(
                    parameters.checks.hertz_axis_direction,
                    scene_file + ": Checks/Hertz axis direction");
                  const auto r                     = hertz.evaluate(pairs);
                  checks["hertz_half_width"]       = r.half_width;
                  checks["hertz_half_width_exact"] = r.half_width_exact;
                  checks["hertz_half_width_error"] =
                    std::abs(r.half_width / r.half_width_exact - 1.);
                  checks["hertz_peak_pressure"]       = r.peak_pressure;
                  checks["hertz_peak_pressure_exact"] = r.peak_pressure_exact;
                  checks["pressure_l2_rel_error"]     = r.profile_l2_error;
                  checks["hertz_loaded_pairs"]        = r.n_loaded;
                  checks["hertz_edge_pair_spacing"]   = r.edge_pair_spacing;
                  checks["hertz_half_width_moment"]   = r.half_width_moment;
                  checks["hertz_half_width_moment_error"] =
                    std::abs(r.half_width_moment / r.half_width_exact - 1.);
                  checks["hertz_max_pair_deviation"] = r.max_pair_deviation;
                  checks["hertz_inner_pairs"]        = r.n_inner_pairs;
                  pcout << "  Hertz: half-width " << std::setprecision(5)
                        << r.half_width << " (Johnson " << r.half_width_exact
                        << "), peak pressure " << r.peak_pressure
                        << " (Johnson " << r.peak_pressure_exact
                        << "), profile L2 error " << std::setprecision(3)
                        << r.profile_l2_error << std::setprecision(6)
                        << std::endl;
                  if (!r.warning.empty())
                    {
                      pcout << "  warning: " << r.warning << std::endl;
                      warnings.push_back(r.warning);
                    }
                }
            }
        }
      summary["checks"] = checks;
      if (!warnings.empty())
        summary["warnings"] = warnings;

      nlohmann::json points   = nlohmann::json::object();
      nlohmann::json stresses = nlohmann::json::object();
      for (const std::string &item : base::split(parameters.probes, ';'))
        {
          const auto [name, location] =
            base::split_entry(item,
                              scene_file + ": Probe points",
                              "'name: x, y[, z]'");
          const Point<dim> x =
            base::parse_point<dim>(location, scene_file + ": Probe points");
          // The first body that holds the point.
          unsigned int b = bodies.size();
          for (unsigned int k = 0; k < bodies.size() && b == bodies.size(); ++k)
            if (bodies[k]->contains(x))
              b = k;
          AssertThrow(b < bodies.size(),
                      base::ExcInput(scene_file + ": Probe points: '" + item +
                                     "' lies in no body; give a point of "
                                     "Body 1 or Body 2."));
          const Tensor<1, dim> d =
            bodies[b]->point_operator(x).displacement(u[b]);
          std::vector<double> value(dim);
          for (unsigned int c = 0; c < dim; ++c)
            value[c] = d[c];
          points[name] = value;
          pcout << "  probe " << name << ": displacement "
                << std::setprecision(5) << d << std::setprecision(6)
                << std::endl;

          // Stress recovered at the probe: upper triangle, row by row.
          const SymmetricTensor<2, dim> sigma = bodies[b]->stress(u[b], x);
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              AssertThrow(std::isfinite(sigma[i][j]),
                          ExcMessage("probe " + name +
                                     ": the stress is not finite (overflow: "
                                     "check the loads and Young's modulus "
                                     "of the scene)."));
          std::vector<double> components;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = i; j < dim; ++j)
              components.push_back(sigma[i][j]);
          const auto    &material = bodies[b]->material();
          nlohmann::json entry    = {
               {"body", bodies[b]->name()},
               {"stress", components},
               {"von_mises", elasticity::von_mises<dim>(sigma, material)}};
          if (dim == 2)
            entry["stress_zz"] =
              elasticity::out_of_plane_stress<dim>(sigma, material);
          stresses[name] = entry;
        }
      summary["points"]         = points;
      summary["point_stresses"] = stresses;
    }



    template <int dim>
    void
    Simulator<dim>::write_step_table() const
    {
      // steps.csv: one row per load step, full precision, for plots.
      std::ostringstream csv;
      csv << "step,load_factor,displacement_factor";
      // Named load histories, when the scene has any.
      for (const auto &h : parameters.load_path.histories)
        csv << "," << h.first << "_factor";
      if (contact_stage)
        {
          csv << ",status,contact_solves,newton_iterations,residual,n_open,"
                 "n_stick,n_slip";
          for (const char *c : {"x", "y", "z"})
            if (c[0] - 'x' < dim)
              csv << ",force_" << c;
        }
      csv << "\n" << std::setprecision(12);
      for (const auto &r : step_records)
        {
          csv << r.at("step").get<double>() << ","
              << r.at("load_factor").get<double>() << ","
              << r.at("displacement_factor").get<double>();
          for (const auto &h : parameters.load_path.histories)
            csv << ","
                << (r.contains("history_factors") ?
                      r.at("history_factors").at(h.first).get<double>() :
                      0.);
          if (contact_stage)
            {
              const auto value = [&](const char *key) {
                return r.contains(key) && r.at(key).is_number() ?
                         r.at(key).get<double>() :
                         0.;
              };
              csv << "," << (r.contains("status") ? "failed" : "ok") << ","
                  << value("contact_solves") << ","
                  << value("newton_iterations") << "," << value("residual")
                  << "," << value("n_open") << "," << value("n_stick") << ","
                  << value("n_slip");
              for (unsigned int c = 0; c < dim; ++c)
                csv << ","
                    << (r.contains("total_contact_force") ?
                          r.at("total_contact_force").at(c).get<double>() :
                          0.);
            }
          csv << "\n";
        }
      write_file_atomically(output_directory + "/steps.csv", csv.str());
    }



    template <int dim>
    void
    Simulator<dim>::write_summary(const std::string &status,
                                  const std::string &error)
    {
      summary["status"] = status;
      if (!error.empty())
        summary["error"] = error;
      if (!root)
        return;
      write_step_table();

      nlohmann::json timing = nlohmann::json::object();
      double         total  = 0.;
      for (const auto &[phase, seconds] :
           timer.get_summary_data(TimerOutput::total_wall_time))
        {
          timing[phase] = seconds;
          total += seconds;
        }
      timing["total"]   = total;
      summary["timing"] = timing;
      write_file_atomically(output_directory + "/summary.json",
                            summary.dump(2) + "\n");
      if (interrupt_record.enabled)
        {
          if (status == "running")
            {
              const int b = 1 - std::max(0, interrupt_record.published.load());
              nlohmann::json copy = summary;
              copy["status"]      = "interrupted";
              for (const int s : {0, 1})
                {
                  const std::string reason = std::string("interrupted by ") +
                                             (s == 0 ? "SIGINT" : "SIGTERM") +
                                             " during " + run_phase;
                  copy["error"]                  = reason;
                  interrupt_record.summary[b][s] = copy.dump(2) + "\n";
                  interrupt_record.line[b][s]    = "igabde: " + reason +
                                                "; the finished steps are in " +
                                                output_directory + "/\n";
                }
              // Set once, before the first publication: the handler reads it.
              if (interrupt_record.summary_path.empty())
                {
                  interrupt_record.summary_path =
                    output_directory + "/summary.json";
                  interrupt_record.log_path = output_directory + "/log.txt";
                }
              interrupt_record.published.store(b);
            }
          else
            interrupt_record.published.store(-1);
        }

      // deal.II's timing table, to a file always and to the screen unless
      // the scene switches it off.
      timing_table.str("");
      timer.print_summary();
      std::ofstream(output_directory + "/timing.txt") << timing_table.str();
      if (parameters.output.print_timing && status != "running")
        pcout << timing_table.str() << std::flush;
    }



    template <int dim>
    void
    Simulator<dim>::run()
    {
      pcout << "Scene " << parameters.name << " (" << dim << "D, "
            << parameters.discretization.type << ", degree "
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
        const SizeEstimate size  = estimate_size(parameters, scene_file);
        summary["size_estimate"] = size.to_json();
        if (parameters.output.progress)
          pcout << "  [progress] size estimate: " << size.describe() << " ("
                << std::setprecision(3)
                << available_memory_bytes() / std::pow(2., 30) << " GiB free)"
                << std::setprecision(6) << std::endl;
      }
      setup_bodies();
      solve_load_steps();
      write_summary("ok", "");
    }



    template <int dim>
    const nlohmann::json &
    Simulator<dim>::get_summary() const
    {
      return summary;
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



namespace igabde
{
  namespace scene
  {



    nlohmann::json
    run_scene_in_process(
      const std::string                                      &scene_file,
      const std::vector<std::pair<std::string, std::string>> &overrides,
      std::ostream                                           &log)
    {
      ParameterHandler    prm;
      const AllParameters parameters = parse_scene(prm, scene_file, overrides);
      std::filesystem::create_directories(parameters.output.directory);
      auto run = [&](auto &simulator) {
        simulator.run();
        return simulator.get_summary();
      };
      if (parameters.dimension == 2)
        {
          Simulator<2> simulator(parameters,
                                 scene_file,
                                 parameters.output.directory,
                                 log);
          return run(simulator);
        }
      Simulator<3> simulator(parameters,
                             scene_file,
                             parameters.output.directory,
                             log);
      return run(simulator);
    }



    int
    run_scene(const std::string &scene_file,
              const std::vector<std::pair<std::string, std::string>> &overrides,
              const bool                                              force)
    {
      ParameterHandler prm;
      AllParameters    parameters;
      try
        {
          parameters = parse_scene(prm, scene_file, overrides);
          // Before anything is built: a scene that cannot fit the memory
          // stops at once (the geometry is checked on the way).
          if (force)
            estimate_size(parameters, scene_file);
          else
            check_size(parameters, scene_file, available_memory_bytes());
        }
      catch (const ExceptionBase &e)
        {
          std::cerr << "igabde: error: " << base::exception_message(e)
                    << std::endl;
          return 2;
        }

      const std::string dir = parameters.output.directory;
      std::error_code   ec;
      std::filesystem::create_directories(dir, ec);
      if (ec)
        {
          std::cerr << "igabde: error: " << scene_file
                    << ": Output/Directory = '" << dir
                    << "' cannot be created (" << ec.message()
                    << "); choose a writable folder." << std::endl;
          return 2;
        }
      {
        std::ofstream echo(dir + "/parameters.prm");
        prm.print_parameters(echo, ParameterHandler::PRM);
        std::ofstream echo_json(dir + "/parameters.json");
        prm.print_parameters(echo_json, ParameterHandler::JSON);
      }

      std::ofstream log_file(dir + "/log.txt");
      TeeBuffer     tee(std::cout.rdbuf(), log_file.rdbuf());
      std::ostream  log(&tee);
      log << std::setprecision(6);

      auto run = [&](auto &simulator) -> int {
        try
          {
            simulator.run();
            return 0;
          }
        catch (const ExceptionBase &e)
          {
            const std::string message = base::exception_message(e);
            log_file << "igabde: error: " << message << std::endl;
            std::cerr << "igabde: error: " << message << std::endl;
            simulator.write_failed_summary(message);
          }
        catch (const std::exception &e)
          {
            log_file << "igabde: error: " << e.what() << std::endl;
            std::cerr << "igabde: error: " << e.what() << std::endl;
            simulator.write_failed_summary(e.what());
          }
        return 1;
      };

      // SIGINT/SIGTERM: the finished steps stay, summary.json says
      // 'interrupted' and why.
      interrupt_record.enabled = true;
      struct sigaction handler = {};
      handler.sa_handler       = write_interrupted_summary_and_exit;
      sigemptyset(&handler.sa_mask);
      struct sigaction previous_int, previous_term;
      sigaction(SIGINT, &handler, &previous_int);
      sigaction(SIGTERM, &handler, &previous_term);
      int status = 0;
      if (parameters.dimension == 2)
        {
          Simulator<2> simulator(parameters, scene_file, dir, log);
          status = run(simulator);
        }
      else
        {
          Simulator<3> simulator(parameters, scene_file, dir, log);
          status = run(simulator);
        }
      interrupt_record.published.store(-1);
      sigaction(SIGINT, &previous_int, nullptr);
      sigaction(SIGTERM, &previous_term, nullptr);
      interrupt_record.enabled = false;
      interrupt_record.summary_path.clear();
      interrupt_record.log_path.clear();
      return status;
    }
  } // namespace scene
} // namespace igabde
