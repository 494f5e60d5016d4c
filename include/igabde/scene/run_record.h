#ifndef igabde_scene_run_record_h
#define igabde_scene_run_record_h

#include <deal.II/base/timer.h>

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief The reaction of one face motion (Body n/Face motions): the
     * force and the moment about the face's centroid that the coupling
     * applies to the body.
     */
    struct FaceMotionReaction
    {
      unsigned int        face = 0;
      std::vector<double> force;
      /// z in 2D; x, y, z in 3D.
      std::vector<double> moment;
    };

    /**
     * @brief The forces of one body (or of the rigid obstacle) at the end of
     * a load step.
     */
    struct BodyForceRecord
    {
      /// body1, body2 or obstacle.
      std::string name;
      /// Resultant of the contact forces on the body.
      std::vector<double> contact_force;
      /// Resultant of the support reactions (none for the obstacle).
      std::optional<std::vector<double>> support_reaction;
      /// Moment of the held rotations' reaction (Hold rotation; z in 2D,
      /// x y z in 3D), about the held face's centroid.
      std::optional<std::vector<double>> held_moment;
      /// One per face motion of the body, in the scene's order.
      std::vector<FaceMotionReaction> face_motion_reactions;
    };

    /**
     * @brief The Newton solves of the bodies at finite strain in one load
     * step (summed over the bodies; the residuals are the last solve's).
     */
    struct NewtonRecord
    {
      unsigned int iterations = 0;
      /// Newton solves (1 + 2 per step cut that succeeded).
      unsigned int solves    = 0;
      unsigned int step_cuts = 0;
      /// The largest final relative residual over the bodies.
      double residual = 0.;
      /// The relative residual before each iteration and at the end of the
      /// last solve (of the last body at finite strain).
      std::vector<double> residual_history;
      /// The smallest det F at the quadrature points at the end.
      double min_det_F = 0.;
    };

    /**
     * @brief What one load step left: an entry of summary.json's
     * "load_steps" and a row of steps.csv.
     */
    struct StepRecord
    {
      /// 1-based step number.
      unsigned int step                = 0;
      double       load_factor         = 0.;
      double       displacement_factor = 0.;
      /// Factor of every named load history (Load path/Histories), in the
      /// order declared.
      std::vector<std::pair<std::string, double>> history_factors;

      /// Whether the step went through the contact solver; the figures
      /// below up to condition_check_max_violation exist only then.
      bool         contact           = false;
      unsigned int newton_iterations = 0;
      unsigned int contact_solves    = 0;
      unsigned int step_cuts         = 0;
      double       residual          = 0.;
      unsigned int n_open = 0, n_stick = 0, n_slip = 0, n_closed = 0;
      /// Penalty methods only.
      std::optional<double> max_penetration;
      /// Augmented Lagrange only.
      std::optional<unsigned int> multiplier_updates;
      std::vector<double>         residual_history;
      /// Iterative full-system solvers only (empty otherwise).
      std::vector<unsigned int> krylov_iterations;
      /// A step whose contact solve failed: why (and no forces).
      bool        failed = false;
      std::string diagnosis;
      /// What to change (the solver's advice, or the usual one).
      std::string advice;
      /// Finished contact steps.
      std::optional<double> condition_check_max_violation;
      /// Scenes with a body at finite strain.
      std::optional<NewtonRecord> finite_strain;

      /// Forces of a finished step, per body (empty for a failed one).
      std::vector<BodyForceRecord> bodies;
      /// Contact force on Body 1 (contact scenes, finished steps).
      std::optional<std::vector<double>> total_contact_force;
      /// With several contact interactions: the resultant of each one's
      /// pair forces on its slave body (finished steps; else empty).
      std::vector<std::vector<double>> interaction_forces;
      /// The largest principal strain of the bodies (finished steps).
      std::optional<double> largest_strain;
      /// ContactStage::largest_sliding() (contact scenes, finished steps).
      std::optional<double> largest_sliding;
      /// ContactStage::largest_normal_turn() (rad; against a curved
      /// obstacle, finished steps).
      std::optional<double> largest_normal_turn;
    };

    /// The load step as summary.json writes it.
    nlohmann::json
    to_json(const StepRecord &record);

    /**
     * @brief The run as summary.json writes it.
     */
    struct RunSummary
    {
      std::string scene;
      /// running, ok, failed (or interrupted, rendered for the handler).
      std::string  status = "running";
      std::string  error;
      int          dim = 2;
      std::string  discretization;
      unsigned int degree      = 0;
      unsigned int refinements = 0;
      std::string  memory_allocator;
      /// The size guard's estimate (SizeEstimate::to_json()).
      std::optional<nlohmann::json>     size_estimate;
      std::optional<unsigned long long> n_dofs;
      std::optional<unsigned int>       n_elements;
      /**
       * The facts the set-up of the bodies and of the contact stage reports
       * ("bodies", "effects", the contact path and its costs, ...), as the
       * keys of summary.json they are written to.
       */
      nlohmann::json setup = nlohmann::json::object();
      /// The finished load steps and a failed one.
      std::vector<StepRecord> load_steps;
      /// The contact force on Body 1 at the last finished step.
      std::optional<std::vector<double>> total_contact_force;
      /// Accuracy checks of the last step (postprocess).
      std::optional<nlohmann::json> checks;
      std::vector<std::string>      warnings;
      /// Probe displacements and stresses of the last step.
      std::optional<nlohmann::json> points;
      std::optional<nlohmann::json> point_stresses;
      /// Seconds per timer phase and "total" (the largest over the ranks).
      std::optional<std::map<std::string, double>> timing;
      /// Wall seconds the background threads spent writing step files,
      /// summed over files (they overlap the run; timing's "output" is
      /// what the run waited).
      double output_background_seconds = 0.;
      /// Processes the run used (mpirun -np N).
      unsigned int mpi_ranks = 1;
      /// Per rank: its peak memory and the bodies it factorised.
      std::optional<nlohmann::json> ranks;
    };

    /// The run as summary.json writes it.
    nlohmann::json
    to_json(const RunSummary &summary);

    /// Seconds per phase of @p timer, and their sum as "total".
    std::map<std::string, double>
    timing_seconds(const dealii::TimerOutput &timer);

    /**
     * @brief steps.csv: one row per load step of @p records, full precision.
     * @p histories names the load histories (a column each); @p contact adds
     * the contact columns and the force of @p dim components, @p finite
     * those of the Newton solves at finite strain.
     */
    std::string
    step_table(const std::vector<StepRecord>  &records,
               const std::vector<std::string> &histories,
               const bool                      contact,
               const bool                      finite,
               const unsigned int              dim);
  } // namespace scene
} // namespace igabde

#endif
