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
        prm.declare_entry("Quiet",
                          "false",
                          Patterns::Bool(),
                          "Print only warnings and errors on screen; "
                          "log.txt keeps every line. The command-line flag "
                          "--quiet sets it (and Progress = false).");
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
        prm.declare_entry(
          "Checkpoint",
          "false",
          Patterns::Bool(),
          "After each finished load step, write checkpoint-NNNN.json: the "
          "step, its factors, the displacement of every body at finite "
          "strain, the contact state with the friction history, and the "
          "finished steps' records, so that igabde SCENE --restart FOLDER "
          "continues the load path from the newest one.");
        prm.declare_entry("Restart",
                          "false",
                          Patterns::Bool(),
                          "Continue from the newest checkpoint-NNNN.json in "
                          "Output/Directory (what --restart FOLDER sets); "
                          "the scene must be the one that wrote it, Output "
                          "aside.");
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
        quiet           = prm.get_bool("Quiet");
        solver_details  = prm.get_bool("Solver details");
        export_geometry = prm.get_bool("Export geometry");
        fclib_export    = prm.get_bool("FCLIB export");
        checkpoint      = prm.get_bool("Checkpoint");
        restart         = prm.get_bool("Restart");
      }
      prm.leave_subsection();
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
        prm.declare_entry("Rounded punch load",
                          "0",
                          Patterns::Double(0.),
                          "Line load P (N/m) of a rigid flat punch with "
                          "rounded corners on Body 1 (2D, frictionless; "
                          "Ciavarella, Hills & Monno 1998), whose profile is "
                          "flat over |x| <= Rounded punch flat half-width "
                          "about the Hertz axis and rounded beyond by "
                          "Rounded punch corner radius: adds "
                          "checks.punch_half_width_exact, "
                          "punch_peak_pressure(_exact) and "
                          "punch_max_pair_deviation (largest |p_i - p(x_i)| "
                          "inside |x| < 0.9 a over the closed form's peak). "
                          "0: no such check.");
        prm.declare_entry("Rounded punch flat half-width",
                          "0",
                          Patterns::Double(0.),
                          "Half-width b (m) of the punch's flat part.");
        prm.declare_entry("Rounded punch corner radius",
                          "0",
                          Patterns::Double(0.),
                          "Radius R (m) of the punch's rounded corners, R "
                          "> 0 with a Rounded punch load.");
        prm.declare_entry("Hertz radius",
                          "0",
                          Patterns::Double(0.),
                          "Radius (m) of the Hertz cylinder or sphere; 0: "
                          "Body 2/Radius when Body 2 is a rigid cylinder or "
                          "sphere, else Body 1/Radius.");
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
        prm.declare_entry("Hertz radii",
                          "",
                          Patterns::Anything(),
                          "Elliptical point contact (3D, with Hertz point "
                          "load): the principal radii of curvature (m) of "
                          "the contact surfaces at the contact point, along "
                          "Hertz principal direction and across it, 'R1x, "
                          "R1y' for Body 1 on a flat or 'R1x, R1y; R2x, "
                          "R2y' for both bodies; 'flat' for a straight "
                          "direction (a cylinder along y: 'R, flat'). The "
                          "two bodies' principal directions are taken "
                          "aligned. Adds checks.hertz_semi_axes (Johnson "
                          "sec. 4.2, elliptic integrals). Empty: the sphere "
                          "of Hertz radius.");
        prm.declare_entry("Hertz principal direction",
                          "",
                          Patterns::Anything(),
                          "The direction along which the first radius of "
                          "each body in Hertz radii is measured; at right "
                          "angles to Hertz axis direction. Empty: x.");
      }
      prm.leave_subsection();
    }



    void
    ChecksParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Checks");
      {
        uniform_pressure   = prm.get_double("Uniform pressure");
        hertz_line_load    = prm.get_double("Hertz line load");
        hertz_point_load   = prm.get_double("Hertz point load");
        hertz_radius       = prm.get_double("Hertz radius");
        rounded_punch_load = prm.get_double("Rounded punch load");
        rounded_punch_flat_half_width =
          prm.get_double("Rounded punch flat half-width");
        rounded_punch_corner_radius =
          prm.get_double("Rounded punch corner radius");
        hertz_axis_point_text          = prm.get("Hertz axis point");
        hertz_axis_direction_text      = prm.get("Hertz axis direction");
        hertz_radii_text               = prm.get("Hertz radii");
        hertz_principal_direction_text = prm.get("Hertz principal direction");
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
          "per step each (as many as the steps); 'ramp a b n' stands for n "
          "factors rising linearly from a (exclusive) to b, 'hold f n' for n "
          "factors f (e.g. 'press: ramp 0 1 10, hold 1 100'). A traction, "
          "point load or "
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
    NonlinearSolverParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Nonlinear solver");
      {
        prm.declare_entry("Tolerance",
                          "1e-10",
                          Patterns::Double(0.),
                          "Newton's method at finite strain has converged "
                          "when the residual over the free unknowns is at "
                          "most this times the largest force of the solve "
                          "(loads and reactions), > 0.");
        prm.declare_entry("Max iterations",
                          "25",
                          Patterns::Integer(1),
                          "Newton iterations per solve before the load "
                          "step is cut.");
        prm.declare_entry("Line search",
                          "false",
                          Patterns::Bool(),
                          "true: a Newton step that does not decrease the "
                          "residual norm is halved (backtracking). false: "
                          "the full step is taken unless it inverts an "
                          "element (the residual of a bent slender "
                          "structure rises before it falls, and "
                          "backtracking on it stalls there).");
        prm.declare_entry("Max step cuts",
                          "4",
                          Patterns::Integer(0, 20),
                          "How often a load increment whose Newton solve "
                          "fails (no convergence, or an inverted element) "
                          "may be halved before the run stops.");
      }
      prm.leave_subsection();
    }



    void
    NonlinearSolverParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Nonlinear solver");
      {
        tolerance      = prm.get_double("Tolerance");
        max_iterations = prm.get_integer("Max iterations");
        max_step_cuts  = prm.get_integer("Max step cuts");
        line_search    = prm.get_bool("Line search");
      }
      prm.leave_subsection();
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
      for (unsigned int b = 2; b <= max_bodies; ++b)
        BodyParameters::declare_parameters(prm,
                                           "Body " + std::to_string(b),
                                           "none");
      ExactSolutionParameters::declare_parameters(prm);
      ContactParameters::declare_parameters(prm);
      LoadPathParameters::declare_parameters(prm);
      NonlinearSolverParameters::declare_parameters(prm);
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
      bodies.resize(max_bodies);
      for (unsigned int b = 0; b < max_bodies; ++b)
        bodies[b].parse_parameters(prm,
                                   "Body " + std::to_string(b + 1),
                                   dimension,
                                   f);
      // A geometry file is found from the scene file's folder and read
      // now, so that a bad file ends the run before anything is built.
      for (unsigned int b = 0; b < max_bodies; ++b)
        if (BodyParameters *body = &bodies[b];
            (body->type == BodyType::deformable ||
             body->type == BodyType::rigid_surface) &&
            body->geometry == Geometry::file)
          {
            const std::string name  = "Body " + std::to_string(b + 1);
            const std::string where = f + name + "/Geometry file";
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
            check_face_patches(*body, {}, dimension, f + name);
          }
      exact.parse_parameters(prm);
      contact.parse_parameters(prm);
      // Pair placement is a property of the discretised surface.
      discretization.pair_placement = contact.pair_placement;
      load_path.parse_parameters(prm);
      checks.parse_parameters(prm);

      nonlinear_solver.parse_parameters(prm);
      probes = read_probe_points(probes_text, dimension, f + "Probe points");
      // Checks that need more than a pattern; each names the parameter and
      // the fix.
      check_scene(*this, f);
    }



    bool
    AllParameters::finite_strain() const
    {
      for (const BodyParameters &body : bodies)
        if (body.type == BodyType::deformable &&
            body.kinematics == elasticity::Kinematics::finite)
          return true;
      return false;
    }



    unsigned int
    AllParameters::n_bodies() const
    {
      unsigned int n = 0;
      while (n < bodies.size() && bodies[n].type != BodyType::none)
        ++n;
      return n;
    }



    std::vector<unsigned int>
    AllParameters::deformable_bodies() const
    {
      std::vector<unsigned int> result;
      for (unsigned int b = 0; b < n_bodies(); ++b)
        if (bodies[b].type == BodyType::deformable)
          result.push_back(b);
      return result;
    }



    std::vector<unsigned int>
    AllParameters::obstacle_bodies() const
    {
      std::vector<unsigned int> result;
      for (unsigned int b = 0; b < n_bodies(); ++b)
        if (is_obstacle(bodies[b].type))
          result.push_back(b);
      return result;
    }
  } // namespace scene
} // namespace igabde
