#ifndef igabde_scene_body_grammars_h
#define igabde_scene_body_grammars_h

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace dealii
{
  template <int dim>
  class FunctionParser;
}

namespace igabde
{
  namespace scene
  {
    /**
     * @brief deal.II's FunctionParser for the @p dim components
     * @p expressions in the variables x, y[, z] and t (and the constant
     * pi), at time @p t. Evaluating it is thread-safe (the parser keeps
     * one muparser per thread).
     */
    template <int dim>
    std::shared_ptr<dealii::FunctionParser<dim>>
    make_function_parser(const std::vector<std::string> &expressions,
                         const double                    t);

    /**
     * @brief One entry of Body n/Supports: components held on a patch face.
     */
    struct SupportParameters
    {
      /// Patch face (boundary id of the parametric mesh).
      unsigned int face = 0;
      /// Held components x, y, z.
      std::array<bool, 3> components = {{false, false, false}};
      /// Prescribed displacement (m) of each held component at
      /// displacement factor 1.
      std::array<double, 3> values = {{0., 0., 0.}};
      /// Load history scaling the values ('@ name'; empty: Displacement
      /// factors).
      std::string history;
      /// A component given as 'c = function expr': its expression of x,
      /// y[, z] (empty: the constant value).
      std::array<std::string, 3> expressions;
    };

    /**
     * @brief One entry of Body n/Tractions.
     */
    struct TractionParameters
    {
      /// What the entry prescribes.
      enum class Kind
      {
        /// t = -p n with the pressure values[0] (Pa).
        pressure,
        /// The constant traction values (Pa), one per component.
        vector,
        /// sigma_exact n from the Exact solution.
        exact,
        /// Components given as expressions of x, y[, z] and t.
        function
      };
      /// Patch face (boundary id of the parametric mesh).
      unsigned int face = 0;
      /// Pressure, vector or exact.
      Kind kind = Kind::pressure;
      /// Pressure (one value) or traction (dimension values), in Pa.
      std::vector<double> values;
      /// Load history scaling the traction ('@ name'; empty: Load factors).
      std::string history;
      /// Kind::function: one expression per component (deal.II's
      /// FunctionParser syntax, variables x, y[, z] and t).
      std::vector<std::string> expressions;
      /// Kind::function: whether an expression uses t. Such a traction is
      /// the expression's value at t = the step's factor of its history
      /// (not scaled again); it enters the solve as one load history per
      /// step (LoadPathParameters::step_history_steps), so that every
      /// step's load is exact and the superposition of history solutions
      /// stays as for every other load.
      bool uses_t = false;
      /// uses_t: per step, the value of t and the index of its history in
      /// LoadPathParameters::history_factors() (set by AllParameters).
      std::vector<double>       step_t;
      std::vector<unsigned int> step_histories;
    };

    /**
     * @brief One entry of Body n/Point loads.
     */
    struct PointLoadParameters
    {
      /// Where the force acts (m), dimension values.
      std::vector<double> location;
      /// The force (N), dimension values.
      std::vector<double> force;
      /// Load history scaling the force ('@ name'; empty: Load factors).
      std::string history;
    };

    /**
     * @brief One entry of Body n/Point supports: components held at zero
     * at one point of the body (a node: a patch corner for NURBS, a mesh
     * node for FE_Q).
     */
    struct PointSupportParameters
    {
      /// Where (m), dimension values.
      std::vector<double> location;
      /// Held components x, y, z.
      std::array<bool, 3> components = {{false, false, false}};
      /// Prescribed values of the held components (m; 'x=0.01'), scaled
      /// by the step's displacement factor or the load history.
      std::array<double, 3> values = {{0., 0., 0.}};
      /// Load history scaling the values ('@ name'; empty: Displacement
      /// factors).
      std::string history;
    };

    /**
     * @brief One entry of Body n/Moments: a moment on a patch face, spread
     * over it as a distributing coupling spreads it.
     */
    struct MomentParameters
    {
      /// The patch face.
      unsigned int face = 0;
      /// The moment about the face's centroid (N m; N m/m in 2D): one value
      /// (about z) in 2D, three in 3D.
      std::vector<double> moment;
      /// Load history scaling the moment ('@ name'; empty: Load factors).
      std::string history;
    };

    /**
     * @brief One entry of Body n/Face motions: a patch face moved rigidly,
     * as a kinematic coupling moves it, by a displacement and a (small)
     * rotation about the face's centroid.
     */
    struct FaceMotionParameters
    {
      /// The patch face.
      unsigned int face = 0;
      /// The displacement of the face's centroid (m), dimension values,
      /// then the rotation (rad): one value (about z) in 2D, three in 3D.
      std::vector<double> motion;
      /// Load history scaling the motion ('@ name'; empty: Displacement
      /// factors).
      std::string history;
      /// The point the face turns about and whose displacement the motion
      /// gives ('about cx, cy[, cz]'), dimension values; empty: the face's
      /// centroid.
      std::vector<double> centre;
    };

    /**
     * @brief One term of a rigid obstacle's Motion: the translation (m),
     * dimension values, then the rotation (rad) about the obstacle's pivot
     * (one value about z in 2D, three in 3D), zero when the entry gives
     * the translation only.
     */
    struct ObstacleMotionParameters
    {
      std::vector<double> translation;
      std::vector<double> rotation;
      /// Load history scaling the term ('@ name'; empty: Displacement
      /// factors).
      std::string history;
    };

    /**
     * @brief Body n/Grading per parametric direction (dimension entries):
     * the ratio of the largest span to the smallest (1: uniform), the
     * smallest at the low end of the direction (toward_high false) or at
     * its high end, or in a band {from, to} of the direction (fractions;
     * from = to: none).
     */
    struct GradingParameters
    {
      std::vector<double>                ratio;
      std::vector<bool>                  toward_high;
      std::vector<std::array<double, 2>> band;
    };

    /**
     * @brief Body n/Body force: a constant vector, or expressions of x,
     * y[, z] (then the vector is zero).
     */
    struct BodyForceParameters
    {
      std::vector<double>      vector;
      std::vector<std::string> expressions;
    };

    /** @brief One entry of Probe points: a named point of a body. */
    struct ProbePoint
    {
      std::string         name;
      std::vector<double> location;
    };

    /**
     * @brief The faces of one patch of a body's geometry as its grammars
     * name them: the 2 dim faces' descriptions ("x = lower", ...), whether
     * the geometry is a file (whose faces may name a patch: 'p.f') and the
     * geometry's name for messages.
     */
    struct PatchFaces
    {
      std::vector<std::string> names;
      bool                     from_file = false;
      std::string              geometry;
    };

    /**
     * @name The grammars of a body's entries
     *
     * Each reads one scene parameter's text and refuses, with one input
     * error (base::ExcInput) that starts with @p where (the file and the
     * parameter, "scene.prm: Body 1/Supports"), what the grammar does not
     * accept, saying what it does. Lists are ';'-separated; an entry
     * optionally ends in '@ history'.
     */
    /** @{ */

    /// Splits "entry @ history" into the entry and the history name
    /// (empty when there is no '@').
    std::pair<std::string, std::string>
    split_history(const std::string &entry);

    /**
     * @brief A vector of @p dimension comma-separated components; extra
     * trailing zero components (a 3D default read in 2D) are dropped.
     */
    std::vector<double>
    read_vector(const std::string &text,
                const unsigned int dimension,
                const std::string &where);

    /**
     * @brief Body n/Motion of a rigid obstacle: 'ux, uy[, uz]' or with the
     * rotation 'ux, uy, rz' (2D) / 'ux, uy, uz, rx, ry, rz' (3D), each entry
     * optionally '@ name', separated by ';'.
     */
    std::vector<ObstacleMotionParameters>
    read_obstacle_motion(const std::string &text,
                         const unsigned int dimension,
                         const std::string &where);

    /**
     * @brief The faces of @p key: a face number f, or 'p.f' (face f of
     * patch p of a multi-patch geometry file), several joined by '+' where
     * @p several allows. The body face is p * faces.names.size() + f.
     * Refuses a face the patch does not have, naming the faces it has;
     * @p item is the entry @p key was read from (for the message).
     */
    std::vector<unsigned int>
    read_faces(const std::string &key,
               const PatchFaces  &faces,
               const std::string &where,
               const std::string &item,
               const bool         several = true);

    /// Subdivisions: one count, or one per direction, each 1 to 9999.
    std::vector<unsigned int>
    read_subdivisions(const std::string &text,
                      const unsigned int dimension,
                      const std::string &where);

    /// Grading: 'face: ratio' or 'band d: from, to, ratio' entries, one per
    /// direction at most.
    GradingParameters
    read_grading(const std::string &text,
                 const unsigned int dimension,
                 const std::string &where);

    /// Supports: 'face: x y=0.1', 'face: c = function expr'; faces joined
    /// by '+' give one support each.
    std::vector<SupportParameters>
    read_supports(const std::string &text,
                  const PatchFaces  &faces,
                  const std::string &where);

    /// Tractions: 'face: pressure p', 'face: vector tx, ty[, tz]',
    /// 'face: exact', 'face: function fx; fy[; fz]'.
    std::vector<TractionParameters>
    read_tractions(const std::string &text,
                   const PatchFaces  &faces,
                   const std::string &where);

    /// Hold rotation: one face, or empty (-1).
    int
    read_hold_rotation(const std::string &text,
                       const PatchFaces  &faces,
                       const std::string &where);

    /// Point loads: 'x, y[, z] : fx, fy[, fz]'.
    std::vector<PointLoadParameters>
    read_point_loads(const std::string &text,
                     const unsigned int dimension,
                     const std::string &where);

    /// Point supports: 'x, y[, z] : x y=0.01'.
    std::vector<PointSupportParameters>
    read_point_supports(const std::string &text,
                        const unsigned int dimension,
                        const std::string &where);

    /// Moments: 'face: M' (2D), 'face: Mx, My, Mz' (3D).
    std::vector<MomentParameters>
    read_moments(const std::string &text,
                 const PatchFaces  &faces,
                 const std::string &where);

    /// Face motions: 'face: ux, uy, rz' (2D), 'face: ux, uy, uz, rx, ry,
    /// rz' (3D), each face once.
    std::vector<FaceMotionParameters>
    read_face_motions(const std::string &text,
                      const PatchFaces  &faces,
                      const std::string &where);

    /// Body force: 'fx, fy[, fz]' or 'function fx; fy[; fz]' (no t).
    BodyForceParameters
    read_body_force(const std::string &text,
                    const unsigned int dimension,
                    const std::string &where);

    /// Probe points: 'name: x, y[, z]'.
    std::vector<ProbePoint>
    read_probe_points(const std::string &text,
                      const unsigned int dimension,
                      const std::string &where);

    /// A list of numbers, separated by commas or spaces (maybe none).
    std::vector<double>
    read_numbers(const std::string &text, const std::string &where);

    /// A point of exactly @p dimension coordinates.
    std::vector<double>
    read_point(const std::string &text,
               const unsigned int dimension,
               const std::string &where);

    /// A non-zero vector of exactly @p dimension components.
    std::vector<double>
    read_direction(const std::string &text,
                   const unsigned int dimension,
                   const std::string &where);

    /**
     * @brief Load path/Histories: 'name: f1, f2, ...' entries, each name one
     * word other than 'load' and 'displacement', declared once.
     */
    std::vector<std::pair<std::string, std::vector<double>>>
    read_histories(const std::string &text, const std::string &where);

    /**
     * @brief One history's factors, one per step: a comma list of numbers,
     * 'ramp a b n' (n factors rising linearly from a, exclusive, to b) and
     * 'hold f n' (n factors f), e.g. 'ramp 0 1 10, hold 1 100'.
     */
    std::vector<double>
    read_history_factors(const std::string &text, const std::string &where);

    /**
     * @brief Refuses, naming @p where, 'function' expressions that are not
     * one per component or that deal.II's FunctionParser cannot evaluate;
     * returns whether one of them uses the variable t.
     */
    bool
    check_expressions(const std::vector<std::string> &expressions,
                      const unsigned int              dimension,
                      const std::string              &where);
    /** @} */
  } // namespace scene
} // namespace igabde

#endif
