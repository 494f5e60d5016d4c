#ifndef igabde_scene_postprocessors_h
#define igabde_scene_postprocessors_h

#include <igabde/base/files.h>

#include <igabde/discretization/body.h>

#include <igabde/contact/contact_stage.h>

#include <igabde/scene/parameters.h>
#include <igabde/scene/run_record.h>

#include <deal.II/base/conditional_ostream.h>

#include <deal.II/lac/vector.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief What a postprocessor sees at the end of a load step: the
     * scene, the bodies and their displacements, the contact state, and
     * where to write and log. Built by the simulator once per step.
     */
    template <int dim>
    struct StepContext
    {
      const AllParameters &parameters;
      /// The scene file, for messages.
      const std::string &scene_file;
      /// The run's output folder.
      const std::string &output_directory;
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies;
      /// The exact solution of a verification scene (empty otherwise).
      const std::optional<discretization::ExactSolution<dim>> &exact;
      /// The contact stage and its pairs after the step; nullptr without
      /// contact.
      const contact::ContactStage<dim>           *stage;
      const std::vector<contact::PairState<dim>> *pairs;
      /// Each body's displacement at the end of the step.
      const std::vector<Vector<double>> &u;
      /// The step's factor of every load history
      /// (LoadPathParameters::history_factors()).
      const std::vector<double> &factors;
      /// The step, from 1, and whether it is the last one.
      unsigned int step;
      bool         last_step;
      /// The log (rank 0) and the contact layer's log (discarding off
      /// rank 0).
      ConditionalOStream &screen;
      std::ostream       &log;
    };

    /**
     * @brief One result a run computes or writes at the end of load steps
     * (ASPECT's Postprocess::Interface): a check, a table, a file series.
     *
     * execute() runs on every rank after each load step, in the order
     * make_postprocessors() gives; what it finds goes to the step's
     * @p record (steps.csv, summary.json's load_steps) or to the run's
     * @p summary (checks, points, warnings).
     */
    template <int dim>
    class Postprocessor
    {
    public:
      virtual ~Postprocessor() = default;

      /// The phase of the timing table it is counted in ("postprocess" or
      /// "output").
      virtual std::string
      timer_section() const = 0;

      /// The step's results into @p record and @p summary.
      virtual void
      execute(const StepContext<dim> &context,
              StepRecord             &record,
              RunSummary             &summary) = 0;

      /**
       * @brief What it gathers over the steps (the PVD series) as files
       * (path, text), holding steps 1..@p steps only; the run writes them
       * whenever it writes summary.json, and an interruption writes those
       * of the steps it keeps.
       */
      virtual std::vector<std::pair<std::string, std::string>>
      series(const unsigned int steps) const
      {
        (void)steps;
        return {};
      }

      /**
       * A run that continues from a checkpoint after @p finished steps, in
       * the folder @p directory, of the bodies @p body_names and with
       * contact or not (@p contact): what the postprocessor would have
       * gathered over those steps (the series' earlier files).
       */
      virtual void
      resume(const unsigned int              finished,
             const std::string              &directory,
             const std::vector<std::string> &body_names,
             const bool                      contact)
      {
        (void)finished;
        (void)directory;
        (void)body_names;
        (void)contact;
      }
    };

    /**
     * @brief The accuracy checks (Checks: uniform pressure, Hertz line,
     * point and elliptical contact, error norms), after the last load step
     * (scene/accuracy_checks.cc).
     */
    template <int dim>
    std::unique_ptr<Postprocessor<dim>>
    make_accuracy_checks();

    /**
     * @brief The postprocessors of a scene, in the order they run: the FCLIB
     * export (Output/FCLIB export, on rank 0), the model's range, the
     * forces, the step files (pair table, VTU/PVD; their files written by
     * @p writer's threads), the accuracy checks and the probes (the last
     * two after the last step only).
     */
    template <int dim>
    std::vector<std::unique_ptr<Postprocessor<dim>>>
    make_postprocessors(const AllParameters    &parameters,
                        const unsigned int      n_bodies,
                        const bool              root,
                        base::BackgroundWriter &writer);
  } // namespace scene
} // namespace igabde

#endif
