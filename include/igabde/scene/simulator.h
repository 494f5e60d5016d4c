#ifndef igabde_scene_simulator_h
#define igabde_scene_simulator_h

#include <igabde/base/files.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/factorization_request.h>
#include <igabde/discretization/finite_strain_solver.h>

#include <igabde/scene/parameters.h>
#include <igabde/scene/postprocessors.h>
#include <igabde/scene/rank_split.h>
#include <igabde/scene/run_record.h>
#include <igabde/scene/scene_reader.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <map>
#include <memory>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace contact
  {
    template <int dim>
    class ContactStage;
  }

  namespace scene
  {
    using namespace dealii;

    /**
     * @brief Runs one scene: bodies, load steps (with contact when the scene
     * asks for it), postprocessing, output. Data flows one way: parameters →
     * bodies → contact → load steps → output.
     */
    template <int dim>
    class Simulator
    {
    public:
      /**
       * @brief Keeps the parameters; nothing is built yet.
       * @param parameters The parsed scene.
       * @param scene_file The scene file, for messages.
       * @param output_directory Existing folder for every output file.
       * @param log Screen log (also copied to log.txt by the caller).
       */
      Simulator(const AllParameters &parameters,
                const std::string   &scene_file,
                const std::string   &output_directory,
                std::ostream        &log);

      ~Simulator();

      /// Builds, solves every load step and writes all output.
      void
      run();

      /// The summary as written to summary.json.
      nlohmann::json
      get_summary() const;

      /**
       * @brief Writes summary.json with status "failed" and @p message,
       * keeping everything finished so far.
       */
      void
      write_failed_summary(const std::string &message);

    private:
      /// Builds and assembles the bodies (and the exact solution).
      void
      setup_bodies();

      /**
       * Prints what the bodies' factorisations cost (progress lines) and
       * records their factor sizes in the summary. The factorisations
       * themselves run in discretization::factorize_bodies(), called by the
       * contact stage's setup() (or directly without contact): under MPI
       * with the direct solver the ranks are split among the bodies (in
       * proportion to their estimated factor sizes), each group factorises
       * its body at the same time as the others, and the results are
       * shared with every rank.
       */
      void
      record_factorization(const discretization::FactorizationReport &report);

      /// With contact: the contact stage (pairs, condensation or coupled
      /// system) and its facts in the summary; the factorisation either way.
      void
      setup_contact();

      void
      solve_load_steps();

      /**
       * A run with Output/Restart: reads the newest checkpoint of the
       * output folder, refuses one of another @p scene (its parameters
       * without Output) or with no step left of the @p n_steps, and
       * restores from it @p previous (the factors of its step), the
       * bodies' @p finite_state, the contact stage's state, the finished
       * steps' records and warnings and the postprocessors' series.
       * Returns the number of finished steps.
       */
      unsigned int
      resume(const nlohmann::json        &scene,
             const unsigned int           n_steps,
             std::vector<double>         &previous,
             std::vector<Vector<double>> &finite_state);

      /**
       * The Newton solves of load step @p step of the bodies at finite
       * strain, from their @p state at the factors @p previous (the last
       * finished step) to the equilibrium at @p factors (with step cuts):
       * @p state and @p u of those bodies hold it after, @p record its
       * figures. A body that cannot reach it ends the run with one line
       * (the record of the failed step kept).
       */
      void
      solve_finite_strain_step(const unsigned int                    step,
                               const std::vector<double>            &previous,
                               const std::vector<double>            &factors,
                               const discretization::NewtonSettings &settings,
                               std::vector<Vector<double>>          &state,
                               std::vector<Vector<double>>          &u,
                               StepRecord                           &record);

      /**
       * Writes summary.json and steps.csv from run_summary, timing.txt and
       * the PVD series. With @p status "running" only if a second has
       * passed since the last time (the summary is published to the signal
       * handler either way); always otherwise.
       */
      void
      write_summary(const std::string &status, const std::string &error);

      /// The stream the contact layer logs to (a discarding one off rank 0).
      std::ostream &
      contact_log();

      const AllParameters parameters;
      const std::string   scene_file;
      const std::string   output_directory;
      /// Whether this process writes files and the log (MPI rank 0).
      const bool root;
      /// The log, printed on rank 0 only.
      ConditionalOStream pcout;

      /// The timer's table, written to timing.txt and, unless switched off,
      /// to the log.
      std::ostringstream timing_table;
      TimerOutput        timer;
      /// What summary.json and steps.csv are written from.
      RunSummary run_summary;
      /// The set-up facts of run_summary (RunSummary::setup), as the bodies
      /// and the contact stage fill them in.
      nlohmann::json &summary;

      /// The communicators of the body groups (split_ranks_among_bodies()),
      /// freed after the bodies (declared before them).
      Communicators body_groups;
      /// Names of the bodies this rank factorises.
      std::vector<std::string> factorised_here;
      /// Factor entries of each body from the run's size estimate (the
      /// rank split and Contact/Path = auto use them).
      std::vector<double> estimated_factor_entries;
      /// Why Contact/Path = auto must take the full path (memory), or "".
      std::string memory_path_reason;
      /// The timing written by write_summary() once gather_rank_figures()
      /// has run (the largest seconds per phase over the ranks).
      std::optional<std::map<std::string, double>> final_timing;

      std::optional<discretization::ExactSolution<dim>>       exact;
      std::vector<std::unique_ptr<discretization::Body<dim>>> bodies;
      std::unique_ptr<contact::ContactStage<dim>>             contact_stage;
      /// Writes the step files while the next step runs; declared after the
      /// bodies, so that it is destroyed (waits for its jobs) before them.
      base::BackgroundWriter writer;
      /// What the run computes and writes after each load step, in order.
      std::vector<std::unique_ptr<Postprocessor<dim>>> postprocessors;
      /// Time since write_summary() last wrote its files.
      Timer since_written;
      bool  written_once = false;
      /// Load steps taken from a checkpoint (--restart): the writer's first
      /// group is the step after them.
      unsigned int resumed_steps = 0;
      /// Where the run is, for the reason an interrupted run gives.
      std::string run_phase;
    };

    /**
     * @brief Runs a scene in this process (tests, studies) and returns its
     * summary; the log goes to @p log. Throws on bad input or failure.
     */
    nlohmann::json
    run_scene_in_process(
      const std::string                                      &scene_file,
      const std::vector<std::pair<std::string, std::string>> &overrides,
      std::ostream                                           &log);

    /**
     * @brief Parses @p scene_file (with the --set overrides) and runs it in
     * the right dimension. Returns the process exit status.
     */
    int
    run_scene(const std::string &scene_file,
              const std::vector<std::pair<std::string, std::string>> &overrides,
              const bool force = false);
  } // namespace scene
} // namespace igabde

#endif
