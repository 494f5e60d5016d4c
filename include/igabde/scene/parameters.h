#ifndef igabde_scene_parameters_h
#define igabde_scene_parameters_h

#include <igabde/base/choice_names.h>

#include <igabde/discretization/settings.h>

#include <igabde/elasticity/hyperelastic.h>
#include <igabde/elasticity/material.h>

#include <igabde/contact/condensation.h>
#include <igabde/contact/contact_solver.h>
#include <igabde/contact/pairing.h>
#include <igabde/contact/sliding.h>

#include <igabde/coupled/solver.h>
#include <igabde/scene/body_grammars.h>

#include <deal.II/base/parameter_handler.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {
    using namespace dealii;

    /** @brief Body N/Type. */
    enum class BodyType
    {
      /// A meshed elastic body.
      deformable,
      /// A flat obstacle with no mesh and no unknowns (not Body 1).
      rigid_plane,
      /// A circle (2D) or circular cylinder (3D) with no mesh and no
      /// unknowns (not Body 1).
      rigid_cylinder,
      /// A sphere (3D) with no mesh and no unknowns (not Body 1).
      rigid_sphere,
      /// Faces of an exact NURBS geometry (a built-in shape or a file),
      /// rigid: no mesh and no unknowns (not Body 1).
      rigid_surface,
      /// No such body (not Body 1).
      none
    };

    /** @brief Body N/Geometry: the built-in exact NURBS geometries. */
    enum class Geometry
    {
      box,
      quarter_annulus,
      thick_cylinder,
      plate_with_hole,
      hertz_quarter_disc,
      curved_beam,
      full_disc,
      half_disc,
      full_cylinder,
      half_cylinder,
      /// A G+Smo XML file (Body N/Geometry file).
      file
    };

    /** @brief Exact solution/Type. */
    enum class ExactSolutionType
    {
      none,
      /// Kirsch's plate with a hole (V1).
      kirsch,
      /// Lame's thick cylinder (V2).
      lame
    };

    /** @brief The names of each enum's values as the scene writes them. */
    inline constexpr base::ChoiceNames<BodyType, 6> body_type_names = {
      {{BodyType::deformable, "deformable"},
       {BodyType::rigid_plane, "rigid plane"},
       {BodyType::rigid_cylinder, "rigid cylinder"},
       {BodyType::rigid_sphere, "rigid sphere"},
       {BodyType::rigid_surface, "rigid surface"},
       {BodyType::none, "none"}}};

    /// Whether @p type is a rigid obstacle (no mesh, no unknowns).
    inline bool
    is_obstacle(const BodyType type)
    {
      return type == BodyType::rigid_plane ||
             type == BodyType::rigid_cylinder ||
             type == BodyType::rigid_sphere || type == BodyType::rigid_surface;
    }
    /** @copydoc body_type_names */
    inline constexpr base::ChoiceNames<Geometry, 11> geometry_names = {
      {{Geometry::box, "box"},
       {Geometry::quarter_annulus, "quarter annulus"},
       {Geometry::thick_cylinder, "thick cylinder"},
       {Geometry::plate_with_hole, "plate with hole"},
       {Geometry::hertz_quarter_disc, "hertz quarter disc"},
       {Geometry::curved_beam, "curved beam"},
       {Geometry::full_disc, "full disc"},
       {Geometry::half_disc, "half disc"},
       {Geometry::full_cylinder, "full cylinder"},
       {Geometry::half_cylinder, "half cylinder"},
       {Geometry::file, "file"}}};
    /** @copydoc body_type_names */
    inline constexpr base::ChoiceNames<ExactSolutionType, 3>
      exact_solution_type_names = {{{ExactSolutionType::none, "none"},
                                    {ExactSolutionType::kirsch, "kirsch"},
                                    {ExactSolutionType::lame, "lame"}}};

    /** @brief The name of each value as the scene writes it. */
    inline std::string
    to_string(const BodyType type)
    {
      return base::name_of(body_type_names, type);
    }
    /** @copydoc to_string(const BodyType) */
    inline std::string
    to_string(const Geometry geometry)
    {
      return base::name_of(geometry_names, geometry);
    }
    /** @copydoc to_string(const BodyType) */
    inline std::string
    to_string(const ExactSolutionType type)
    {
      return base::name_of(exact_solution_type_names, type);
    }

    /**
     * @brief Where and what a run writes.
     */
    struct OutputParameters
    {
      /// Output folder; empty means output/<scene name>/.
      std::string directory;
      /// Write VTU/PVD fields.
      bool write_vtu = true;
      /// Print the timing table on screen (off in tests: it is not
      /// reproducible); summary.json and timing.txt always get it.
      bool print_timing = true;
      /// Print progress lines (phase, elapsed seconds) for phases that can
      /// take long; --quiet turns them off.
      bool progress = true;
      /// Print only warnings and errors on screen (--quiet); log.txt keeps
      /// every line.
      bool quiet = false;
      /// Print the contact solver's line per solve (iterations, residuals,
      /// contact counts) and step-cut notices (off in scene tests: they are
      /// not physical results); summary.json always has them.
      bool solver_details = true;
      /// Write each body's geometry after refinement as a G+Smo XML file
      /// and its control net as VTU (--export-geometry).
      bool export_geometry = false;
      /// Write each load step's condensed contact problem, with the
      /// step's solution, as an FCLIB local problem (fclib-NNNN.hdf5).
      bool fclib_export = false;
      /// Write after each finished step what a later run needs to
      /// continue (checkpoint-NNNN.json, scene/checkpoint.h).
      bool checkpoint = false;
      /// Continue from the newest checkpoint in the output folder
      /// (igabde SCENE --restart FOLDER).
      bool restart = false;

      /// Declares the "Output" subsection.
      static void
      declare_parameters(ParameterHandler &prm);
      /// Reads the "Output" subsection.
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * @brief One deformable body (or, for Body 2, a rigid plane) as the
     * scene file writes it; turned into a BodyDescription by the simulator.
     */
    struct BodyParameters
    {
      BodyType type     = BodyType::deformable;
      Geometry geometry = Geometry::box;
      /// Box lower corner (m), dimension values; empty: the origin.
      std::vector<double> lower_corner;
      /// Box upper corner (m), dimension values; empty: all ones.
      std::vector<double> upper_corner;
      /// Radii of annulus-like geometries (m).
      double inner_radius = 1.;
      /// Radii of annulus-like geometries (m).
      double outer_radius = 2.;
      /// Radius of the Hertz quarter disc, the discs and cylinders (m).
      double radius = 8.;
      /// Centre of the discs (base centre of the cylinders) (m), dimension
      /// values; empty: the origin.
      std::vector<double> centre;
      /// Extrusion width of 3D geometries (m).
      double width = 1.;
      /// Half-size L of the plate with a hole (m).
      double plate_size = 4.;
      /// Geometry = file: the G+Smo XML file, as written in the scene
      /// (relative to the scene file's folder or absolute), and the path
      /// it resolves to.
      std::string geometry_file;
      std::string geometry_path;
      /// Number of patches of the geometry (of a file: read with the
      /// scene).
      unsigned int n_patches = 1;
      /// Knot spans per direction of the base mesh, before refinements
      /// (dimension counts, 1 to 9999).
      std::vector<unsigned int> subdivisions = {1, 1, 1};
      /// Grading of the spans per parametric direction (dimension entries):
      /// the ratio of the largest span to the smallest (1: uniform), the
      /// smallest at the low end of the direction (toward_high false) or
      /// at its high end. Read from "face: ratio; ...".
      std::vector<double> grading             = {1., 1., 1.};
      std::vector<bool>   grading_toward_high = {false, false, false};
      /// Per direction: a band {from, to} (fractions of the direction) the
      /// spans are graded toward instead of a face ('band d: from, to,
      /// ratio'); from = to: none.
      std::vector<std::array<double, 2>> grading_band = {{{0., 0.}},
                                                         {{0., 0.}},
                                                         {{0., 0.}}};
      /// Young's modulus (Pa).
      double youngs_modulus = 1000.;
      /// Poisson's ratio (-).
      double poisson_ratio = 0.3;
      /// Body N/Kinematics: small strain (linear elasticity) or finite
      /// strain (total Lagrangian, Newton's method per load step).
      elasticity::Kinematics kinematics = elasticity::Kinematics::small;
      /// Body N/Material: the law (linear at small strain only).
      elasticity::MaterialModel material = elasticity::MaterialModel::linear;
      /// Supports, read from "face: x y=0.1; face: z".
      std::vector<SupportParameters> supports;
      /// Point supports, read from "x, y[, z] : components; ...".
      std::vector<PointSupportParameters> point_supports;
      /// Hold rotation: the face whose mean rotation is held (-1: none).
      int hold_rotation_face = -1;
      /// Tractions, read from "face: pressure p; face: vector tx, ty;
      /// face: exact".
      std::vector<TractionParameters> tractions;
      /// Point loads, read from "x, y[, z] : fx, fy[, fz]; ...".
      std::vector<PointLoadParameters> point_loads;
      /// Moments on faces, read from "face: M; ..." (2D) or "face: Mx, My,
      /// Mz; ..." (3D).
      std::vector<MomentParameters> moments;
      /// Rigid face motions, read from "face: ux, uy, rz; ..." (2D) or
      /// "face: ux, uy, uz, rx, ry, rz; ..." (3D).
      std::vector<FaceMotionParameters> face_motions;
      /// Body force per volume (N/m^3), dimension values.
      std::vector<double> body_force;
      /// 'function fx; fy[; fz]': the body force's expressions of x, y[, z]
      /// (empty: the constant body_force).
      std::vector<std::string> body_force_expressions;
      /// Rigid plane: a point on it (m), dimension values.
      std::vector<double> plane_point = {0., 0., 0.};
      /// Rigid plane: the normal pointing towards Body 1 (not zero),
      /// dimension values.
      std::vector<double> plane_normal = {0., 1., 0.};
      /// Rigid cylinder (3D): the direction of its axis (not zero),
      /// dimension values.
      std::vector<double> axis = {0., 0., 1.};
      /// Rigid obstacles: the prescribed rigid motion, one term per entry
      /// of "ux, uy[, uz][, rotation] [@ history]; ...".
      std::vector<ObstacleMotionParameters> motion;

      /// Declares the subsection @p name ("Body 1" or "Body 2").
      static void
      declare_parameters(ParameterHandler  &prm,
                         const std::string &name,
                         const std::string &default_type);
      /**
       * @brief Reads the subsection @p name of a @p dimension-D scene and
       * refuses, with a one-line input error prefixed by @p context (the
       * scene file), what no body can have: E <= 0, nu outside (-1, 0.5),
       * a face the geometry does not have, a malformed support, traction or
       * point load. The grammar is read only for deformable bodies.
       */
      void
      parse_parameters(ParameterHandler  &prm,
                       const std::string &name,
                       const unsigned int dimension,
                       const std::string &context);
    };

    /**
     * @brief Exact solution of a verification scene.
     */
    struct ExactSolutionParameters
    {
      ExactSolutionType type = ExactSolutionType::none;
      /// Kirsch remote tension T_x (Pa).
      double remote_tension = 10.;
      /// Kirsch hole radius (m).
      double hole_radius = 1.;
      /// Lame inner radius a (m).
      double inner_radius = 1.;
      /// Lame outer radius b (m).
      double outer_radius = 2.;
      /// Lame internal pressure (Pa).
      double pressure = 1.;

      /// Declares the "Exact solution" subsection.
      static void
      declare_parameters(ParameterHandler &prm);
      /// Reads the "Exact solution" subsection.
      void
      parse_parameters(ParameterHandler &prm);
    };

    /// The most bodies (Body 1 ... Body 8) and contact interactions
    /// (the first in Contact, Contact/Interaction 2 ... 8) a scene has.
    inline constexpr unsigned int max_bodies = 8, max_interactions = 8;

    /**
     * @brief One contact interaction as the scene writes it: the first in
     * the Contact subsection itself (Body 1 on Body 2 unless it says
     * otherwise), the others in Contact/Interaction k.
     */
    struct InteractionParameters
    {
      /// Where the scene writes it ("Contact", "Contact/Interaction 2").
      std::string name = "Contact";
      /// The slave and master bodies (1-based, as the scene numbers them).
      unsigned int slave_body = 1, master_body = 2;
      /// The scene's Slave face and Master face as written.
      std::string slave_face_text = "2", master_face_text = "3";
      /// Patch faces of the slave and the master ('p.f' of a multi-patch
      /// body: p * 2 dim + f; several joined by '+'), read from the texts
      /// once the dimension and the bodies are known (check_scene()).
      std::vector<unsigned int> slave_faces = {2}, master_faces = {3};
      /// Coulomb friction coefficient mu (>= 0); 0 forms no tangential
      /// unknowns. friction_text: as written in Contact/Interaction k
      /// (empty: Contact's), read by check_scene().
      double      friction_coefficient = 0.;
      std::string friction_text;
      /// Slave points farther from the master than this are left out (m;
      /// 0: no limit). search_text: as written in Contact/Interaction k
      /// (empty: Contact's).
      double      search_distance = 0.;
      std::string search_text;
      /// Pairing strategy.
      contact::Pairing pairing = contact::Pairing::node_to_surface;
    };

    /**
     * @brief Contact: the solver settings and the interactions.
     */
    struct ContactParameters
    {
      /// Whether the scene has contact at all.
      bool enabled = false;
      /// The interactions (at least the first, Body 1 on Body 2).
      std::vector<InteractionParameters> interactions = {
        InteractionParameters()};
      /// Contact/Algorithm: bde, penalty or augmented-lagrange.
      contact::Algorithm algorithm = contact::Algorithm::bde;
      /// Contact/Path: condensed, full or auto.
      contact::Path path = contact::Path::automatic;
      /// Contact/Sliding = finite: pairs on the current configuration
      /// (ContactSettings::finite_sliding); small: formed once.
      bool finite_sliding = false;
      /// Contact/Sliding tangent (ContactSettings::sliding_tangent); full
      /// is the default.
      contact::SlidingTangent sliding_tangent = contact::SlidingTangent::full;
      /// FKN: normal penalty stiffness factor (penalty methods).
      double penalty_factor = 1.;
      /// FKT: stick stiffness factor, k_t = FKT k_n.
      double tangential_penalty_factor = 1.;
      /// Line search on the penalty Newton steps.
      bool penalty_line_search = true;
      /// Linear solver of the full path.
      coupled::Solver full_system_solver = coupled::Solver::mumps;
      /// GMRES iteration limit per Newton step (gmres-amg).
      unsigned int          krylov_max_iterations = 1000;
      contact::Condensation condensation = contact::Condensation::schur;
      /// Where pairs sit on a NURBS surface.
      discretization::PairPlacement pair_placement =
        discretization::PairPlacement::greville;
      /// Natural-map residual tolerance relative to ||q||.
      double tolerance = 1e-10;
      /// B-Newton iteration limit per load step.
      unsigned int max_iterations = 100;
      /// Scaling of the per-pair r (hard-case studies).
      double r_scale = 1.;
      /// Print every B-Newton iteration.
      bool verbose = false;
      /// How often a load increment whose contact solve fails may be halved.
      unsigned int max_step_cuts = 4;

      /// Declares the "Contact" subsection.
      static void
      declare_parameters(ParameterHandler &prm);
      /// Reads the "Contact" subsection.
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * @brief Named accuracy checks where the scene has an exact answer.
     */
    struct ChecksParameters
    {
      /// Expected uniform contact pressure (Pa); 0: no such check (V3).
      double uniform_pressure = 0.;
      /// Hertz line load P (N/m) on the cylinder of Body 1/Radius against a
      /// rigid flat; 0: no Hertz check (V5).
      double hertz_line_load = 0.;
      /// Hertz point load P (N) on the sphere of radius hertz_radius against
      /// a flat (3D, V7); 0: no such check.
      double hertz_point_load = 0.;
      /// Line load P (N/m) of a rigid flat punch with rounded corners
      /// (2D, Ciavarella, Hills & Monno), its flat half-width b and corner
      /// radius R (m); load 0: no such check.
      double rounded_punch_load            = 0.;
      double rounded_punch_flat_half_width = 0.;
      double rounded_punch_corner_radius   = 0.;
      /// Radius of the Hertz cylinder or sphere; 0: Body 1/Radius.
      double hertz_radius = 0.;
      /// A point on the Hertz symmetry axis, and its direction (dimension
      /// values each, read by AllParameters); empty: the origin and the
      /// last coordinate direction.
      std::vector<double> hertz_axis_point;
      std::vector<double> hertz_axis_direction;
      /// Their texts as the scene writes them.
      std::string hertz_axis_point_text;
      std::string hertz_axis_direction_text;
      /// Elliptical point contact: the principal curvatures (1/R, 0 for a
      /// flat direction) of Body 1 and Body 2 along the principal
      /// direction and across it, {k1x, k1y, k2x, k2y}; empty: the
      /// sphere of hertz_radius.
      std::vector<double> hertz_curvatures;
      /// Along which the first radius of each body is measured (3 values);
      /// empty: x.
      std::vector<double> hertz_principal_direction;
      std::string         hertz_radii_text;
      std::string         hertz_principal_direction_text;

      /// Declares the "Checks" subsection.
      static void
      declare_parameters(ParameterHandler &prm);
      /// Reads the "Checks" subsection.
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * @brief The load path: one load factor (scales tractions, point loads,
     * body force) and one displacement factor (scales prescribed
     * displacements) per step.
     */
    struct LoadPathParameters
    {
      /// Number of load steps for proportional loading.
      unsigned int n_steps = 1;
      /// Explicit load factors per step (overrides proportional).
      std::vector<double> load_factors;
      /// Explicit displacement factors per step.
      std::vector<double> displacement_factors;
      /// Named load histories: a factor per step each, referenced from
      /// load entries by '@ name'.
      std::vector<std::pair<std::string, std::vector<double>>> histories;
      /**
       * @brief Histories that are not named by the user: the load of a
       * t-dependent expression at one step each. Entry j is the 0-based
       * step at which history 2 + histories.size() + j has factor 1 (0 at
       * every other step). Added by AllParameters::parse_parameters.
       */
      std::vector<unsigned int> step_history_steps;

      /// Declares the "Load path" subsection.
      static void
      declare_parameters(ParameterHandler &prm);
      /// Reads the "Load path" subsection.
      void
      parse_parameters(ParameterHandler &prm);

      /// Load and displacement factor of every step.
      std::vector<std::pair<double, double>>
      steps() const;

      /**
       * @brief The factors of every history at every step: [step][h], with
       * h = 0 the load factor, 1 the displacement factor and 2 + k the k-th
       * named history.
       */
      std::vector<std::vector<double>>
      history_factors() const;

      /**
       * @brief The index in history_factors() of the history a load entry
       * names (@p name; empty: @p default_index).
       */
      unsigned int
      history_index(const std::string &name,
                    const unsigned int default_index) const;
    };

    /**
     * @brief Newton's method of the bodies at finite strain: when a load
     * step's solve has converged and how often a step may be cut.
     */
    struct NonlinearSolverParameters
    {
      /// ||R|| over the free unknowns relative to the largest force of the
      /// solve at which Newton's method has converged.
      double tolerance = 1e-10;
      /// Newton iterations per solve.
      unsigned int max_iterations = 25;
      /// How often a load increment whose Newton solve fails may be halved.
      unsigned int max_step_cuts = 4;
      /// Backtracking on the residual norm (NewtonSettings::line_search).
      bool line_search = false;

      /// Declares the "Nonlinear solver" subsection.
      static void
      declare_parameters(ParameterHandler &prm);
      /// Reads the "Nonlinear solver" subsection.
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * @brief All parameters of a scene (step-44's AllParameters).
     */
    struct AllParameters
    {
      /// Scene name (from the file name unless set).
      std::string name;
      /// Spatial dimension, 2 or 3.
      unsigned int dimension = 2;
      /// Plane strain or plane stress (2D).
      elasticity::PlaneModel plane_model = elasticity::PlaneModel::plane_strain;
      /// Probe points, read from "name: x, y[, z]; ...".
      std::vector<ProbePoint> probes;
      /// Output.
      OutputParameters output;
      /// Discretisation.
      discretization::DiscretizationSettings discretization;
      /// Body 1 ... Body 8 (max_bodies; Type = none past the scene's
      /// last): Body 1 (Omega^1) is the first interaction's slave, Body 2
      /// (Omega^2) its master.
      std::vector<BodyParameters> bodies =
        std::vector<BodyParameters>(max_bodies);

      /// The bodies the scene has (those before the first Type = none).
      unsigned int
      n_bodies() const;

      /// The indices in bodies of the deformable bodies, in order (the
      /// simulator's and the contact stage's body b is Body
      /// deformable_bodies()[b] + 1).
      std::vector<unsigned int>
      deformable_bodies() const;

      /// The indices in bodies of the rigid obstacles, in order.
      std::vector<unsigned int>
      obstacle_bodies() const;
      /// Exact solution.
      ExactSolutionParameters exact;
      /// Contact.
      ContactParameters contact;
      /// Load path.
      LoadPathParameters load_path;
      /// Newton's method at finite strain.
      NonlinearSolverParameters nonlinear_solver;
      /// Accuracy checks.
      ChecksParameters checks;

      /// Declares every parameter.
      static void
      declare_parameters(ParameterHandler &prm);
      /// Reads every parameter; @p scene_file names the file in messages.
      void
      parse_parameters(ParameterHandler &prm, const std::string &scene_file);

      /// Whether a body of the scene is modelled at finite strain.
      bool
      finite_strain() const;
    };

    /**
     * @brief The checks of a read scene that need more than one subsection
     * (AllParameters::parse_parameters() calls it): each refuses a
     * combination no run can honour with a one-line input error prefixed
     * by @p f (the scene file and ': '). Some complete what they check
     * (the contact faces, the Hertz axis, the histories of t-dependent
     * tractions).
     */
    void
    check_scene(AllParameters &parameters, const std::string &f);

    /// The faces of a patch of @p body's geometry, as its grammars name
    /// them.
    PatchFaces
    patch_faces_of(const BodyParameters &body, const unsigned int dimension);

    /**
     * @brief Refuses a face of @p body (its supports, tractions, moments,
     * face motions, held rotation and @p more) on a patch that the body's
     * geometry does not have; @p where names the body.
     */
    void
    check_face_patches(const BodyParameters            &body,
                       const std::vector<unsigned int> &more,
                       const unsigned int               dimension,
                       const std::string               &where);

    /**
     * @brief Declares the "Discretization" subsection.
     */
    void
    declare_discretization_parameters(ParameterHandler &prm);

    /**
     * @brief Reads the "Discretization" subsection.
     */
    void
    parse_discretization_parameters(
      ParameterHandler                       &prm,
      discretization::DiscretizationSettings &settings);
  } // namespace scene
} // namespace igabde

#endif
