#ifndef igabde_contact_contact_stage_h
#define igabde_contact_contact_stage_h

#include <igabde/discretization/body.h>
#include <igabde/discretization/factorization_request.h>

#include <igabde/contact/condensation.h>
#include <igabde/contact/contact_law.h>
#include <igabde/contact/contact_path.h>
#include <igabde/contact/contact_problem.h>
#include <igabde/contact/contact_solver.h>
#include <igabde/contact/obstacle.h>
#include <igabde/contact/pairing.h>
#include <igabde/contact/path_cost.h>

#include <deal.II/base/timer.h>

#include <Eigen/Dense>

#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

namespace igabde
{
  namespace contact
  {
    using namespace dealii;

    /**
     * @brief One contact interaction: the patch faces of a slave body
     * against the faces of a master body or an obstacle, with its pairing
     * and its friction coefficient.
     */
    struct ContactInteraction
    {
      /// The slave body: its index in the stage's deformable bodies.
      unsigned int slave_body = 0;
      /// The master: a deformable body (its index), or, when master_body
      /// is numbers::invalid_unsigned_int, the obstacle of that index.
      unsigned int master_body = 1;
      unsigned int obstacle    = numbers::invalid_unsigned_int;
      /// Patch faces of the slave and of the master (a rigid surface's
      /// faces were chosen when it was built).
      std::vector<unsigned int> slave_faces = {2}, master_faces = {3};
      /// Pairing strategy (create_pairing_strategy()).
      Pairing pairing = Pairing::node_to_surface;
      /// Coulomb friction coefficient; 0 in every interaction forms no
      /// tangential unknowns.
      double friction_coefficient = 0.;
      /// Slave points farther from the master than this are left out (0:
      /// no limit).
      double search_distance = 0.;
      /// For messages: where the scene writes it ("Contact",
      /// "Contact/Interaction 2").
      std::string name = "Contact";
    };

    /**
     * @brief What the contact layer needs from the scene.
     */
    struct ContactSettings
    {
      /// The interactions (at least one); their pairs are numbered in this
      /// order.
      std::vector<ContactInteraction> interactions = {ContactInteraction()};
      /// For messages: the scene's name of each deformable body ("Body 3");
      /// empty: "Body b+1".
      std::vector<std::string> body_labels;
      /// The condensed path condenses through the bodies' Schur complements
      /// (Contact/Condensation = schur with the direct linear solver); else
      /// one solve per pair direction.
      bool schur_condensation = true;
      /// Solver (create_contact_solver()).
      ContactSolverSettings solver;
      /// Tolerance of the post-solve condition check.
      double check_tolerance = 1e-6;
      /// Prefix of input errors (the scene file).
      std::string context;
      /// Progress lines for phases that may take long.
      bool progress = true;
      /// Write the solver's one-line summary of every solve to the log.
      bool log_solves = true;
      /// Estimated sparse factor entries of each deformable body and the
      /// number of load steps: inputs of the cost model of Contact/Path =
      /// auto (path_cost.h).
      std::vector<double> factor_entries;
      unsigned int        n_load_steps = 1;
      /// Non-empty: Contact/Path = auto takes the full path for this
      /// reason (the condensed path's dense blocks would not fit in
      /// memory; scene::SizeEstimate::choose_path_for_memory()).
      std::string memory_path_reason;
      /// Contact/Sliding = finite: the pairs are formed again on the
      /// current configuration at the start of every load step (the set of
      /// slave points) and at every Newton iterate of the solve (their
      /// master points, frames and gaps); the full path only.
      bool finite_sliding = false;
      /// Contact/Sliding tangent: with finite sliding whether the Newton
      /// matrix takes the pairs' derivatives by the configuration
      /// (FiniteSliding::tangent).
      SlidingTangent sliding_tangent = SlidingTangent::frozen;
    };

    /**
     * @brief What one contact solve of a load step gave: a plain record for
     * the step table and summary.json.
     */
    template <int dim>
    struct StepResult
    {
      bool        converged = false;
      std::string diagnosis;
      /// What to change when the solve failed and no cut of the load
      /// helps (empty: the usual advice applies).
      std::string  advice;
      unsigned int iterations = 0;
      double       residual   = 0.;
      unsigned int n_open = 0, n_stick = 0, n_slip = 0, n_closed = 0;
      /// Post-solve condition check (only when converged).
      bool        conditions_passed = false;
      std::string first_violation;
      double      condition_check_max_violation = 0.;
      /// Resultant of the contact forces on the slave bodies (the masters
      /// carry the opposite); one per interaction in interaction_forces.
      Tensor<1, dim>              contact_force;
      std::vector<Tensor<1, dim>> interaction_forces;
      /// Largest penetration max(0, -u_n) (the penalty methods' answer
      /// carries one; length).
      double max_penetration = 0.;
      /// Multiplier updates of the augmented Lagrangian.
      unsigned int updates = 0;
      /// Residual of every iteration of the last solve (the solver's
      /// measure: relative natural map, or the penalty residual).
      std::vector<double> residual_history;
      /// GMRES iterations of every Newton step of the last solve (full
      /// path with Contact/Full system solver = gmres-amg; else empty).
      std::vector<unsigned int> linear_iterations;
    };

    /**
     * @brief The state of one pair after a solve, for output and checks.
     */
    template <int dim>
    struct PairState
    {
      /// The slave body's point.
      Point<dim> location;
      /// The same point in the reference configuration, where its stress
      /// is read (the recovered pressure): location itself with small
      /// sliding; with finite sliding the mean of the slave's control
      /// points or nodes by the pair's operator.
      Point<dim> material_location;
      /// The interaction of the pair (0: the first) and its slave body
      /// (the index in the stage's deformable bodies).
      unsigned int interaction = 0, slave_body = 0;
      /// Body 1's outward unit normal at the point.
      Tensor<1, dim> normal;
      /// Tributary area (share of a uniform pressure).
      double area = 0.;
      /// Local force components (normal first; tangents when frictional).
      std::vector<double> force_local;
      /// Local relative displacement: normal gap, then the tangential
      /// slip increments of the step.
      std::vector<double> displacement_local;
      /// The force on Body 1 and the slip, in global coordinates.
      Tensor<1, dim> force;
      Tensor<1, dim> slip;
      ContactStatus  status = ContactStatus::open;

      /// Normal force per tributary area.
      double
      pressure() const
      {
        return force_local[0] / area;
      }
    };

    /**
     * @brief Which contact effects the scene has, and sizes.
     */
    struct ContactSummary
    {
      unsigned int n_pairs        = 0;
      unsigned int n_unknowns     = 0;
      bool         friction       = false;
      bool         rigid_obstacle = false;
      /// The obstacles' kinds ("rigid plane", ...; empty: none, joined by
      /// ", " when there are several) and whether a motion is prescribed
      /// for one.
      std::string obstacle_kind;
      bool        obstacle_moves = false;
      /// Interactions and the pairs of each.
      unsigned int              n_interactions = 1;
      std::vector<unsigned int> interaction_pairs;
      bool                      initial_gaps         = false;
      unsigned int              floating_rigid_modes = 0;
      unsigned int              pairs_left_out       = 0;
      /// The slave points the pairing considered and left out at set-up
      /// (PairingExclusions): turned away from the master, beyond its
      /// extent, not projected; whether they are quadrature points.
      unsigned int slave_candidates       = 0;
      unsigned int left_out_not_facing    = 0;
      unsigned int left_out_outside       = 0;
      unsigned int left_out_unprojected   = 0;
      unsigned int left_out_degenerate    = 0;
      unsigned int left_out_beyond        = 0;
      bool         left_out_of_quadrature = false;
      /// Contact/Algorithm.
      Algorithm algorithm = Algorithm::bde;
      /// The path taken (condensed or full), and why (Contact/Path = auto
      /// decides).
      Path        path = Path::condensed;
      std::string path_reason;
      /// Nonzeros of the coupled Newton matrix (full path).
      double coupled_nonzeros = 0.;
      /// Contact/Path = auto: the estimated seconds of both paths (else
      /// both 0).
      double estimated_condensed_seconds = 0., estimated_full_seconds = 0.;
      /// The inputs of that cost model for the pairs kept.
      PathCostInputs cost_inputs;
      /// What the set-up noticed that makes a figure not mean what it
      /// seems (more contact unknowns than face unknowns: redundant rows);
      /// summary.json's warnings.
      std::vector<std::string> warnings;
    };

    /**
     * @brief The step driver of the contact between Body 1 and the surface
     * it faces (a face of Body 2, or an obstacle): pairs by a
     * PairingStrategy, the path (ContactPath: condensed or coupled, chosen
     * once by build_pairs()), one solve by a ContactSolver per load step,
     * the post-solve condition check, and the contact forces back to the
     * fields. It sees the bodies only through discretization::Body, writes
     * no file and knows no scene check: the postprocessors read
     * pair_states(). The simulator's part: setup(), then solve_step() per
     * load step.
     */
    template <int dim>
    class ContactStage
    {
    public:
      /**
       * @brief Keeps references; @p bodies holds the deformable bodies and
       * @p obstacles the rigid ones that the settings' interactions name
       * by index. @p coupled_factory builds the coupled system of the full
       * path (coupled::coupled_factory(); without one the full path is
       * refused).
       */
      ContactStage(
        const ContactSettings                                         &settings,
        const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
        std::vector<std::unique_ptr<Obstacle<dim>>> obstacles,
        std::ostream                               &log,
        const CoupledFactory<dim> &coupled_factory = CoupledFactory<dim>());

      ~ContactStage();

      /**
       * @brief Everything before the first load step, in order: the pairs
       * and frames, the path (condensed or full), each body's factorisation
       * as the path asks it (discretization::factorize_bodies(): a Schur
       * interface on the pairs' unknowns or none, K and the factor kept
       * or freed after the load cases), then the contact problem on that
       * path. @p factorized receives what the factorisations cost as soon
       * as they are done (progress, records), before the contact problem
       * is formed. Collective on the bodies' world.
       */
      void
      setup(
        TimerOutput &timer,
        const std::function<void(const discretization::FactorizationReport &)>
          &factorized = {});

      /// The path taken (condensed or full; known after setup()).
      Path
      path() const;

      /**
       * @brief Solves a load step at load factor @p load_factor
       * (which scales the loads that the equilibrium of floating bodies
       * balances): on entry @p u holds each body's displacement under the
       * external loads of this step, on exit, when the solve converged and
       * passed the condition check, the total displacement with the
       * contact forces. The stage's state moves on only then.
       */
      StepResult<dim>
      solve_step(const double                 load_factor,
                 std::vector<Vector<double>> &u,
                 TimerOutput                 &timer);

      /**
       * @brief As above, with one factor per load history
       * (Body::n_histories(): 0 the load factor, 1 the displacement
       * factor, 2.. named histories; missing ones count as 0).
       */
      StepResult<dim>
      solve_step(const std::vector<double>   &factors,
                 std::vector<Vector<double>> &u,
                 TimerOutput                 &timer);

      /**
       * @brief Why the loads at @p factors (as in solve_step()) cannot be
       * balanced by any contact forces, or an empty string. A free rigid
       * mode (a column of G) whose load the pairs can only push against in
       * the other direction (every pair's normal force, with its
       * tangential force inside Coulomb's cone, does work of one sign on
       * it) has no equilibrium, whatever the gaps and the flexibility: a
       * body pulled off the surface it rests on. A sufficient condition
       * for no solution (one mode at a time), never a false alarm; no
       * step cut helps, since the set of loads contact can balance is a
       * cone.
       */
      std::string
      unbalanceable_load(const std::vector<double> &factors) const;

      /**
       * @brief The state a load step starts from (forces, rigid-mode
       * amplitudes, the bodies' contact displacement on the full path,
       * the friction history), to retry a step.
       */
      struct State
      {
        ContactIterate             x;
        Eigen::VectorXd            u_rel;
        Eigen::VectorXd            previous_external;
        std::vector<ContactStatus> status;
        bool                       has_previous = false;
        /// The displacement of each body at finite strain at the end of
        /// the last step (empty for the others).
        std::vector<Vector<double>> finite_u;
        /// Finite sliding: every body's displacement at the end of the last
        /// step (the configuration the next step's pairs are formed on),
        /// and the pairs x's forces belong to, by (interaction, slave key).
        std::vector<Vector<double>>                                   sliding_u;
        std::vector<std::pair<unsigned int, types::global_dof_index>> keys;
        /// The history factors of the last step (where the moving
        /// obstacles were for sliding_u).
        std::vector<double> sliding_factors;
      };

      State
      save_state() const;

      void
      restore_state(const State &state);

      /// The pairs after the last solve (empty before the first).
      std::vector<PairState<dim>>
      pair_states() const;

      ContactSummary
      summary() const;

      /**
       * @brief What this rank holds for the contact (base::MemoryItem): the
       * pairs with their point operators, the condensed problem (W, the
       * rigid-mode columns) and the path's operator (the coupled system's
       * rows on the full path). After setup(); not collective.
       */
      std::vector<base::MemoryItem>
      memory_record() const;

      /**
       * @brief The largest tangential displacement between the two points
       * of a pair at the displacements @p u (total, not the step's slip),
       * relative to the pair spacing there (the distance from the pair's
       * point on Body 1 to the nearest other pair's), and that pair's
       * point: past 1, pairs formed once in the reference configuration no
       * longer face each other (the small-sliding model's range check).
       * Pairs whose current gap exceeds their spacing are left out: they
       * cannot touch in this configuration. Against a moving obstacle its
       * motion at the history factors @p factors is the other point's.
       * None against a rigid plane, whose gap and normal stay exact
       * whatever the slide.
       */
      std::optional<std::pair<double, Point<dim>>>
      largest_sliding(const std::vector<Vector<double>> &u,
                      const std::vector<double>         &factors) const;

      /**
       * Against a curved rigid obstacle: the largest angle (rad) by which
       * the obstacle's normal at a pair's current closest point has
       * turned from the reference normal the pair keeps, the pair's
       * tangential displacement relative to the obstacle over its
       * curvature radius, and the pair's point; over the pairs whose
       * current gap is at most their spacing. None without such an
       * obstacle.
       */
      std::optional<std::pair<double, Point<dim>>>
      largest_normal_turn(const std::vector<Vector<double>> &u,
                          const std::vector<double>         &factors) const;

      /// The contact forces of the last solve on body @p b as a load vector
      /// of its unknowns.
      Vector<double>
      contact_load(const unsigned int b) const;

      const std::vector<ContactPair<dim>> &
      pairs() const;

      /// The law's data and, on the condensed path, W.
      const ContactProblem &
      condensed_problem() const;

      double
      flexibility_asymmetry() const;

      const Eigen::VectorXd &
      forces() const;

      /// Local components per pair: 1 frictionless, dim with friction.
      unsigned int
      n_components() const;

      /**
       * @brief Whether a body is at finite strain: the full path then solves
       * its equilibrium with the contact (f_int(u) - f_ext - C^T p = 0 with
       * its tangent in every Newton iteration); solve_step() takes its
       * state from the last step, not from @p u.
       */
      bool
      finite_strain() const;

    private:
      /// The pairs and frames; chooses the path.
      void
      build_pairs(TimerOutput &timer);

      /// Appends @p pairs of interaction @p k to @p list, with the
      /// interaction's bodies or obstacle and friction coefficient.
      void
      append_pairs(std::vector<ContactPair<dim>> &&pairs,
                   const unsigned int              k,
                   std::vector<ContactPair<dim>>  &list) const;

      /**
       * @brief Finite sliding: the pairs of every interaction on the
       * configuration X + @p u of the bodies (Body::move_surfaces()), the
       * moving obstacles placed at the history factors @p factors
       * (PlacedObstacle), as the pairings form them there; with @p keys
       * (one sorted list per interaction) only the pairs whose slave keys
       * those name (PairingStrategy::make_pairs_of()).
       */
      std::vector<ContactPair<dim>>
      pairs_on(const std::vector<Vector<double>>                       &u,
               const std::vector<double>                               &factors,
               const std::vector<std::vector<types::global_dof_index>> &keys =
                 {}) const;

      /**
       * @brief pairs_on() into @p pairs, and where @p derivatives is not
       * nullptr each pair's derivatives by the bodies' unknowns there
       * (PairingStrategy::make_pairs_with_derivatives(); @p keys must then
       * name the pairs); false where an interaction's pairing has none in
       * closed form.
       */
      bool
      pairs_with_derivatives_on(
        const std::vector<Vector<double>>                       &u,
        const std::vector<double>                               &factors,
        const std::vector<std::vector<types::global_dof_index>> &keys,
        std::vector<ContactPair<dim>>                           &pairs,
        std::vector<PairDerivatives<dim>> *derivatives) const;

      /// The bodies' displacements on the configuration that the
      /// correction @p w reaches from sliding_base.
      std::vector<Vector<double>>
      configuration_at(const Eigen::VectorXd &w) const;

      /// ContactPair::step_slip of the step's pair @p pair on the
      /// configuration @p relative (from_paired_configuration()).
      Tensor<1, dim>
      step_slip_of(const ContactPair<dim>            &pair,
                   const std::vector<Vector<double>> &relative) const;

      /**
       * @brief Finite sliding's full tangent in closed form
       * (FiniteSliding::linearization_of): the pairs of pairs_of() with the
       * derivatives of their gaps, frames, slips and operators; false where
       * a pairing has none.
       */
      bool
      linearization_of(const Eigen::VectorXd               &w,
                       const std::vector<unsigned int>     &indices,
                       std::vector<PairLinearization<dim>> &result) const;

      /**
       * @brief Finite sliding, at the start of a step after the first: the
       * pairs formed on the last step's configuration, the operator on
       * them, the last forces and states carried over by slave key.
       */
      void
      form_step_pairs(TimerOutput &timer);

      /**
       * @brief Finite sliding: the pairs of the step's set on the
       * configuration the correction @p w reaches from sliding_base (the
       * operator's FiniteSliding::pairs_at): each as pairs_on() forms it
       * there, or, one whose slave part no longer faces the master, the
       * step's own, with its gap carried linearly.
       */
      std::vector<ContactPair<dim>>
      pairs_at(const Eigen::VectorXd &w) const;

      /// The pairs of pairs_at() numbered @p indices in the step's set, in
      /// that order, as pairs_at() forms them (FiniteSliding::pairs_of).
      std::vector<ContactPair<dim>>
      pairs_of(const Eigen::VectorXd           &w,
               const std::vector<unsigned int> &indices) const;

      /// pairs_at() for the pairs @p indices of the step's set (nullptr:
      /// all, formed by one make_pairs() per interaction).
      std::vector<ContactPair<dim>>
      pairs_at(const Eigen::VectorXd           &w,
               const std::vector<unsigned int> *indices) const;

      /// The (interaction, slave key) of every pair of the list.
      std::vector<std::pair<unsigned int, types::global_dof_index>>
      pair_keys() const;

      /// @p v less paired_at, body by body (finite sliding; @p v itself
      /// when the pairs are the reference ones).
      std::vector<Vector<double>>
      from_paired_configuration(const std::vector<Vector<double>> &v) const;

      /// Forms the contact problem on the chosen path (the bodies
      /// factorised) and reports what was formed.
      void
      prepare(TimerOutput &timer);

      /// The pairs' relative displacements in their frames: Body 1's
      /// point's less the other body's, or less the obstacle's motion at
      /// the history factors @p factors.
      /// The largest tangential displacement of a pair, Body 1's point's
      /// less the other's (or the obstacle's motion), over the pair
      /// spacing or, @p over_radius, the obstacle's curvature radius; over
      /// the pairs whose current gap is at most their spacing.
      std::pair<double, Point<dim>>
      largest_tangential(const std::vector<Vector<double>> &u,
                         const std::vector<double>         &factors,
                         const bool                         over_radius) const;

      Eigen::VectorXd
      relative_displacement(const std::vector<Vector<double>> &u,
                            const std::vector<double>         &factors) const;

      /// The warm start, or the bilateral start of the path, whichever
      /// has the smaller natural-map plus equilibrium residual.
      ContactIterate
      initial_guess() const;

      /// Pairs expected closed: touching at the start, later those closed
      /// at the end of the previous step.
      std::vector<bool>
      expected_closed() const;

      Tensor<1, dim>
      global_force(const unsigned int i, const Eigen::VectorXd &p) const;

      /// The loads the free rigid modes must balance at @p factors (the
      /// equilibrium's right-hand side b, G^T p = b).
      Eigen::VectorXd
      rigid_mode_load(const std::vector<double> &factors) const;

      /**
       * @brief The inputs of the cost model of Contact/Path = auto for the
       * pairs built (face unknowns from the pair operators, factor entries
       * and load steps from the settings).
       */
      PathCostInputs
      compute_path_cost_inputs() const;

      /**
       * @brief The contact unknowns whose direction moves some unknown not
       * held by supports, on either side: a direction held on both sides
       * (the tangent of a pair on a symmetry plane) is a zero row of the
       * flexibility and is not counted.
       */
      unsigned int
      n_moving_contact_unknowns() const;

      /// The obstacle pair @p i faces (nullptr: a deformable body).
      const Obstacle<dim> *
      obstacle_of(const ContactPair<dim> &pair) const;

      /// The scene's name of deformable body @p b ("Body 1").
      std::string
      body_label(const unsigned int b) const;

      const ContactSettings                                          settings;
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies;
      const std::vector<std::unique_ptr<Obstacle<dim>>>              obstacles;
      const CoupledFactory<dim> coupled_factory;
      /// Per interaction: the master surface of a deformable master (else
      /// nullptr) and the pairing strategy.
      std::vector<std::unique_ptr<ContactSurface<dim>>>  master_faces;
      std::vector<std::unique_ptr<PairingStrategy<dim>>> pairings;
      std::unique_ptr<ContactSolver>                     solver;
      std::unique_ptr<ContactPath<dim>>                  contact_path;
      std::ostream                                      &log;

      unsigned int                  m = 1;
      std::vector<ContactPair<dim>> pair_list;
      /// Per pair: the distance to the nearest other pair (largest_sliding()).
      std::vector<double>   pair_spacing;
      CondensedContact<dim> contact;
      /// The path taken, and why; the names of its phases.
      Path        resolved_path = Path::condensed;
      std::string path_why;
      std::string prepare_section, solver_section, solver_label;
      /// Contact/Path = auto: the cost model's estimates (seconds).
      double estimated_condensed_seconds = 0., estimated_full_seconds = 0.;
      /// The cost model's inputs and the set-up's warnings (prepare()).
      PathCostInputs           cost_inputs;
      std::vector<std::string> setup_warnings;

      /// The last solve's unknowns (w: the contact part of the
      /// displacement on the full path).
      ContactIterate             x;
      Eigen::VectorXd            u_rel, previous_external;
      std::vector<ContactStatus> status;
      /// The displacement of each body at finite strain after the last
      /// step (State::finite_u).
      std::vector<Vector<double>> finite_u;
      bool                        has_previous = false;

      /// Finite sliding (ContactSettings::finite_sliding): every body's
      /// displacement at the end of the last step; the configuration the
      /// pairs of pair_list were formed on (empty: the reference one); the
      /// displacement the correction w of the solve adds to; the keys of
      /// the pairs x's forces belong to.
      std::vector<Vector<double>> sliding_u, paired_at, sliding_base;
      /// The history factors of sliding_u (State::sliding_factors), of
      /// paired_at and of the solve (where the moving obstacles are).
      std::vector<double> sliding_factors, paired_factors, solve_factors;
      std::vector<std::pair<unsigned int, types::global_dof_index>> x_keys;
    };
  } // namespace contact
} // namespace igabde

#endif
