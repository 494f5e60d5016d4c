#include <igabde/base/utilities.h>

#include <igabde/nurbs/nurbs_patch.h>

#include <igabde/discretization/body_description.h>

#include <igabde/elasticity/finite_output.h>
#include <igabde/elasticity/stress_measures.h>

#include <igabde/postprocess/contact_checks.h>
#include <igabde/postprocess/contact_output.h>
#include <igabde/postprocess/fclib_writer.h>
#include <igabde/scene/postprocessors.h>
#include <igabde/scene/step_results.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <tuple>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /**
       * Output/FCLIB export: the condensed contact problem solved last (the
       * step's W, q, mu; the tangential rows are the step's increments)
       * with its solution p, u = W p + q, written as the FCLIB local
       * problem fclib-NNNN.hdf5 of the step. A problem that is not an FCLIB
       * local problem (no W: the full path; floating bodies) is left out
       * with a line in the log.
       */
      template <int dim>
      class FclibExport : public Postprocessor<dim>
      {
      public:
        std::string
        timer_section() const override
        {
          return "output";
        }

        void
        execute(const StepContext<dim> &context,
                StepRecord &,
                RunSummary &) override
        {
          if (context.stage == nullptr)
            return;
          const contact::ContactStage<dim> &stage  = *context.stage;
          const std::string             &directory = context.output_directory;
          const unsigned int             step      = context.step;
          std::ostream                  &log       = context.log;
          const contact::ContactProblem &problem   = stage.condensed_problem();
          std::ostringstream             name;
          name << "fclib-" << std::setw(4) << std::setfill('0') << step
               << ".hdf5";
          if (problem.W.rows() != problem.n_rows() || problem.n_rows() == 0)
            {
              log << "  FCLIB export: step " << step
                  << " left out: the full path forms no flexibility W"
                  << std::endl;
              return;
            }
          if (problem.n_alpha() > 0)
            {
              log << "  FCLIB export: step " << step
                  << " left out: a body is held by contact only (its rigid "
                     "modes join the problem, which FCLIB's local problems "
                     "cannot hold)"
                  << std::endl;
              return;
            }
          contact::ContactSolverResult solution;
          solution.p         = stage.forces();
          solution.u         = problem.relative_displacement(solution.p);
          solution.converged = true;
          postprocess::write_fclib_local(problem,
                                         &solution,
                                         directory + "/" + name.str());
        }
      };



      /**
       * The model's range at the end of a load step: the largest strain of
       * the bodies and, with contact, the largest tangential displacement
       * between paired points in pair spacings go to the step's record;
       * the first step past a strain of 0.1 (small-strain, linear elastic)
       * or past one pair spacing (pairs formed once in the reference
       * configuration, small sliding) adds a warning to the summary and a
       * line to the log.
       */
      template <int dim>
      class ModelRange : public Postprocessor<dim>
      {
      public:
        std::string
        timer_section() const override
        {
          return "postprocess";
        }

        void
        execute(const StepContext<dim> &context,
                StepRecord             &record,
                RunSummary             &summary) override
        {
          const auto &bodies   = context.bodies;
          const auto *stage    = context.stage;
          const auto &u        = context.u;
          auto       &warnings = summary.warnings;
          auto       &log      = context.log;
          // Beyond these the linearised model no longer describes the scene:
          // a strain of 0.1, where the quadratic term the small-strain measure
          // drops (of relative size eps / 2) reaches 5 % of it; paired points
          // moved apart by more than the pair spacing (pairs formed once in the
          // reference configuration no longer face each other); a curved
          // obstacle's normal turned by 0.1 rad from the one a pair keeps
          // (its gap then off by the turn times half the slide).
          const double strain_limit = 0.1, sliding_limit = 1., turn_limit = 0.1;
          const double smallest_strain = 1e-8;
          const char  *units_advice =
            "units: E, loads and lengths must be in one system (with "
            "lengths in mm and forces in N, E is in MPa = N/mm^2; E in Pa "
            "makes the bodies 10^6 times too stiff, lengths in m with E in "
            "MPa 10^6 times too soft).";
          const auto warn = [&](const std::string &kind,
                                const std::string &text) {
            for (const std::string &w : warnings)
              if (w.find(kind) != std::string::npos)
                return;
            warnings.push_back("load step " + std::to_string(record.step) +
                               ": " + text);
            log << "  warning: " << warnings.back() << std::endl;
          };
          std::pair<double, Point<dim>> strain(0., Point<dim>());
          unsigned int                  strain_body = 0;
          for (unsigned int b = 0; b < bodies.size(); ++b)
            {
              // A body at finite strain is inside its model at any strain.
              if (bodies[b]->finite_strain())
                continue;
              const auto largest = bodies[b]->largest_strain(u[b]);
              if (largest.first >= strain.first)
                std::tie(strain, strain_body) = std::make_pair(largest, b);
            }
          // The small-strain range: of the bodies at small strain.
          if (std::any_of(bodies.begin(), bodies.end(), [](const auto &b) {
                return !b->finite_strain();
              }))
            record.largest_strain = strain.first;
          std::ostringstream text;
          text << std::setprecision(3);
          if (strain.first > strain_limit)
            {
              text
                << "the largest strain is " << strain.first << " (Body "
                << strain_body + 1 << " at (" << base::to_string(strain.second)
                << ")"
                << "), beyond 0.1, where the quadratic term that small-strain "
                   "elasticity drops reaches 5 % of the strain: the results "
                   "are outside the model's range.";
              if (strain.first > 100. * strain_limit)
                text << " A strain this large usually means inconsistent "
                     << units_advice;
              warn("the largest strain", text.str());
            }
          // So small a strain under a load is rarely meant either: steel
          // at its yield stress strains 1e-3, and E in Pa where the
          // lengths are in mm scales every strain by 1e-6.
          else if (strain.first > 0. && strain.first < smallest_strain)
            {
              text << "the largest strain is " << strain.first << " (Body "
                   << strain_body + 1 << " at ("
                   << base::to_string(strain.second)
                   << ")), below 1e-8: so small a strain usually means "
                      "inconsistent "
                   << units_advice;
              warn("the largest strain", text.str());
            }
          // Contact that never happened: every pair open at every step (a
          // gap larger than the bodies' approach), which no figure of the
          // run says by itself.
          const auto *pairs = context.pairs;
          if (context.last_step && pairs != nullptr && !pairs->empty() &&
              std::all_of(summary.load_steps.begin(),
                          summary.load_steps.end(),
                          [](const StepRecord &r) {
                            return r.n_stick + r.n_slip + r.n_closed == 0;
                          }))
            {
              std::size_t closest = 0;
              for (std::size_t i = 1; i < pairs->size(); ++i)
                if ((*pairs)[i].displacement_local[0] <
                    (*pairs)[closest].displacement_local[0])
                  closest = i;
              text.str("");
              text << "no contact pair closed in any load step: the smallest "
                      "gap at the end is "
                   << (*pairs)[closest].displacement_local[0] << " (at ("
                   << base::to_string((*pairs)[closest].location)
                   << ")), so the bodies never touch under these loads; if "
                      "they should, check the initial gap against the push "
                      "(the bodies' positions, Contact faces, the loads' "
                      "direction and Load path).";
              warn("no contact pair closed", text.str());
            }
          const auto turn = stage ?
                              stage->largest_normal_turn(u, context.factors) :
                              std::nullopt;
          if (turn)
            {
              record.largest_normal_turn = turn->first;
              if (turn->first > turn_limit)
                {
                  text.str("");
                  text << "the obstacle's normal at the pairs' points has "
                          "turned by "
                       << turn->first << " rad (at ("
                       << base::to_string(turn->second)
                       << ")) from the reference normal the pairs keep: "
                          "past "
                       << turn_limit
                       << " rad the contact is outside the model's "
                          "small-sliding range (its gaps are off by about "
                          "the radius times half the turn squared).";
                  warn("normal at the pairs' points has", text.str());
                }
            }
          const auto largest =
            stage ? stage->largest_sliding(u, context.factors) : std::nullopt;
          if (!largest)
            return;
          const auto &sliding    = *largest;
          record.largest_sliding = sliding.first;
          if (sliding.first > sliding_limit)
            {
              text.str("");
              text
                << "paired points have moved " << sliding.first
                << " pair spacings apart along the surface (at ("
                << base::to_string(sliding.second) << ")"
                << "): the pairs, formed once in the reference configuration, "
                   "no longer face each other, so the contact is outside the "
                   "model's small-sliding range.";
              warn("pair spacings apart", text.str());
            }
        }
      };



      /**
       * The contact resultant and support reaction of every body (and the
       * obstacle's contact force) at the end of a step, into its record;
       * with contact, the step's resultant on Body 1 goes to the log, its
       * components below 1e-10 of its length (round-off) as 0.
       */
      template <int dim>
      class Forces : public Postprocessor<dim>
      {
      public:
        std::string
        timer_section() const override
        {
          return "postprocess";
        }

        void
        execute(const StepContext<dim> &context,
                StepRecord             &record,
                RunSummary             &summary) override
        {
          const auto &bodies    = context.bodies;
          const auto *stage     = context.stage;
          const auto &u         = context.u;
          const auto &factors   = context.factors;
          auto       &log       = context.log;
          const auto  to_vector = [](const Tensor<1, dim> &t) {
            std::vector<double> v(dim);
            for (unsigned int c = 0; c < dim; ++c)
              v[c] = t[c];
            return v;
          };
          Tensor<1, dim> on_body1;
          for (unsigned int b = 0; b < bodies.size(); ++b)
            {
              Vector<double> applied = bodies[b]->applied_loads(u[b], factors);
              Tensor<1, dim> contact_force;
              if (stage != nullptr)
                {
                  const Vector<double> f = stage->contact_load(b);
                  applied += f;
                  for (unsigned int i = 0; i < f.size(); ++i)
                    contact_force[bodies[b]->dof_component(i)] += f[i];
                }
              if (b == 0)
                on_body1 = contact_force;
              BodyForceRecord forces;
              forces.name          = bodies[b]->name();
              forces.contact_force = to_vector(contact_force);
              forces.support_reaction =
                to_vector(bodies[b]->support_reaction(u[b], applied));
              record.bodies.push_back(forces);
              if (!bodies[b]->held_rigid_mode_names().empty())
                record.bodies.back().held_moment =
                  bodies[b]->held_moment(applied);
              const auto &motions = bodies[b]->description().face_motions;
              for (unsigned int k = 0; k < motions.size(); ++k)
                {
                  const std::vector<double> r =
                    bodies[b]->face_motion_reaction(u[b], applied, k, factors);
                  FaceMotionReaction reaction;
                  reaction.face = motions[k].boundary_id;
                  reaction.force =
                    std::vector<double>(r.begin(), r.begin() + dim);
                  reaction.moment =
                    std::vector<double>(r.begin() + dim, r.end());
                  record.bodies.back().face_motion_reactions.push_back(
                    reaction);
                }
            }
          // Each interaction's resultant on its slave body, when there are
          // several (the roller: its two contacts' forces, which the
          // resultant on the roller balances to round-off).
          const unsigned int n_interactions =
            context.parameters.contact.interactions.size();
          if (stage != nullptr && context.pairs != nullptr &&
              n_interactions > 1)
            {
              std::vector<Tensor<1, dim>> sums(n_interactions);
              for (const auto &pair : *context.pairs)
                sums[pair.interaction] += pair.force;
              for (const Tensor<1, dim> &f : sums)
                record.interaction_forces.push_back(to_vector(f));
            }
          if (stage != nullptr)
            {
              record.total_contact_force = to_vector(on_body1);
              // Along a translation the supports leave free, the resultant
              // balances the load (the equilibrium of a body held by contact
              // alone): named, not printed as if it were a result.
              log << "  total contact force on Body 1:" << std::setprecision(6);
              std::string balanced;
              for (unsigned int c = 0; c < dim; ++c)
                if (bodies[0]->free_translation(c))
                  balanced += std::string(" ") + "xyz"[c];
                else
                  log << ' '
                      << (std::abs(on_body1[c]) > 1e-10 * on_body1.norm() ?
                            on_body1[c] :
                            0.);
              if (!balanced.empty())
                log << " (" << balanced.substr(1)
                    << ": held by contact alone, balances the load)";
              log << std::endl;
              if (bodies.size() == 1)
                {
                  BodyForceRecord obstacle;
                  obstacle.name          = "obstacle";
                  obstacle.contact_force = to_vector(-on_body1);
                  record.bodies.push_back(obstacle);
                }
            }
          if (stage != nullptr)
            summary.total_contact_force = record.total_contact_force;
        }
      };



      /**
       * The files of a load step: the pair table contact-NNNN.csv (with
       * contact; recovered pressures on Body 1's contact faces) and, with
       * Output/Write vtu, the pairs' and the bodies' VTU files, gathered in
       * one PVD series per body and one for the pairs (write_series()).
       * The files are written by the background writer's threads while the
       * run goes on, after the previous step's (execute() waits for them
       * first).
       *
       * Collective in spirit: every rank runs it, rank r writes piece r of
       * each body's VTU (with more than one rank and cell:
       * solution-NAME-NNNN.R.vtu, and rank 0 the record
       * solution-NAME-NNNN.pvtu that names them); rank 0 alone writes the
       * pairs' files. No rank waits for another.
       */
      template <int dim>
      class StepFiles : public Postprocessor<dim>
      {
      public:
        StepFiles(const AllParameters    &parameters,
                  const unsigned int      n_bodies,
                  base::BackgroundWriter &writer)
          : write_fields(parameters.output.write_vtu)
          , pvd_records(n_bodies)
          , writer(writer)
          , this_rank(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD))
          , ranks(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD))
        {
          for (const InteractionParameters &c : parameters.contact.interactions)
            slave_faces.emplace_back(c.slave_faces.begin(),
                                     c.slave_faces.end());
        }

        std::string
        timer_section() const override
        {
          return "output";
        }

        void
        execute(const StepContext<dim> &context,
                StepRecord &,
                RunSummary &) override
        {
          const auto        &bodies    = context.bodies;
          const auto        &u         = context.u;
          const auto        *pairs     = context.pairs;
          const std::string &directory = context.output_directory;
          const unsigned int step      = context.step;
          const bool         write_vtu = write_fields;
          const unsigned int rank      = this_rank;
          const unsigned int n_ranks   = ranks;
          series_directory             = directory;
          body_names.clear();
          for (const auto &body : bodies)
            body_names.push_back(body->name());
          // The files of the step before the previous one first: at most two
          // steps in flight.
          writer.begin_group();
          writer.wait_all_but_last_group();
          std::ostringstream number;
          number << std::setw(4) << std::setfill('0') << step;
          // The pair table every step; fields only with Write vtu. Each file is
          // a job of its own, on copies of the step's results.
          if (pairs != nullptr && rank == 0)
            {
              const std::string name = "contact-" + number.str();
              // The recovered pressure reads each slave body's stress field
              // on the interaction's slave faces, which the next step does
              // not change (the displacements are copies).
              std::vector<const discretization::Body<dim> *> slaves;
              for (const auto &body : bodies)
                slaves.push_back(body.get());
              writer.add([directory,
                          name,
                          write_vtu,
                          slaves,
                          u,
                          faces = slave_faces,
                          pairs = *pairs]() {
                std::vector<double> recovered(pairs.size());
                for (unsigned int k = 0; k < faces.size(); ++k)
                  {
                    std::vector<contact::PairState<dim>> of_k;
                    std::vector<unsigned int>            index;
                    for (unsigned int i = 0; i < pairs.size(); ++i)
                      if (pairs[i].interaction == k)
                        {
                          of_k.push_back(pairs[i]);
                          index.push_back(i);
                        }
                    if (of_k.empty())
                      continue;
                    const unsigned int        b = of_k.front().slave_body;
                    const std::vector<double> p =
                      postprocess::recovered_pressures<dim>(*slaves[b],
                                                            faces[k],
                                                            u[b],
                                                            of_k);
                    for (unsigned int j = 0; j < index.size(); ++j)
                      recovered[index[j]] = p[j];
                  }
                postprocess::write_pair_csv<dim>(pairs,
                                                 recovered,
                                                 directory + "/" + name +
                                                   ".csv");
                if (write_vtu)
                  postprocess::write_pair_vtu<dim>(pairs,
                                                   recovered,
                                                   directory + "/" + name +
                                                     ".vtu");
              });
              if (write_vtu)
                {
                  // The pairs' series after the bodies' (contact.pvd).
                  pvd_records.resize(bodies.size() + 1);
                  pvd_records.back().emplace_back(double(step), name + ".vtu");
                }
            }
          if (!write_vtu)
            return;
          for (unsigned int b = 0; b < bodies.size(); ++b)
            {
              // One piece per rank, as long as each has a cell to write.
              const unsigned int n_pieces =
                std::min(n_ranks, bodies[b]->n_elements());
              const std::string name =
                "solution-" + bodies[b]->name() + "-" + number.str();
              if (n_pieces == 1)
                {
                  if (rank == 0)
                    writer.add([body = bodies[b].get(),
                                ub   = u[b],
                                path = directory + "/" + name + ".vtu"]() {
                      body->write_vtu(ub, path, 0, 1);
                    });
                  pvd_records[b].emplace_back(double(step), name + ".vtu");
                  continue;
                }
              std::vector<std::string> pieces;
              for (unsigned int r = 0; r < n_pieces; ++r)
                pieces.push_back(name + "." +
                                 Utilities::int_to_string(
                                   r,
                                   Utilities::needed_digits(n_pieces - 1)) +
                                 ".vtu");
              if (rank < n_pieces)
                writer.add([body = bodies[b].get(),
                            ub   = u[b],
                            path = directory + "/" + pieces[rank],
                            rank,
                            n_pieces]() {
                  body->write_vtu(ub, path, rank, n_pieces);
                });
              if (rank == 0)
                writer.add([body = bodies[b].get(),
                            path = directory + "/" + name + ".pvtu",
                            pieces]() {
                  body->write_pvtu_record(path, pieces);
                });
              pvd_records[b].emplace_back(double(step), name + ".pvtu");
            }
        }

        void
        resume(const unsigned int              finished,
               const std::string              &directory,
               const std::vector<std::string> &names,
               const bool                      contact) override
        {
          // The files execute() wrote for steps 1..finished, by their
          // names (one process: no pieces).
          series_directory = directory;
          body_names       = names;
          if (!write_fields)
            return;
          pvd_records.resize(names.size() + (contact ? 1 : 0));
          for (unsigned int step = 1; step <= finished; ++step)
            {
              std::ostringstream number;
              number << std::setw(4) << std::setfill('0') << step;
              for (unsigned int b = 0; b < names.size(); ++b)
                pvd_records[b].emplace_back(double(step),
                                            "solution-" + names[b] + "-" +
                                              number.str() + ".vtu");
              if (contact)
                pvd_records.back().emplace_back(double(step),
                                                "contact-" + number.str() +
                                                  ".vtu");
            }
        }

        std::vector<std::pair<std::string, std::string>>
        series(const unsigned int steps) const override
        {
          std::vector<std::pair<std::string, std::string>> files;
          for (unsigned int b = 0; b < pvd_records.size(); ++b)
            {
              std::vector<std::pair<double, std::string>> kept;
              for (const auto &record : pvd_records[b])
                if (record.first <= double(steps))
                  kept.push_back(record);
              if (kept.empty())
                continue;
              std::ostringstream pvd;
              DataOutBase::write_pvd_record(pvd, kept);
              files.emplace_back(series_directory + "/" +
                                   (b < body_names.size() ?
                                      "solution-" + body_names[b] :
                                      std::string("contact")) +
                                   ".pvd",
                                 pvd.str());
            }
          return files;
        }

      private:
        /// Output/Write vtu; Body 1's contact faces (recovered pressures).
        const bool write_fields;
        /// Per interaction: its slave faces.
        std::vector<std::vector<types::boundary_id>> slave_faces;
        /// Per body, then for the pairs: (step, file) of each VTU.
        std::vector<std::vector<std::pair<double, std::string>>> pvd_records;
        base::BackgroundWriter                                  &writer;
        const unsigned int                                       this_rank;
        const unsigned int                                       ranks;
        /// Where the series go and the bodies' names (from the first step).
        std::string              series_directory;
        std::vector<std::string> body_names;
      };



      /**
       * The displacement and stress at every probe point after the last
       * load step, into the summary's points and point_stresses and a line
       * each to the log.
       */
      template <int dim>
      class Probes : public Postprocessor<dim>
      {
      public:
        std::string
        timer_section() const override
        {
          return "postprocess";
        }

        void
        execute(const StepContext<dim> &context,
                StepRecord &,
                RunSummary &summary) override
        {
          if (!context.last_step)
            return;
          const auto    &parameters = context.parameters;
          const auto    &bodies     = context.bodies;
          const auto    &u          = context.u;
          auto          &pcout      = context.screen;
          nlohmann::json points     = nlohmann::json::object();
          nlohmann::json stresses   = nlohmann::json::object();
          for (const ProbePoint &probe : parameters.probes)
            {
              const std::string &name = probe.name;
              const Point<dim>   x    = point_of<dim>(probe.location);
              // In a body: check_probe_points() before the solve.
              const unsigned int   b = body_holding<dim>(bodies, x);
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
              const SymmetricTensor<2, dim> sigma =
                bodies[b]->point_stress(u[b], x);
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = 0; j < dim; ++j)
                  AssertThrow(std::isfinite(sigma[i][j]),
                              ExcMessage(
                                "probe " + name +
                                ": the stress is not finite (overflow: "
                                "check the loads and Young's modulus "
                                "of the scene)."));
              std::vector<double> components;
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = i; j < dim; ++j)
                  components.push_back(sigma[i][j]);
              const auto    &material = bodies[b]->material();
              nlohmann::json entry    = {{"body", bodies[b]->name()},
                                         {"stress", components}};
              if (bodies[b]->finite_strain())
                {
                  // The Cauchy stress and the deformation at the point.
                  const Tensor<2, dim> grad_u =
                    bodies[b]->displacement_gradient(u[b], x);
                  const auto law = bodies[b]->finite_law();
                  const auto names =
                    elasticity::finite_strain_field_names<dim>();
                  std::vector<double> values(names.size());
                  elasticity::finite_strain_fields<dim>(grad_u,
                                                        law,
                                                        values.data());
                  for (unsigned int k = 0; k < names.size(); ++k)
                    if (names[k] == "von_mises" || names[k] == "det_F" ||
                        names[k] == "largest_stretch")
                      entry[names[k]] = values[k];
                  if (dim == 2)
                    {
                      const Tensor<2, dim> F =
                        elasticity::deformation_gradient(grad_u);
                      entry["stress_zz"] =
                        law.out_of_plane_second_piola(
                          elasticity::right_cauchy_green(F)) /
                        determinant(F);
                    }
                }
              else
                {
                  entry["von_mises"] =
                    elasticity::von_mises<dim>(sigma, material);
                  if (dim == 2)
                    entry["stress_zz"] =
                      elasticity::out_of_plane_stress<dim>(sigma, material);
                }
              stresses[name] = entry;
            }
          summary.points         = points;
          summary.point_stresses = stresses;
        }
      };
    } // namespace



    template <int dim>
    std::vector<std::unique_ptr<Postprocessor<dim>>>
    make_postprocessors(const AllParameters    &parameters,
                        const unsigned int      n_bodies,
                        const bool              root,
                        base::BackgroundWriter &writer)
    {
      std::vector<std::unique_ptr<Postprocessor<dim>>> postprocessors;
      if (parameters.output.fclib_export && root)
        postprocessors.push_back(std::make_unique<FclibExport<dim>>());
      postprocessors.push_back(std::make_unique<ModelRange<dim>>());
      postprocessors.push_back(std::make_unique<Forces<dim>>());
      postprocessors.push_back(
        std::make_unique<StepFiles<dim>>(parameters, n_bodies, writer));
      postprocessors.push_back(make_accuracy_checks<dim>());
      postprocessors.push_back(std::make_unique<Probes<dim>>());
      return postprocessors;
    }



    template std::vector<std::unique_ptr<Postprocessor<2>>>
    make_postprocessors<2>(const AllParameters &,
                           const unsigned int,
                           const bool,
                           base::BackgroundWriter &);
    template std::vector<std::unique_ptr<Postprocessor<3>>>
    make_postprocessors<3>(const AllParameters &,
                           const unsigned int,
                           const bool,
                           base::BackgroundWriter &);
  } // namespace scene
} // namespace igabde
