#include <igabde/base/utilities.h>

#include <igabde/discretization/body.h>

#include <igabde/scene/geometry.h>
#include <igabde/scene/parameters.h>

#include <algorithm>
#include <string>

namespace igabde
{
  namespace scene
  {
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
                          "flat obstacle with no mesh and no unknowns (Plane "
                          "point, Plane normal). rigid cylinder: a circle of "
                          "Radius about Centre (2D) or the infinite circular "
                          "cylinder of Radius about the axis through Centre "
                          "along Axis (3D), touched from outside. rigid "
                          "sphere (3D): the sphere of Radius about Centre, "
                          "touched from outside. rigid surface: the exact "
                          "Geometry (a built-in shape or a Geometry file, "
                          "with its Subdivisions), rigid; Contact/Master "
                          "face names the faces that Body 1 touches, e.g. "
                          "a punch with rounded corners. A rigid obstacle "
                          "is fixed or moved by Motion (Body 2 only). none: "
                          "no such body (Body 2 only).");
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
                          "Radius (m) of the hertz quarter disc, of the "
                          "full/half discs and cylinders, and of the rigid "
                          "cylinder and sphere.");
        prm.declare_entry("Centre",
                          "",
                          Patterns::Anything(),
                          "full/half disc: centre (m), 'x, y'; full/half "
                          "cylinder: centre of the base face z = const, "
                          "'x, y, z'; rigid cylinder: a point on its axis; "
                          "rigid sphere: its centre. Empty: the origin.");
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
          "Kinematics",
          "small",
          Patterns::Selection(base::selection_of(elasticity::kinematics_names)),
          "small: linear elasticity, small strain and rotation (one linear "
          "solve per load step). finite: finite strain and rotation, total "
          "Lagrangian, Newton's method at every load step; needs a "
          "finite-strain Material.");
        prm.declare_entry(
          "Material",
          "linear",
          Patterns::Selection(
            base::selection_of(elasticity::material_model_names)),
          "The material law. linear: Hooke's law (Kinematics = small). "
          "saint venant-kirchhoff: W = lambda/2 (tr E)^2 + mu E:E. "
          "neo-hookean: the compressible W = mu/2 (tr C - 3) - mu ln J + "
          "lambda/2 (ln J)^2. lambda and mu are Lame's constants of Young's "
          "modulus and Poisson's ratio (Kinematics = finite).");
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
          "displacement (m) of the face's centroid c (or of the point "
          "named by 'about cx, cy[, cz]' after the values) and r the "
          "rotation (rad, small: the rotation is linearised, as the "
          "small-strain model requires), scaled by the step's displacement "
          "factor (or by the load history 'name' when the entry ends in '@ "
          "name'); "
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
        prm.declare_entry("Axis",
                          "0, 0, 1",
                          Patterns::Anything(),
                          "rigid cylinder (3D): the direction of its axis, "
                          "not zero.");
        prm.declare_entry(
          "Motion",
          "",
          Patterns::Anything(),
          "Rigid obstacles: the prescribed rigid motion, 'ux, uy[, uz]' "
          "(m), or with the rotation 'ux, uy, rz' (2D) / 'ux, uy, uz, rx, "
          "ry, rz' (3D; rad, small: linearised, about Centre, Plane point "
          "for a plane, the mean of the contact faces' centroids for a "
          "rigid surface), scaled by the step's displacement factor (or "
          "by the load history 'name' when the entry ends in '@ name'); "
          "several entries separated by ';' add up, e.g. '0, -0.01; 0.02, 0 "
          "@ slide' presses an indenter with the displacement factors and "
          "slides it with the history 'slide'. Empty: fixed.");
      }
      prm.leave_subsection();
    }



    PatchFaces
    patch_faces_of(const BodyParameters &body, const unsigned int dimension)
    {
      return {patch_faces(body.geometry, dimension),
              body.geometry == Geometry::file,
              to_string(body.geometry)};
    }



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
        AssertThrow(face / (2 * dimension) < body.n_patches,
                    base::ExcInput(where + "/" + parameter + ": face " +
                                   discretization::face_name(face, dimension) +
                                   " is on patch " +
                                   std::to_string(face / (2 * dimension)) +
                                   ", but the geometry has " +
                                   std::to_string(body.n_patches) + " patch" +
                                   (body.n_patches == 1 ? "" : "es") + " (0.." +
                                   std::to_string(body.n_patches - 1) + ")."));
    }



    void
    BodyParameters::parse_parameters(ParameterHandler  &prm,
                                     const std::string &name,
                                     const unsigned int dimension,
                                     const std::string &context)
    {
      std::string supports_text, tractions_text, point_loads_text, hold_text,
        moments_text, point_supports_text, face_motions_text, body_force_text,
        lower_text, upper_text, centre_text, subdivisions_text, grading_text,
        point_text, normal_text, axis_text, motion_text;
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
        kinematics =
          base::value_of(elasticity::kinematics_names, prm.get("Kinematics"));
        material =
          base::value_of(elasticity::material_model_names, prm.get("Material"));
        supports_text       = prm.get("Supports");
        hold_text           = prm.get("Hold rotation");
        tractions_text      = prm.get("Tractions");
        point_loads_text    = prm.get("Point loads");
        moments_text        = prm.get("Moments");
        point_supports_text = prm.get("Point supports");
        face_motions_text   = prm.get("Face motions");
        body_force_text     = prm.get("Body force");
        point_text          = prm.get("Plane point");
        normal_text         = prm.get("Plane normal");
        axis_text           = prm.get("Axis");
        motion_text         = prm.get("Motion");
      }
      prm.leave_subsection();

      body_force.assign(dimension, 0.);
      const std::string where           = context + name + "/";
      const auto        optional_vector = [&](const std::string &text,
                                       const std::string &parameter) {
        return base::trim(text).empty() ?
                        std::vector<double>() :
                        read_vector(text, dimension, where + parameter);
      };
      motion.clear();
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
      if (type == BodyType::rigid_sphere)
        AssertThrow(dimension == 3,
                    base::ExcInput(where +
                                   "Type = rigid sphere is a 3D obstacle; "
                                   "in 2D use Type = rigid cylinder (a "
                                   "circle of Radius about Centre)."));
      if (type == BodyType::rigid_cylinder || type == BodyType::rigid_sphere)
        {
          centre = optional_vector(centre_text, "Centre");
          if (centre.empty())
            centre.assign(dimension, 0.);
          AssertThrow(radius > 0.,
                      base::ExcInput(
                        where + "Radius = " + base::number_text(radius) +
                        " must be > 0 (m) for a rigid " +
                        (type == BodyType::rigid_sphere ? "sphere" :
                                                          "cylinder") +
                        "; give the obstacle's radius."));
          if (type == BodyType::rigid_cylinder && dimension == 3)
            {
              axis = read_vector(axis_text, dimension, where + "Axis");
              AssertThrow(std::any_of(axis.begin(),
                                      axis.end(),
                                      [](const double x) {
                                        return x != 0.;
                                      }),
                          base::ExcInput(where + "Axis = '" + axis_text +
                                         "' must not be zero; give the "
                                         "direction of the cylinder's "
                                         "axis, e.g. '0, 0, 1'."));
            }
        }
      if (is_obstacle(type))
        motion = read_obstacle_motion(motion_text, dimension, where + "Motion");
      else
        AssertThrow(base::trim(motion_text).empty(),
                    base::ExcInput(where + "Motion is for rigid obstacles "
                                           "(Type = rigid plane, cylinder, "
                                           "sphere or surface); move a "
                                           "deformable "
                                           "body's faces with Face motions "
                                           "or Supports."));
      supports.clear();
      tractions.clear();
      point_loads.clear();
      moments.clear();
      face_motions.clear();
      point_supports.clear();
      body_force_expressions.clear();
      if (type != BodyType::deformable && type != BodyType::rigid_surface)
        return;

      // The points and counts of the geometry, each read once.
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
      // A geometry the dimension does not have (a rigid surface needs one
      // as much as a deformable body).
      const PatchFaces faces = patch_faces_of(*this, dimension);
      AssertThrow(!faces.names.empty(),
                  base::ExcInput(where + "Geometry = " + to_string(geometry) +
                                 " does not exist in " +
                                 std::to_string(dimension) +
                                 "D; choose another geometry or Dimension."));
      if (type == BodyType::rigid_surface)
        return;

      // What no material and no body can have, refused before any set-up.
      AssertThrow(youngs_modulus > 0.,
                  base::ExcInput(where + "Young's modulus = " +
                                 base::number_text(youngs_modulus) +
                                 " must be > 0 (Pa); set the material's "
                                 "stiffness, e.g. 1000."));
      AssertThrow(poisson_ratio > -1. && poisson_ratio < 0.5,
                  base::ExcInput(where + "Poisson's ratio = " +
                                 base::number_text(poisson_ratio) +
                                 " must lie in -1 < nu < 0.5; nearly "
                                 "incompressible materials need nu < 0.5 "
                                 "(e.g. 0.49)."));

      // The law must belong to the kinematics.
      AssertThrow(kinematics == elasticity::Kinematics::small ||
                    material != elasticity::MaterialModel::linear,
                  base::ExcInput(where +
                                 "Kinematics = finite needs a finite-strain "
                                 "law, but Material = linear; set Material = "
                                 "neo-hookean (or saint venant-kirchhoff)."));
      AssertThrow(kinematics == elasticity::Kinematics::finite ||
                    material == elasticity::MaterialModel::linear,
                  base::ExcInput(
                    where + "Material = " + elasticity::to_string(material) +
                    " is a finite-strain law, but Kinematics = "
                    "small; set Kinematics = finite (or "
                    "Material = linear)."));

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
  } // namespace scene
} // namespace igabde
