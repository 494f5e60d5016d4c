#ifndef igabde_contact_contact_stage_h
#define igabde_contact_contact_stage_h

#include <igabde/base/json.h>

#include <igabde/discretization/body.h>

#include <igabde/contact/bnewton.h>
#include <igabde/contact/contact_problem.h>

#include <deal.II/base/timer.h>

#include <Eigen/Dense>

#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    using namespace dealii;

    /**
     * @brief The contact solver did not converge in a load step (the
     * simulator may cut the increment and retry).
     */
    DeclException1(ExcContactNotConverged, std::string, << arg1);

    /**
     * @brief What the contact layer needs from the scene.
     */
    template <int dim>
    struct ContactSettings
    {
      /// Coulomb friction coefficient; 0 forms no tangential unknowns.
      double friction_coefficient = 0.;
      /// Patch face of Body 1 (slave) and Body 2 (master) that may touch.
      unsigned int slave_face = 2, master_face = 3;
      /// Rigid obstacle instead of a deformable Body 2.
      bool rigid_plane = false;
      /// Rigid plane: a point on it and the unit normal towards Body 1.
      Point<dim> plane_point;
      /// Rigid plane: normal towards Body 1.
      Tensor<1, dim> plane_normal;
      /// B-Newton settings (tolerance, iteration limit, r scale, logging).
      BNewtonSolver::Settings solver;
      /// Tolerance of the post-solve condition check (scaled violations).
      double check_tolerance = 1e-6;
      /// Expected uniform pressure (V3 check), 0: none.
      double uniform_pressure = 0.;
      /// Hertz line load (V5 check), 0: none.
      double hertz_line_load = 0.;
      /// Hertz cylinder radius (m).
      double hertz_radius = 0.;
      /// Scene file, for messages.
      std::string scene_file;
      /// Print progress lines for the phases that can take long.
      bool progress = true;
    };

    /**
     * @brief One node-to-node contact pair: a point on Body 1 and the point
     * of Body 2 (or of the rigid plane) that faces it.
     */
    template <int dim>
    struct PointPair
    {
      /// Point on Body 1 (m).
      Point<dim> x1;
      /// Facing point on Body 2 or the plane (m).
      Point<dim> x2;
      /// Rows: n (outward normal of Body 2, towards Body 1), a[, b].
      Tensor<2, dim> frame;
      /// Initial normal gap (m), >= 0 when open.
      double gap = 0.;
      /// Tributary area of the pair on Body 1 (m^2, m in 2D).
      double area = 0.;
      /// Displacement operators on Body 1 and Body 2 (empty: rigid).
      discretization::PointOperator<dim> op1, op2;
    };

    /**
     * @brief The contact layer between two bodies (or a body and a rigid
     * plane): pairs and frames, condensation into the flexibility F^L with
     * the rigid modes of floating bodies, one BDE solve per load step, the
     * post-solve condition check, and contact forces back to the fields.
     * It sees the bodies only through discretization::Body.
     */
    template <int dim>
    class ContactStage
    {
    public:
      /**
       * @brief Keeps references; @p bodies holds Body 1 and, unless the
       * obstacle is rigid, Body 2.
       */
      ContactStage(
        const ContactSettings<dim>                                    &settings,
        const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
        std::ostream                                                  &log);

      /**
       * @brief Builds the pairs and frames (the bodies need not be
       * factorised yet).
       */
      void
      build_pairs(TimerOutput &timer);

      /**
       * @brief The point operators of the pairs on body @p b: the unknowns
       * on which a Schur complement serves the condensation.
       */
      std::vector<discretization::PointOperator<dim>>
      contact_operators(const unsigned int b) const;

      /**
       * @brief Condenses onto the pairs (the bodies must be factorised) and
       * reports what was formed.
       */
      void
      condense(TimerOutput &timer);

      /**
       * @brief Solves the load step @p step at load factor @p load_factor
       * (which scales the loads that the equilibrium of floating bodies
       * balances): on entry @p u holds each body's
       * displacement under the external loads of this step, on exit the
       * total displacement with the contact forces. Throws, with a
       * diagnosis, when the solver does not converge or the solution
       * violates a contact condition.
       */
      void
      solve_step(const unsigned int           step,
                 const double                 load_factor,
                 std::vector<Vector<double>> &u,
                 base::Json                  &record,
                 TimerOutput                 &timer);

      /**
       * @brief The state a load step starts from (forces, rigid-mode
       * amplitudes, the friction history), to retry a step.
       */
      struct State
      {
        /// Contact forces, local frames.
        Eigen::VectorXd p;
        /// Rigid-mode amplitudes.
        Eigen::VectorXd alpha;
        /// Relative displacements.
        Eigen::VectorXd u_rel;
        /// Relative displacement of the external loads (friction history).
        Eigen::VectorXd previous_external;
        /// Pair status.
        std::vector<ContactStatus> status;
        /// Whether a step has been solved.
        bool has_previous = false;
      };

      /// The state after the last solved step.
      State
      save_state() const;

      /// Returns to a saved state (after a failed attempt).
      void
      restore_state(const State &state);

      /// Writes contact-NNNN.csv and contact-NNNN.vtu for the last step.
      void
      write_step_output(const unsigned int step,
                        const std::string &directory) const;

      /// Adds effects, n_contact_pairs, n_contact_unknowns.
      void
      add_summary(base::Json &summary) const;

      /// Adds the named accuracy checks of the final step.
      void
      add_checks(base::Json &checks) const;

      /// Pairs in use.
      const std::vector<PointPair<dim>> &
      pairs() const;

      /// The condensed problem of the last step (W = F^L, q, mu, G, b).
      const ContactProblem &
      condensed_problem() const;

      /// Relative asymmetry |F - F^T| / |F| of the flexibility before it
      /// was symmetrised (round-off for a correct condensation).
      double
      flexibility_asymmetry() const;

      /// Contact forces of the last step, local frames (n_components per
      /// pair).
      const Eigen::VectorXd &
      forces() const;

    private:
      void
      form_pairs();

      void
      form_flexibility();

      Eigen::VectorXd
      relative_displacement(const std::vector<Vector<double>> &u) const;

      /// Start of the first load step's B-Newton iteration (p, alpha).
      std::pair<Eigen::VectorXd, Eigen::VectorXd>
      initial_guess() const;

      Tensor<1, dim>
      global_force(const unsigned int i, const Eigen::VectorXd &p) const;

      const ContactSettings<dim>                                     settings;
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies;
      std::ostream                                                  &log;

      unsigned int                n_components = 1;
      std::vector<PointPair<dim>> pair_list;
      unsigned int                n_dropped = 0;
      double                      asymmetry = 0.;
      ContactProblem              problem;
      /// Which body and mode each alpha belongs to.
      std::vector<std::pair<unsigned int, unsigned int>> alpha_modes;
      /// Rigid-mode loads R^T f_ext at load factor 1, per alpha.
      Eigen::VectorXd rigid_mode_loads;

      Eigen::VectorXd            p, u_rel, alpha, previous_external;
      std::vector<ContactStatus> status;
      bool                       has_previous = false;
    };
  } // namespace contact
} // namespace igabde

#endif
