#include <igabde/base/utilities.h>

#include <igabde/discretization/body.h>

#include <igabde/contact/contact_solver.h>
#include <igabde/contact/pairing.h>

#include <igabde/scene/geometry.h>
#include <igabde/scene/parameters.h>

#include <deal.II/base/function_parser.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <regex>
#include <sstream>

namespace igabde
{
  namespace scene
  {
    void
    OutputParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      {
        prm.declare_entry("Directory",
                          "",
                          Patterns::Anything(),
                          "Folder for all output of the run. Empty: "
                          "output/<scene name>/ below the working directory.");
        prm.declare_entry("Write vtu",
                          "true",
                          Patterns::Bool(),
                          "Write the displacement, strain, stress and von "
                          "Mises fields as VTU files with a PVD series.");
        prm.declare_entry("Print timing",
                          "true",
                          Patterns::Bool(),
                          "Print the timing table on screen. Scene tests "
                          "switch it off; timing.txt and summary.json always "
                          "have it.");
        prm.declare_entry("Progress",
                          "true",
                          Patterns::Bool(),
                          "Print a progress line with the elapsed seconds for "
                          "every phase that can take long (assembly, "
                          "factorisation, condensation, contact iterations); "
                          "the command-line flag --quiet sets it to false.");
        prm.declare_entry("Solver details",
                          "true",
                          Patterns::Bool(),
                          "Print the contact solver's line for every solve "
                          "(iterations, residuals, open/stick/slip counts) "
                          "and the notices of halved load increments. Scene "
                          "tests switch it off, so that their reference "
                          "output holds physical figures only; summary.json "
                          "always has these figures.");
        prm.declare_entry(
          "FCLIB export",
          "false",
          Patterns::Bool(),
          "Write each load step's condensed contact problem (W, q, mu in "
          "the pairs' local frames) with the step's solution as an FCLIB "
          "local problem, fclib-NNNN.hdf5, so that another solver (or "
          "igabde --fclib) can solve exactly the problem this run solved. "
          "Needs contact with friction (FCLIB's problems have two or three "
          "components per contact) on the condensed path (Contact/Algorithm "
          "= bde, Path = condensed or auto); a step whose bodies float "
          "(held by contact only) is not an FCLIB local problem and is left "
          "out, with a line in the log.");
        prm.declare_entry("Export geometry",
                          "false",
                          Patterns::Bool(),
                          "Write each body's geometry after Subdivisions, "
                          "degree elevation and Refinements as a G+Smo XML "
                          "file (<body>-geometry.xml, readable with Geometry "
                          "= file) and its control net as VTU "
                          "(<body>-control-net.vtu). The command-line flag "
                          "--export-geometry sets it to true.");
      }
      prm.leave_subsection();
    }



    void
    OutputParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      {
        directory       = prm.get("Directory");
        write_vtu       = prm.get_bool("Write vtu");
        print_timing    = prm.get_bool("Print timing");
        progress        = prm.get_bool("Progress");
        solver_details  = prm.get_bool("Solver details");
        export_geometry = prm.get_bool("Export geometry");
        fclib_export    = prm.get_bool("FCLIB export");
      }
      prm.leave_subsection();
    }



    void
    BodyParameters::declare_parameters(ParameterHandler  &prm,
                                       const std::string &name,
                                       const std::string &default_type)
    {
      prm.enter_subsection(name);
      {
        prm.declare_entry("Type",
                          default_type,
                          Patterns::Selection(
                            base::selection_of(body_type_names)),
                          "deformable: a meshed elastic body. rigid plane: a "
                          "fixed flat obstacle with no mesh and no unknowns "
                          "(Body 2 only). none: no such body (Body 2 only).");
        prm.declare_entry(
          "Geometry",
          "box",
          Patterns::Selection(base::selection_of(geometry_names)),
          "Exact NURBS geometry. box: [Lower corner, Upper corner]. quarter "
          "annulus / thick cylinder: Inner/Outer radius, 0..90 degrees "
          "(3D: extruded by Width along z). plate with hole: the quarter "
          "[0,Plate size]^2 minus the hole of radius Inner radius. hertz "
          "quarter disc: lower right quarter of a disc of Radius touching "
          "y = 0 at the origin. curved beam: quarter annulus in the x-z "
          "plane extruded in y by Width. full disc / half disc (2D): the "
          "disc of Radius about Centre, or its lower half y <= Centre y "
          "(faces 0 left, 1 right, 2 bottom arc, 3 top arc or diameter). "
          "full cylinder / half cylinder (3D): those extruded along z from "
          "Centre z by Width (faces 4: z = Centre z, 5: z = Centre z + "
          "Width). file: the single-patch G+Smo XML file Geometry file "
          "(faces 0..2dim-1: low and high end of parametric directions 0, 1, "
          "2).");
        prm.declare_entry("Geometry file",
                          "",
                          Patterns::Anything(),
                          "Geometry = file: a G+Smo XML file holding one "
                          "TensorBSpline or TensorNurbs patch of the scene's "
                          "dimension, relative to the scene file's folder "
                          "(or absolute). Subdivisions, Grading and "
                          "Discretization/Degree and Refinements apply to it "
                          "as to the built-in shapes.");
        prm.declare_entry("Lower corner",
                          "",
                          Patterns::Anything(),
                          "box: lower corner (m), comma-separated; empty: "
                          "the origin.");
        prm.declare_entry("Upper corner",
                          "",
                          Patterns::Anything(),
                          "box: upper corner (m), comma-separated; empty: "
                          "(1, 1[, 1]).");
        prm.declare_entry("Inner radius",
                          "1",
                          Patterns::Double(0.),
                          "Inner radius (m) of annulus, cylinder, curved "
                          "beam; hole radius of the plate with hole.");
        prm.declare_entry("Outer radius",
                          "2",
                          Patterns::Double(0.),
                          "Outer radius (m) of annulus, cylinder, curved "
                          "beam.");
        prm.declare_entry("Radius",
                          "8",
                          Patterns::Double(0.),
                          "Radius (m) of the hertz quarter disc and of the "
                          "full/half discs and cylinders.");
        prm.declare_entry("Centre",
                          "",
                          Patterns::Anything(),
                          "full/half disc: centre (m), 'x, y'; full/half "
                          "cylinder: centre of the base face z = const, "
                          "'x, y, z'. Empty: the origin.");
        prm.declare_entry("Width",
                          "1",
                          Patterns::Double(0.),
                          "Extrusion width (m) of 3D annulus-like bodies.");
        prm.declare_entry("Plate size",
                          "4",
                          Patterns::Double(0.),
                          "Edge length L (m) of the plate with hole.");
        prm.declare_entry("Subdivisions",
                          "1",
                          Patterns::Anything(),
                          "Knot spans per parametric direction of the base "
                          "mesh (one number for all, or one per direction), "
                          "before Discretization/Refinements.");
        prm.declare_entry(
          "Grading",
          "",
          Patterns::Anything(),
          "Spans graded toward faces: 'face: ratio; ...', the spans of the "
          "face's parametric direction growing geometrically away from it, "
          "the largest 'ratio' times the smallest (e.g. '0: 8; 2: 8' refines "
          "the Hertz quarter disc toward its contact point), or toward a band "
          "inside a direction: 'band d: from, to, ratio', the spans of "
          "parametric direction d smallest over the fractions [from, to] of "
          "it and growing by 1.25 per span away from the band up to 'ratio' "
          "times (e.g. 'band 0: 0.45, 0.55, 8' around the middle of the half "
          "disc's bottom arc). At most one grading per direction; empty: "
          "uniform spans.");
        prm.declare_entry("Young's modulus",
                          "1000",
                          Patterns::Double(0.),
                          "Young's modulus E (Pa), E > 0.");
        prm.declare_entry("Poisson's ratio",
                          "0.3",
                          Patterns::Double(-1., 0.5),
                          "Poisson's ratio nu, -1 < nu < 0.5 (the bounds "
                          "themselves are refused: no stiffness exists "
                          "there).");
        prm.declare_entry(
          "Supports",
          "",
          Patterns::Anything(),
          "Prescribed displacements on patch faces: 'face: components; ...' "
          "where a component is x, y or z, optionally with a value "
          "(x=0.05) scaled by the step's displacement factor (or by the "
          "load history 'name' when the entry ends in '@ name'); e.g. "
          "'0: x; 2: y'; a component may be 'y = function -0.01*x^2' (a "
          "FunctionParser expression of x, y[, z], one component per entry). "
          "Faces: 0/1 low/high end of parametric direction "
          "0, 2/3 of direction 1, 4/5 of direction 2; a face the Geometry "
          "does not have is refused when the scene is read.");
        prm.declare_entry(
          "Hold rotation",
          "",
          Patterns::Anything(),
          "A patch face whose mean rotation is held at zero, as a "
          "distributing coupling does: the body's rigid rotation (about z "
          "in 2D, about every axis in 3D) is removed by one constraint per "
          "axis, whose reaction is a pure moment spread over that face as "
          "a linear traction, so the deformation is not constrained. For a "
          "body held by forces and contact, e.g. a disc pressed and pushed "
          "sideways through its flat face. Rotations the Supports already "
          "hold are left to them. Empty: none.");
        prm.declare_entry(
          "Tractions",
          "",
          Patterns::Anything(),
          "Tractions on patch faces, scaled by the load factor: "
          "'face: pressure p' (t = -p n), 'face: vector tx, ty[, tz]', "
          "'face: exact' (sigma_exact n from the Exact solution) or "
          "'face: function fx; fy[; fz]' (deal.II FunctionParser "
          "expressions of x, y[, z] and t, in Pa, e.g. '3: function 0; "
          "-100*(1-x^2)'); separated by ';'. An entry ending in '@ name' "
          "follows the load history 'name' of Load path/Histories instead. "
          "A function that uses t is the traction itself at t = the step's "
          "factor of its history (not scaled again); one without t is "
          "scaled like every other entry.");
        prm.declare_entry("Point loads",
                          "",
                          Patterns::Anything(),
                          "Point forces 'x, y[, z] : fx, fy[, fz]; ...' (N), "
                          "scaled by the load factor, or by the load history "
                          "'name' of Load path/Histories when the entry ends "
                          "in '@ name'.");
        prm.declare_entry(
          "Point supports",
          "",
          Patterns::Anything(),
          "Components held at single points: 'x, y[, z] : components; "
          "...', e.g. '0, -0.5 : x y; 0, 0.5 : x' (a pin and a roller); a "
          "component may carry a value, 'x=0.01' (m), scaled by the step's "
          "displacement factor (or by the load history 'name' when the "
          "entry ends in '@ name'); without one it is held at zero. A point must be a node where one basis function is one "
          "and the others vanish: a corner of the patch for NURBS, a mesh "
          "node for FE_Q (refused otherwise). The support holds that node "
          "only: its reaction is a point force, with the stress singularity "
          "that brings.");
        prm.declare_entry(
          "Moments",
          "",
          Patterns::Anything(),
          "Moments on patch faces about each face's centroid, scaled by the "
          "load factor (or by the load history 'name' when the entry ends "
          "in '@ name'): 'face: M' in 2D (N m/m, about z, counterclockwise "
          "positive), 'face: Mx, My, Mz' in 3D (N m); separated by ';'. "
          "Spread over the face as a distributing coupling spreads a "
          "moment: a traction linear in the position, zero resultant force "
          "(for a straight beam end, the bending stress My/I). E.g. "
          "'1: 20' on a cantilever's end face.");
        prm.declare_entry(
          "Face motions",
          "",
          Patterns::Anything(),
          "Patch faces moved rigidly, as a kinematic coupling moves them: "
          "'face: ux, uy, rz' in 2D, 'face: ux, uy, uz, rx, ry, rz' in 3D; "
          "every point x of the face takes u = d + r x (x - c), d the "
          "displacement (m) of the face's centroid c and r the rotation "
          "(rad, small: the rotation is linearised, as the small-strain "
          "model requires), scaled by the step's displacement factor (or by "
          "the load history 'name' when the entry ends in '@ name'); "
          "separated by ';'. Every component is prescribed (a face whose "
          "motion is partly free is not modelled: hold what is known with "
          "Supports, and load the face with Tractions and Moments). The "
          "reaction force and the moment about c are reported per step "
          "(summary.json, steps.csv). E.g. '1: 0, 0, 0.01' turns a "
          "cantilever's end by 0.01 rad.");
        prm.declare_entry("Body force",
                          "0, 0, 0",
                          Patterns::Anything(),
                          "Body force per unit volume (N/m^3), scaled by "
                          "the load factor: 'fx, fy[, fz]' or 'function fx; "
                          "fy[; fz]' (FunctionParser expressions of x, y[, "
                          "z], e.g. 'function 0; -9.81*7800').");
        prm.declare_entry("Plane point",
                          "0, 0, 0",
                          Patterns::Anything(),
                          "rigid plane: a point on the plane (m).");
        prm.declare_entry("Plane normal",
                          "0, 1, 0",
                          Patterns::Anything(),
                          "rigid plane: normal pointing towards Body 1.");
      }
      prm.leave_subsection();
    }



    namespace
    {
      /// A number as a user wrote it (six significant digits).
      std::string
      number(const double x)
      {
        std::ostringstream out;
        out << x;
        return out.str();
      }



      /// The faces of a patch of @p body's geometry, as its grammars name
      /// them.
      PatchFaces
      patch_faces_of(const BodyParameters &body, const unsigned int dimension)
      {
        return {patch_faces(body.geometry, dimension),
                body.geometry == Geometry::file,
                to_string(body.geometry)};
      }



      /**
       * Refuses a face of @p body (its supports, tractions, moments, face
       * motions, held rotation and @p more) on a patch that the body's
       * geometry does not have; @p where names the body.
       */
      void
      check_face_patches(const BodyParameters            &body,
                         const std::vector<unsigned int> &more,
                         const unsigned int               dimension,
                         const std::string               &where)
      {
        std::vector<std::pair<std::string, unsigned int>> faces;
        for (const auto &s : body.supports)
          faces.emplace_back("Supports", s.face);
        for (const auto &t : body.tractions)
          faces.emplace_back("Tractions", t.face);
        for (const auto &m : body.moments)
          faces.emplace_back("Moments", m.face);
        for (const auto &m : body.face_motions)
          faces.emplace_back("Face motions", m.face);
        if (body.hold_rotation_face >= 0)
          faces.emplace_back("Hold rotation", body.hold_rotation_face);
        for (const unsigned int face : more)
          faces.emplace_back("contact face", face);
        for (const auto &[parameter, face] : faces)
          AssertThrow(
            face / (2 * dimension) < body.n_patches,
            base::ExcInput(
              where + "/" + parameter + ": face " +
              discretization::face_name(face, dimension) + " is on patch " +
              std::to_string(face / (2 * dimension)) +
              ", but the geometry has " + std::to_string(body.n_patches) +
              " patch" + (body.n_patches == 1 ? "" : "es") + " (0.." +
              std::to_string(body.n_patches - 1) + ")."));
      }



    } // namespace



    void
    BodyParameters::parse_parameters(ParameterHandler  &prm,
                                     const std::string &name,
                                     const unsigned int dimension,
                                     const std::string &context)
    {
      std::string supports_text, tractions_text, point_loads_text, hold_text,
        moments_text, point_supports_text, face_motions_text, body_force_text,
        lower_text, upper_text, centre_text, subdivisions_text, grading_text,
        point_text, normal_text;
      prm.enter_subsection(name);
      {
        type              = base::value_of(body_type_names, prm.get("Type"));
        geometry          = base::value_of(geometry_names, prm.get("Geometry"));
        geometry_file     = base::trim(prm.get("Geometry file"));
        lower_text        = prm.get("Lower corner");
        upper_text        = prm.get("Upper corner");
        inner_radius      = prm.get_double("Inner radius");
        outer_radius      = prm.get_double("Outer radius");
        radius            = prm.get_double("Radius");
        centre_text       = prm.get("Centre");
        width             = prm.get_double("Width");
        plate_size        = prm.get_double("Plate size");
        subdivisions_text = prm.get("Subdivisions");
        grading_text      = prm.get("Grading");
        youngs_modulus    = prm.get_double("Young's modulus");
        poisson_ratio     = prm.get_double("Poisson's ratio");
        supports_text     = prm.get("Supports");
        hold_text         = prm.get("Hold rotation");
        tractions_text    = prm.get("Tractions");
        point_loads_text  = prm.get("Point loads");
        moments_text      = prm.get("Moments");
        point_supports_text = prm.get("Point supports");
        face_motions_text   = prm.get("Face motions");
        body_force_text     = prm.get("Body force");
        point_text          = prm.get("Plane point");
        normal_text         = prm.get("Plane normal");
      }
      prm.leave_subsection();

      body_force.assign(dimension, 0.);
      const std::string where = context + name + "/";
      if (type == BodyType::rigid_plane)
        {
          plane_point =
            read_vector(point_text, dimension, where + "Plane point");
          plane_normal =
            read_vector(normal_text, dimension, where + "Plane normal");
          AssertThrow(std::any_of(plane_normal.begin(),
                                  plane_normal.end(),
                                  [](const double x) {
                                    return x != 0.;
                                  }),
                      base::ExcInput(where + "Plane normal = '" + normal_text +
                                     "' must not be zero; give the normal "
                                     "pointing towards Body 1, e.g. '0, 1'."));
        }
      supports.clear();
      tractions.clear();
      point_loads.clear();
      moments.clear();
      face_motions.clear();
      point_supports.clear();
      body_force_expressions.clear();
      if (type != BodyType::deformable)
        return;

      // The points and counts of the geometry, each read once.
      const auto optional_vector = [&](const std::string &text,
                                       const std::string &parameter) {
        return base::trim(text).empty() ?
                 std::vector<double>() :
                 read_vector(text, dimension, where + parameter);
      };
      lower_corner = optional_vector(lower_text, "Lower corner");
      upper_corner = optional_vector(upper_text, "Upper corner");
      centre       = optional_vector(centre_text, "Centre");
      subdivisions =
        read_subdivisions(subdivisions_text, dimension, where + "Subdivisions");
      const GradingParameters g =
        read_grading(grading_text, dimension, where + "Grading");
      grading             = g.ratio;
      grading_toward_high = g.toward_high;
      grading_band        = g.band;

      // What no material and no body can have, refused before any set-up.
      AssertThrow(youngs_modulus > 0.,
                  base::ExcInput(where +
                                 "Young's modulus = " + number(youngs_modulus) +
                                 " must be > 0 (Pa); set the material's "
                                 "stiffness, e.g. 1000."));
      AssertThrow(poisson_ratio > -1. && poisson_ratio < 0.5,
                  base::ExcInput(where +
                                 "Poisson's ratio = " + number(poisson_ratio) +
                                 " must lie in -1 < nu < 0.5; nearly "
                                 "incompressible materials need nu < 0.5 "
                                 "(e.g. 0.49)."));

      const PatchFaces faces = patch_faces_of(*this, dimension);
      AssertThrow(!faces.names.empty(),
                  base::ExcInput(where + "Geometry = " + to_string(geometry) +
                                 " does not exist in " +
                                 std::to_string(dimension) +
                                 "D; choose another geometry or Dimension."));

      supports  = read_supports(supports_text, faces, where + "Supports");
      tractions = read_tractions(tractions_text, faces, where + "Tractions");
      hold_rotation_face =
        read_hold_rotation(hold_text, faces, where + "Hold rotation");
      point_loads =
        read_point_loads(point_loads_text, dimension, where + "Point loads");
      point_supports = read_point_supports(point_supports_text,
                                           dimension,
                                           where + "Point supports");
      moments        = read_moments(moments_text, faces, where + "Moments");
      face_motions =
        read_face_motions(face_motions_text, faces, where + "Face motions");
      // A face motion prescribes every component and the rotation of its
      // face: a support or a held rotation of the same face says it twice.
      for (const auto &motion : face_motions)
        {
          for (const auto &support : supports)
            AssertThrow(support.face != motion.face,
                        base::ExcInput(
                          where + "Face motions: face " +
                          std::to_string(motion.face) +
                          " is also in Supports; a face motion prescribes "
                          "every component of the face, so remove the "
                          "face from Supports (or from Face motions)."));
          AssertThrow(hold_rotation_face != int(motion.face),
                      base::ExcInput(where + "Face motions: face " +
                                     std::to_string(motion.face) +
                                     " is also the Hold rotation face; a "
                                     "face motion prescribes its rotation "
                                     "already, so leave Hold rotation "
                                     "empty."));
        }
      const BodyForceParameters force =
        read_body_force(body_force_text, dimension, where + "Body force");
      body_force             = force.vector;
      body_force_expressions = force.expressions;
    }



    void
    ExactSolutionParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Exact solution");
      {
        prm.declare_entry("Type",
                          "none",
                          Patterns::Selection(
                            base::selection_of(exact_solution_type_names)),
                          "Exact solution for error norms and 'exact' "
                          "tractions: kirsch (V1, infinite plate with a hole "
                          "under remote tension along x), lame (V2, thick "
                          "cylinder under internal pressure, plane strain).");
        prm.declare_entry("Remote tension",
                          "10",
                          Patterns::Double(),
                          "kirsch: remote tension T_x (Pa).");
        prm.declare_entry("Hole radius",
                          "1",
                          Patterns::Double(0.),
                          "kirsch: hole radius (m).");
        prm.declare_entry("Inner radius",
                          "1",
                          Patterns::Double(0.),
                          "lame: inner radius a (m).");
        prm.declare_entry("Outer radius",
                          "2",
                          Patterns::Double(0.),
                          "lame: outer radius b (m).");
        prm.declare_entry("Pressure",
                          "1",
                          Patterns::Double(),
                          "lame: internal pressure (Pa).");
      }
      prm.leave_subsection();
    }



    void
    ExactSolutionParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Exact solution");
      {
        type = base::value_of(exact_solution_type_names, prm.get("Type"));
        remote_tension = prm.get_double("Remote tension");
        hole_radius    = prm.get_double("Hole radius");
        inner_radius   = prm.get_double("Inner radius");
        outer_radius   = prm.get_double("Outer radius");
        pressure       = prm.get_double("Pressure");
      }
      prm.leave_subsection();
    }



    void
    ContactParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      {
        prm.declare_entry("Enabled",
                          "false",
                          Patterns::Bool(),
                          "Whether Body 1 and Body 2 may touch.");
        prm.declare_entry("Friction coefficient",
                          "0",
                          Patterns::Double(),
                          "Coulomb friction coefficient mu >= 0. With 0 no "
                          "tangential contact unknowns are formed.");
        prm.declare_entry("Algorithm",
                          "bde",
                          Patterns::Selection(
                            base::selection_of(contact::algorithm_names)),
                          "Contact algorithm: bde (B-differentiable "
                          "equations with damped B-Newton); penalty "
                          "(node-to-node penalty with Coulomb return "
                          "mapping, Newton on the full system, as ANSYS); "
                          "augmented-lagrange (multiplier updates around "
                          "the penalty solve until the BDE tolerance).");
        prm.declare_entry("Penalty factor",
                          "1",
                          Patterns::Double(0.),
                          "FKN > 0: normal penalty stiffness per pair "
                          "k_n = FKN E A / h (E of the two bodies in "
                          "series, A the pair's tributary area, h the mean "
                          "element size) for penalty and "
                          "augmented-lagrange.");
        prm.declare_entry("Tangential penalty factor",
                          "1",
                          Patterns::Double(0.),
                          "FKT > 0: stick stiffness k_t = FKT k_n.");
        prm.declare_entry("Penalty line search",
                          "true",
                          Patterns::Bool(),
                          "Armijo line search on the Newton steps of the "
                          "penalty methods; false takes full steps, as "
                          "ANSYS does by default (a stiff penalty may then "
                          "chatter between pair states).");
        prm.declare_entry("Full system solver",
                          "mumps",
                          Patterns::Selection(
                            base::selection_of(coupled::solver_names)),
                          "Linear solver of the coupled Newton matrix on "
                          "the full path: mumps or klu (sparse direct, "
                          "Trilinos Amesos), or gmres-amg (GMRES with a "
                          "block preconditioner: AMG on the stiffness, a "
                          "sparse LU of an approximate Schur complement on "
                          "the pair forces; each Newton step solved to "
                          "1e-2 min(1, |F_k|/|F_0|) of its residual).");
        prm.declare_entry("Krylov max iterations",
                          "1000",
                          Patterns::Integer(1),
                          "gmres-amg: GMRES iteration limit per Newton "
                          "step; reaching it fails the contact solve with "
                          "the iterations and the residual.");
        prm.declare_entry("Path",
                          "auto",
                          Patterns::Selection(
                            base::selection_of(contact::path_names)),
                          "condensed: flexibility matrix and dense BDE "
                          "system; full: uncondensed sparse system "
                          "(displacements and pair forces together); auto: "
                          "the path a cost model estimates cheaper (contact "
                          "unknowns, face unknowns, estimated sparse factor "
                          "size; penalty and augmented-lagrange always "
                          "solve the full system).");
        prm.declare_entry("Condensation",
                          "schur",
                          Patterns::Selection(
                            base::selection_of(contact::condensation_names)),
                          "How the flexibility F^L is formed. schur: from the "
                          "Schur complement of each body's stiffness onto "
                          "its contact-face unknowns, returned by the same "
                          "sparse factorisation (Linear solver = direct); "
                          "columns: one solve per pair direction (any linear "
                          "solver).");
        prm.declare_entry("Slave face",
                          "2",
                          Patterns::Anything(),
                          "Patch face of Body 1 that may touch Body 2: f, "
                          "or p.f for face f of patch p of a multi-patch "
                          "geometry file.");
        prm.declare_entry("Master face",
                          "3",
                          Patterns::Anything(),
                          "Patch face of Body 2 that may touch Body 1: f or "
                          "p.f.");
        prm.declare_entry("Pair placement",
                          "greville",
                          Patterns::Selection(base::selection_of(
                            discretization::pair_placement_names)),
                          "Where pairs sit on a NURBS surface: images of the "
                          "Greville abscissae (one per face control point, "
                          "the most accurate: doc/studies.md), knot-grid "
                          "points (fewer than the control points for p >= 2: "
                          "least-squares areas) or Gauss points (p+1 per "
                          "span: more pairs than the face has control "
                          "points, redundant on a curved face, where the "
                          "solver may not converge). Lagrange surfaces use "
                          "their nodes.");
        prm.declare_entry(
          "Pairing",
          "node-to-surface",
          Patterns::Selection(base::selection_of(contact::pairing_names)),
          "How Body 1's contact face is paired with the surface it faces. "
          "node-to-surface: Body 1's points (Pair placement) with the "
          "coincident point where the meshes match, else the closest point "
          "of the master face (exact on NURBS); node-to-node: matching "
          "meshes only (an error names the first point without a partner); "
          "weighted-gap: one pair per basis function N_j of Body 1's face "
          "(mortar-like), its gap, slip and operators integrated against "
          "the dual basis function psi_j (int psi_j N_k = delta_jk int N_j, "
          "element by element) over the face with the master side found "
          "by projection, tributary area int N_j dGamma: transmits a "
          "uniform pressure exactly on non-matching meshes, and its pair "
          "pressures are N_j-weighted means of the pressure (smooth up to "
          "the edge of a contact zone); weighted-gap-standard: the same "
          "integrated against N_j itself (its pair pressures are the "
          "coefficients of the pressure in the N_j, which oscillate next "
          "to the edge of a contact zone).");
        prm.declare_entry("Tolerance",
                          "1e-10",
                          Patterns::Double(0.),
                          "Stopping test: natural-map residual relative to "
                          "||q||.");
        prm.declare_entry("Max iterations",
                          "100",
                          Patterns::Integer(1),
                          "B-Newton iteration limit per load step.");
        prm.declare_entry("r scale",
                          "1",
                          Patterns::Double(0.),
                          "Factor on the per-pair r_n = 1/F_nn, "
                          "r_t = 1/lambda_max(F_tt).");
        prm.declare_entry("Verbose",
                          "false",
                          Patterns::Bool(),
                          "Print every B-Newton iteration.");
        prm.declare_entry("Max step cuts",
                          "4",
                          Patterns::Integer(0, 12),
                          "When the contact solve of a load increment does "
                          "not converge, the increment is halved (loads and "
                          "prescribed displacements interpolated linearly) "
                          "and retried, at most this many times in a row; "
                          "0 stops at the first failure.");
      }
      prm.leave_subsection();
    }



    void
    ContactParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      {
        enabled              = prm.get_bool("Enabled");
        friction_coefficient = prm.get_double("Friction coefficient");
        algorithm =
          base::value_of(contact::algorithm_names, prm.get("Algorithm"));
        penalty_factor            = prm.get_double("Penalty factor");
        tangential_penalty_factor = prm.get_double("Tangential penalty factor");
        full_system_solver =
          base::value_of(coupled::solver_names, prm.get("Full system solver"));
        krylov_max_iterations = prm.get_integer("Krylov max iterations");
        penalty_line_search   = prm.get_bool("Penalty line search");
        path = base::value_of(contact::path_names, prm.get("Path"));
        condensation =
          base::value_of(contact::condensation_names, prm.get("Condensation"));
        slave_face_text  = base::trim(prm.get("Slave face"));
        master_face_text = base::trim(prm.get("Master face"));
        pair_placement   = base::value_of(discretization::pair_placement_names,
                                        prm.get("Pair placement"));
        pairing   = base::value_of(contact::pairing_names, prm.get("Pairing"));
        tolerance = prm.get_double("Tolerance");
        max_iterations = prm.get_integer("Max iterations");
        r_scale        = prm.get_double("r scale");
        verbose        = prm.get_bool("Verbose");
        max_step_cuts  = prm.get_integer("Max step cuts");
      }
      prm.leave_subsection();
    }



    void
    ChecksParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Checks");
      {
        prm.declare_entry("Uniform pressure",
                          "0",
                          Patterns::Double(0.),
                          "Exact uniform contact pressure (Pa): adds "
                          "checks.pressure_uniformity = max_i |p_i / p - 1| "
                          "to summary.json. 0: no such check.");
        prm.declare_entry("Hertz line load",
                          "0",
                          Patterns::Double(0.),
                          "Line load P (N/m) of a Hertz cylinder (radius "
                          "Body 1/Radius) on a rigid flat: adds "
                          "checks.hertz_half_width, hertz_peak_pressure and "
                          "pressure_l2_rel_error. 0: no Hertz check.");
        prm.declare_entry("Hertz point load",
                          "0",
                          Patterns::Double(0.),
                          "Load P (N) of a Hertz sphere (radius Hertz "
                          "radius) on a flat, 3D: adds "
                          "checks.hertz_contact_radius, hertz_peak_pressure "
                          "and pressure_l2_rel_error. P is the whole "
                          "sphere's load also in a half or quarter model. 0: "
                          "no such check.");
        prm.declare_entry("Hertz radius",
                          "0",
                          Patterns::Double(0.),
                          "Radius (m) of the Hertz cylinder or sphere; 0: "
                          "Body 1/Radius.");
        prm.declare_entry("Hertz axis point",
                          "",
                          Patterns::Anything(),
                          "A point (m) on the symmetry axis of the Hertz "
                          "contact: pair pressures are compared against the "
                          "distance from this axis. Empty: the origin.");
        prm.declare_entry("Hertz axis direction",
                          "",
                          Patterns::Anything(),
                          "Direction of the symmetry axis of the Hertz "
                          "contact (the load direction). Empty: y in 2D, z "
                          "in 3D.");
      }
      prm.leave_subsection();
    }



    void
    ChecksParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Checks");
      {
        uniform_pressure          = prm.get_double("Uniform pressure");
        hertz_line_load           = prm.get_double("Hertz line load");
        hertz_point_load          = prm.get_double("Hertz point load");
        hertz_radius              = prm.get_double("Hertz radius");
        hertz_axis_point_text     = prm.get("Hertz axis point");
        hertz_axis_direction_text = prm.get("Hertz axis direction");
      }
      prm.leave_subsection();
    }



    void
    LoadPathParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Load path");
      {
        prm.declare_entry("Number of steps",
                          "1",
                          Patterns::Integer(1),
                          "Proportional loading in this many equal steps. "
                          "A frictionless proportional scene needs one.");
        prm.declare_entry("Load factors",
                          "",
                          Patterns::Anything(),
                          "Explicit load factor of each step (scales "
                          "tractions, point loads, body force), e.g. "
                          "'0.5, 1, 0.5' to unload. Overrides Number of "
                          "steps.");
        prm.declare_entry("Displacement factors",
                          "",
                          Patterns::Anything(),
                          "Explicit factor of the prescribed displacements "
                          "per step; as many as Load factors, or empty "
                          "(then equal to the load factors).");
        prm.declare_entry(
          "Histories",
          "",
          Patterns::Anything(),
          "Named load histories, 'name: f1, f2, ...; name2: ...', one factor "
          "per step each (as many as the steps). A traction, point load or "
          "support entry follows one by ending in '@ name', e.g. Tractions "
          "= '3: pressure 10 @ normal; 1: vector -2, 0 @ shear'; entries "
          "without it follow Load factors (loads) or Displacement factors "
          "(prescribed displacements). The body force follows Load "
          "factors.");
      }
      prm.leave_subsection();
    }



    void
    LoadPathParameters::parse_parameters(ParameterHandler &prm)
    {
      step_history_steps.clear();
      prm.enter_subsection("Load path");
      {
        n_steps = prm.get_integer("Number of steps");
        load_factors =
          read_numbers(prm.get("Load factors"), "Load path/Load factors");
        displacement_factors = read_numbers(prm.get("Displacement factors"),
                                            "Load path/Displacement factors");
        histories = read_histories(prm.get("Histories"), "Load path/Histories");
      }
      prm.leave_subsection();
    }



    std::vector<std::pair<double, double>>
    LoadPathParameters::steps() const
    {
      std::vector<std::pair<double, double>> result;
      if (load_factors.empty() && displacement_factors.empty())
        {
          for (unsigned int s = 1; s <= n_steps; ++s)
            result.emplace_back(double(s) / n_steps, double(s) / n_steps);
          return result;
        }
      const std::vector<double> &lf =
        load_factors.empty() ? displacement_factors : load_factors;
      const std::vector<double> &df =
        displacement_factors.empty() ? load_factors : displacement_factors;
      for (unsigned int s = 0; s < lf.size(); ++s)
        result.emplace_back(lf[s], df[s]);
      return result;
    }



    std::vector<std::vector<double>>
    LoadPathParameters::history_factors() const
    {
      const auto                       base_steps = steps();
      std::vector<std::vector<double>> result;
      for (unsigned int s = 0; s < base_steps.size(); ++s)
        {
          std::vector<double> f = {base_steps[s].first, base_steps[s].second};
          for (const auto &h : histories)
            f.push_back(s < h.second.size() ? h.second[s] : 0.);
          for (const unsigned int step : step_history_steps)
            f.push_back(step == s ? 1. : 0.);
          result.push_back(f);
        }
      return result;
    }



    unsigned int
    LoadPathParameters::history_index(const std::string &name,
                                      const unsigned int default_index) const
    {
      if (name.empty())
        return default_index;
      if (name == "load")
        return 0;
      if (name == "displacement")
        return 1;
      for (unsigned int k = 0; k < histories.size(); ++k)
        if (histories[k].first == name)
          return 2 + k;
      std::string names = "load, displacement";
      for (const auto &h : histories)
        names += ", " + h.first;
      AssertThrow(false,
                  base::ExcInput("load history '" + name +
                                 "' is not declared in Load path/Histories; "
                                 "declared: " +
                                 names + "."));
      return default_index;
    }



    void
    declare_discretization_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Discretization");
      {
        prm.declare_entry("Type",
                          "nurbs",
                          Patterns::Selection(
                            base::selection_of(discretization::type_names)),
                          "nurbs: isogeometric analysis on the exact "
                          "geometry. lagrange: FE_Q elements on the same "
                          "knot-span mesh, geometry interpolated.");
        prm.declare_entry("Degree",
                          "2",
                          Patterns::Integer(1, 6),
                          "NURBS degree (geometry elevated to it) or FE_Q "
                          "degree.");
        prm.declare_entry("Refinements",
                          "0",
                          Patterns::Integer(0, 12),
                          "Extra uniform h-refinements (each halves every "
                          "knot span / cell).");
        prm.declare_entry("Linear solver",
                          "direct",
                          Patterns::Selection(base::selection_of(
                            discretization::linear_solver_names)),
                          "direct: sparse LDL^T Cholesky (MUMPS), one "
                          "factorisation per body serving all right-hand "
                          "sides and, with contact, the Schur complement on "
                          "the contact face. umfpack: sparse LU (UMFPACK), "
                          "one solve per right-hand side. cg-amg: "
                          "conjugate gradients with Trilinos ML algebraic "
                          "multigrid, for large models.");
        prm.declare_entry("Linear tolerance",
                          "1e-12",
                          Patterns::Double(0.),
                          "cg-amg: relative residual at which CG stops.");
        prm.declare_entry(
          "Output subdivisions",
          "auto",
          Patterns::Anything(),
          "Subdivisions per element and direction in VTU output (1 to 16), "
          "so that curved boundaries and the fields inside an element look "
          "curved; FE_Q uses at least its degree. 'auto': the largest "
          "number up to 4 that keeps each body's output at most 8192 "
          "sub-cells per step (4 on coarse meshes, 1 on fine ones, where the "
          "elements are small on the screen anyway), so that writing the "
          "fields never costs more than solving.");
      }
      prm.leave_subsection();
    }



    void
    parse_discretization_parameters(
      ParameterHandler                       &prm,
      discretization::DiscretizationSettings &settings)
    {
      prm.enter_subsection("Discretization");
      {
        settings.type =
          base::value_of(discretization::type_names, prm.get("Type"));
        settings.degree      = prm.get_integer("Degree");
        settings.refinements = prm.get_integer("Refinements");
        settings.linear_solver =
          base::value_of(discretization::linear_solver_names,
                         prm.get("Linear solver"));
        settings.linear_tolerance      = prm.get_double("Linear tolerance");
        const std::string subdivisions = prm.get("Output subdivisions");
        if (subdivisions == "auto")
          settings.output_subdivisions = 0;
        else
          {
            std::size_t end   = 0;
            int         value = 0;
            try
              {
                value = std::stoi(subdivisions, &end);
              }
            catch (const std::exception &)
              {
                end = 0;
              }
            AssertThrow(
              end > 0 &&
                subdivisions.find_first_not_of(" ", end) == std::string::npos &&
                value >= 1 && value <= 16,
              base::ExcInput("Discretization/Output subdivisions = '" +
                             subdivisions +
                             "': write 'auto' or a whole number from 1 to 16"));
            settings.output_subdivisions = value;
          }
      }
      prm.leave_subsection();
    }



    void
    AllParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Scene name",
                        "",
                        Patterns::Anything(),
                        "Name of the scene; empty: the file name without "
                        ".prm.");
      prm.declare_entry("Dimension",
                        "2",
                        Patterns::Integer(2, 3),
                        "Spatial dimension: 2 (two displacement "
                        "components) or 3.");
      prm.declare_entry("Plane model",
                        "plane strain",
                        Patterns::Selection(
                          base::selection_of(elasticity::plane_model_names)),
                        "2D kinematics.");
      prm.declare_entry("Probe points",
                        "",
                        Patterns::Anything(),
                        "Named points whose displacement goes to "
                        "summary.json: 'A: x, y[, z]; B: ...' (on Body 1).");
      OutputParameters::declare_parameters(prm);
      declare_discretization_parameters(prm);
      BodyParameters::declare_parameters(prm, "Body 1", "deformable");
      BodyParameters::declare_parameters(prm, "Body 2", "none");
      ExactSolutionParameters::declare_parameters(prm);
      ContactParameters::declare_parameters(prm);
      LoadPathParameters::declare_parameters(prm);
      ChecksParameters::declare_parameters(prm);
    }



    void
    AllParameters::parse_parameters(ParameterHandler  &prm,
                                    const std::string &scene_file)
    {
      name      = prm.get("Scene name");
      dimension = prm.get_integer("Dimension");
      plane_model =
        base::value_of(elasticity::plane_model_names, prm.get("Plane model"));
      const std::string probes_text = prm.get("Probe points");
      output.parse_parameters(prm);
      parse_discretization_parameters(prm, discretization);
      const std::string f = scene_file + ": ";
      body1.parse_parameters(prm, "Body 1", dimension, f);
      body2.parse_parameters(prm, "Body 2", dimension, f);
      // A geometry file is found from the scene file's folder and read
      // now, so that a bad file ends the run before anything is built.
      for (auto *body : {&body1, &body2})
        if (body->type == BodyType::deformable &&
            body->geometry == Geometry::file)
          {
            const std::string where =
              f + (body == &body1 ? "Body 1" : "Body 2") + "/Geometry file";
            AssertThrow(!body->geometry_file.empty(),
                        base::ExcInput(where + " is empty; Geometry = file "
                                               "needs the path of a G+Smo "
                                               "XML file."));
            const std::filesystem::path file(body->geometry_file);
            body->geometry_path =
              file.is_absolute() ?
                file.string() :
                (std::filesystem::path(scene_file).parent_path() / file)
                  .lexically_normal()
                  .string();
            body->n_patches =
              check_geometry_file(*body,
                                  dimension,
                                  discretization.degree,
                                  where + " = " + body->geometry_file + ": ");
            check_face_patches(*body,
                               {},
                               dimension,
                               f + (body == &body1 ? "Body 1" : "Body 2"));
          }
      exact.parse_parameters(prm);
      contact.parse_parameters(prm);
      // Pair placement is a property of the discretised surface.
      discretization.pair_placement = contact.pair_placement;
      load_path.parse_parameters(prm);
      checks.parse_parameters(prm);

      // Checks that need more than a pattern; each names the parameter and
      // the fix.
      probes = read_probe_points(probes_text, dimension, f + "Probe points");
      AssertThrow(body1.type == BodyType::deformable,
                  base::ExcInput(f + "Body 1/Type must be 'deformable'; only "
                                     "Body 2 may be a rigid plane."));
      AssertThrow(!output.fclib_export ||
                    (contact.enabled && contact.friction_coefficient > 0. &&
                     contact.algorithm == contact::Algorithm::bde &&
                     contact.path != contact::Path::full),
                  base::ExcInput(
                    f + "Output/FCLIB export = true needs a contact problem "
                        "with friction on the condensed path (Contact/Enabled "
                        "= true, Friction coefficient > 0, Algorithm = bde, "
                        "Path = condensed or auto): FCLIB's local problems "
                        "have two or three components per contact and a "
                        "flexibility W; set it to false for this scene."));
      AssertThrow(contact.friction_coefficient >= 0.,
                  base::ExcInput(
                    f + "Contact/Friction coefficient = " +
                    number(contact.friction_coefficient) +
                    " is negative; use mu >= 0 (0 for frictionless)."));
      AssertThrow(!contact.enabled || body2.type != BodyType::none,
                  base::ExcInput(f + "Contact/Enabled is true but Body 2/Type "
                                     "is 'none'; set Body 2/Type to "
                                     "'deformable' or 'rigid plane'."));
      AssertThrow(contact.algorithm == contact::Algorithm::bde ||
                    contact.path != contact::Path::condensed,
                  base::ExcInput(f + "Contact/Algorithm = " +
                                 contact::to_string(contact.algorithm) +
                                 " solves the full system; set Contact/Path "
                                 "to 'full' or 'auto' (or use Algorithm = "
                                 "bde for the condensed path)."));
      // A held rotation is a constraint the coupled system has no rows for.
      for (const auto *body : {&body1, &body2})
        if (contact.enabled && body->type == BodyType::deformable &&
            body->hold_rotation_face >= 0)
          {
            const std::string name = (body == &body1 ? "Body 1" : "Body 2");
            AssertThrow(contact.algorithm == contact::Algorithm::bde &&
                          contact.path != contact::Path::full,
                        base::ExcInput(
                          f + name +
                          "/Hold rotation is modelled on the condensed "
                          "path only, but Contact/" +
                          (contact.algorithm != contact::Algorithm::bde ?
                             "Algorithm = " +
                               contact::to_string(contact.algorithm) +
                               " solves the full system" :
                             std::string("Path = full")) +
                          "; use Contact/Algorithm = bde with Path = "
                          "condensed or auto."));
          }
      // What the contact solver would refuse only when it is built.
      AssertThrow(contact.tolerance > 0.,
                  base::ExcInput(
                    f + "Contact/Tolerance = " + number(contact.tolerance) +
                    " must be > 0 (the natural-map residual "
                    "relative to ||q|| at which a solve stops; "
                    "e.g. 1e-10)."));
      AssertThrow(contact.r_scale > 0.,
                  base::ExcInput(
                    f + "Contact/r scale = " + number(contact.r_scale) +
                    " must be > 0 (a factor on the per-pair "
                    "r; 1 is the default)."));
      AssertThrow(contact.penalty_factor > 0. &&
                    contact.tangential_penalty_factor > 0.,
                  base::ExcInput(f + "Contact/Penalty factor and Contact/"
                                     "Tangential penalty factor must be "
                                     "positive (FKN = 0.01 to 10 is the "
                                     "usual range)."));
      for (const auto *body : {&body1, &body2})
        for (const auto &traction : body->tractions)
          AssertThrow(traction.kind != TractionParameters::Kind::exact ||
                        exact.type != ExactSolutionType::none,
                      base::ExcInput(f +
                                     (body == &body1 ? "Body 1" : "Body 2") +
                                     "/Tractions: 'exact' needs Exact "
                                     "solution/Type other than none."));
      AssertThrow(
        (contact.pairing != contact::Pairing::weighted_gap &&
         contact.pairing != contact::Pairing::weighted_gap_standard) ||
          contact.pair_placement == discretization::PairPlacement::greville,
        base::ExcInput(
          f + "Contact/Pair placement = " + to_string(contact.pair_placement) +
          " places point pairs, but Contact/Pairing = " +
          contact::to_string(contact.pairing) +
          " has one pair per basis function of the slave face; "
          "remove Contact/Pair placement or use Pairing = "
          "node-to-surface."));
      if (contact.enabled)
        {
          // The contact faces must exist on the bodies that carry them.
          const auto read_contact_face = [&](const BodyParameters &body,
                                             const std::string    &body_name,
                                             const std::string    &parameter,
                                             const std::string    &text) {
            return read_faces(text,
                              patch_faces_of(body, dimension),
                              f + "Contact/" + parameter + " (" + body_name +
                                ")",
                              text);
          };
          contact.slave_faces = read_contact_face(body1,
                                                  "Body 1",
                                                  "Slave face",
                                                  contact.slave_face_text);
          if (body2.type == BodyType::deformable)
            contact.master_faces = read_contact_face(body2,
                                                     "Body 2",
                                                     "Master face",
                                                     contact.master_face_text);
          // A face of a patch the geometry file does not have.
          for (const auto *body : {&body1, &body2})
            if (body->type == BodyType::deformable)
              check_face_patches(*body,
                                 body == &body1 ? contact.slave_faces :
                                                  contact.master_faces,
                                 dimension,
                                 f + (body == &body1 ? "Body 1" : "Body 2"));
        }
      // A body with no Supports at all is held by nothing but contact.
      for (const auto *body : {&body1, &body2})
        {
          const std::string name = (body == &body1 ? "Body 1" : "Body 2");
          AssertThrow(body->type != BodyType::deformable ||
                        !body->supports.empty() ||
                        !body->point_supports.empty() ||
                        !body->face_motions.empty() || contact.enabled,
                      base::ExcInput(
                        f + name +
                        "/Supports is empty and the scene has no contact "
                        "(Contact/Enabled = false): nothing holds " +
                        name +
                        " against rigid motion; add Supports, e.g. "
                        "'0: x; 2: y'."));
        }
      AssertThrow(!contact.enabled || body2.type != BodyType::deformable ||
                    !body1.supports.empty() || !body2.supports.empty() ||
                    !body1.point_supports.empty() ||
                    !body2.point_supports.empty() ||
                    !body1.face_motions.empty() || !body2.face_motions.empty(),
                  base::ExcInput(
                    f + "Body 1/Supports and Body 2/Supports are both empty: "
                        "contact only acts between the two bodies, so "
                        "nothing holds them against rigid motion; add "
                        "Supports to Body 2, e.g. '2: x y'."));
      AssertThrow(checks.hertz_line_load == 0. || dimension == 2,
                  base::ExcInput(f + "Checks/Hertz line load is the 2D "
                                     "line contact; in 3D set Checks/Hertz "
                                     "point load (a sphere) instead."));
      AssertThrow(checks.hertz_point_load == 0. || dimension == 3,
                  base::ExcInput(f + "Checks/Hertz point load is the 3D "
                                     "point contact of a sphere; in 2D set "
                                     "Checks/Hertz line load instead."));
      if (checks.hertz_line_load > 0. || checks.hertz_point_load > 0.)
        {
          if (!checks.hertz_axis_direction_text.empty())
            checks.hertz_axis_direction =
              read_direction(checks.hertz_axis_direction_text,
                             dimension,
                             f + "Checks/Hertz axis direction");
          if (!checks.hertz_axis_point_text.empty())
            checks.hertz_axis_point = read_point(checks.hertz_axis_point_text,
                                                 dimension,
                                                 f + "Checks/Hertz axis point");
          AssertThrow(checks.hertz_radius > 0. ||
                        body1.geometry != Geometry::file,
                      base::ExcInput(f + "Checks/Hertz radius = 0 takes "
                                         "Body 1/Radius, which a geometry "
                                         "file does not have; give the "
                                         "radius of the contact surface, "
                                         "e.g. 'set Hertz radius = 1'."));
        }
      AssertThrow(load_path.displacement_factors.empty() ||
                    load_path.load_factors.empty() ||
                    load_path.displacement_factors.size() ==
                      load_path.load_factors.size(),
                  base::ExcInput(
                    f + "Load path/Displacement factors has " +
                    std::to_string(load_path.displacement_factors.size()) +
                    " entries but Load path/Load factors has " +
                    std::to_string(load_path.load_factors.size()) +
                    "; give both lists the same length."));
      const std::size_t n_steps = load_path.steps().size();
      for (const auto &h : load_path.histories)
        AssertThrow(h.second.size() == n_steps,
                    base::ExcInput(f + "Load path/Histories: '" + h.first +
                                   "' has " + std::to_string(h.second.size()) +
                                   " factors but the load path has " +
                                   std::to_string(n_steps) +
                                   " steps; give one factor per step."));
      // Every history a load entry names must exist.
      for (const auto *body : {&body1, &body2})
        {
          const std::string where =
            f + (body == &body1 ? "Body 1" : "Body 2") + ": ";
          const auto known = [&](const std::string &name) {
            bool found =
              name.empty() || name == "load" || name == "displacement";
            std::string names = "load, displacement";
            for (const auto &h : load_path.histories)
              {
                found = found || h.first == name;
                names += ", " + h.first;
              }
            AssertThrow(found,
                        base::ExcInput(where + "load history '" + name +
                                       "' is not declared in Load "
                                       "path/Histories; declared: " +
                                       names + "."));
          };
          for (const auto &s : body->supports)
            known(s.history);
          for (const auto &t : body->tractions)
            known(t.history);
          for (const auto &l : body->point_loads)
            known(l.history);
          for (const auto &m : body->moments)
            known(m.history);
          for (const auto &m : body->face_motions)
            known(m.history);
          for (const auto &p : body->point_supports)
            known(p.history);
        }
      // A traction that depends on t gets one history per step: factor 1
      // at its step, 0 elsewhere, the expression evaluated at that step's
      // factor of the history it names.
      const auto factors = load_path.history_factors();
      for (auto *body : {&body1, &body2})
        for (auto &traction : body->tractions)
          if (traction.kind == TractionParameters::Kind::function &&
              traction.uses_t)
            {
              const unsigned int base =
                load_path.history_index(traction.history, 0);
              traction.step_t.clear();
              traction.step_histories.clear();
              for (unsigned int s = 0; s < n_steps; ++s)
                {
                  traction.step_t.push_back(factors[s][base]);
                  traction.step_histories.push_back(
                    2 + load_path.histories.size() +
                    load_path.step_history_steps.size());
                  load_path.step_history_steps.push_back(s);
                }
            }
    }

  } // namespace scene
} // namespace igabde
