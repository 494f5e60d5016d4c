#include <igabde/base/utilities.h>

#include <igabde/contact/contact_solver.h>
#include <igabde/contact/pairing.h>
#include <igabde/contact/sliding.h>

#include <igabde/scene/parameters.h>

// The Contact subsection: the solver settings and the interactions.

namespace igabde
{
  namespace scene
  {
    void
    ContactParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      {
        prm.declare_entry("Enabled",
                          "false",
                          Patterns::Bool(),
                          "Whether the scene has contact: the interaction "
                          "written here (Slave body on Master body) and "
                          "those of Interaction 2 ... 8.");
        prm.declare_entry("Slave body",
                          "1",
                          Patterns::Integer(1, max_bodies),
                          "The first interaction's slave: Body k, a "
                          "deformable body.");
        prm.declare_entry("Master body",
                          "2",
                          Patterns::Integer(1, max_bodies),
                          "The first interaction's master: Body k, "
                          "deformable or rigid.");
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
        prm.declare_entry("Sliding",
                          "small",
                          Patterns::Selection(
                            base::selection_of(contact::sliding_names)),
                          "small: the pairs are formed once, on the "
                          "reference configuration (sliding well below the "
                          "pair spacing). finite: formed again on the "
                          "current configuration, which slave parts face a "
                          "master at the start of every load step and their "
                          "master points, normals and gaps at every Newton "
                          "iterate (the full path, contact paired by the "
                          "weighted gap, masters that are bodies or fixed "
                          "obstacles; with friction the slip of a step is "
                          "measured against the master point the slave "
                          "faced at the step's start).");
        prm.declare_entry(
          "Sliding tangent",
          "full",
          Patterns::Selection(
            base::selection_of(contact::sliding_tangent_names)),
          "Sliding = finite: the Newton matrix's contact rows. full (the "
          "default): the derivatives of the pairs' gaps, slips and force "
          "directions by the configuration, for the pairs that carry a "
          "force or nearly touch: in closed form where the master's normal "
          "is continuous (an obstacle, NURBS faces of degree 2 or more, any "
          "face whose normal turns by less than 0.05 at its element edges), "
          "by finite differences of the pairing elsewhere (those "
          "pairs formed again once per group of unknowns that no pair reads "
          "together); the Newton iteration converges fast where contact "
          "pressures are large against the stiffness on curved surfaces. "
          "differences: the same derivatives by finite differences "
          "everywhere (the closed form's check; slower). frozen: the pairs' "
          "operators at the iterate (one pairing per iteration, linear "
          "convergence, slow where the pressure is a sizeable part of the "
          "modulus; cheaper per iteration where most pairs are in "
          "contact). auto: frozen until the residual contracts slowly (two "
          "iterations after the first each cut it by less than 20x), full "
          "from there to the end of the Newton solve.");
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
                          "Patch face of the slave body that may touch the "
                          "master: f, or p.f for face f of patch p of a "
                          "multi-patch geometry file; several joined by '+'.");
        prm.declare_entry("Master face",
                          "3",
                          Patterns::Anything(),
                          "Patch face of the master body that may touch the "
                          "slave: f or p.f, several joined by '+' (also the "
                          "faces of a rigid surface).");
        prm.declare_entry("Search distance",
                          "0",
                          Patterns::Double(0.),
                          "Slave points farther than this (m) from their "
                          "closest point of the master are left out and "
                          "counted (summary.json contact_points_left_out): "
                          "the contact surface cut to the part within this "
                          "distance of the other one. 0: no limit.");
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
          "How the slave's contact face is paired with the surface it faces. "
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
        for (unsigned int k = 2; k <= max_interactions; ++k)
          {
            prm.enter_subsection("Interaction " + std::to_string(k));
            prm.declare_entry("Slave body",
                              "0",
                              Patterns::Integer(0, max_bodies),
                              "Body k whose faces touch the master in this "
                              "interaction; 0: no such interaction.");
            prm.declare_entry("Slave face",
                              "",
                              Patterns::Anything(),
                              "Its patch faces: f or p.f, several joined by "
                              "'+'.");
            prm.declare_entry("Master body",
                              "0",
                              Patterns::Integer(0, max_bodies),
                              "Body k (deformable or rigid) that the slave "
                              "touches.");
            prm.declare_entry("Master face",
                              "",
                              Patterns::Anything(),
                              "Its patch faces: f or p.f, several joined by "
                              "'+'.");
            prm.declare_entry("Friction coefficient",
                              "",
                              Patterns::Anything(),
                              "Coulomb mu >= 0 of this interaction; empty: "
                              "Contact/Friction coefficient.");
            prm.declare_entry("Search distance",
                              "",
                              Patterns::Anything(),
                              "As Contact/Search distance, for this "
                              "interaction; empty: Contact's.");
            prm.declare_entry(
              "Pairing",
              "as Contact",
              Patterns::Selection("as Contact|" +
                                  base::selection_of(contact::pairing_names)),
              "As Contact/Pairing, for this interaction; as Contact: "
              "Contact/Pairing.");
            prm.leave_subsection();
          }
      }
      prm.leave_subsection();
    }



    void
    ContactParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      {
        enabled = prm.get_bool("Enabled");
        // The first interaction is filled here and copied into the list
        // once complete (a reference into the list would dangle as the
        // list grows).
        InteractionParameters first;
        first.slave_body           = prm.get_integer("Slave body");
        first.master_body          = prm.get_integer("Master body");
        first.friction_coefficient = prm.get_double("Friction coefficient");
        first.search_distance      = prm.get_double("Search distance");
        algorithm =
          base::value_of(contact::algorithm_names, prm.get("Algorithm"));
        penalty_factor            = prm.get_double("Penalty factor");
        tangential_penalty_factor = prm.get_double("Tangential penalty factor");
        full_system_solver =
          base::value_of(coupled::solver_names, prm.get("Full system solver"));
        krylov_max_iterations = prm.get_integer("Krylov max iterations");
        penalty_line_search   = prm.get_bool("Penalty line search");
        path = base::value_of(contact::path_names, prm.get("Path"));
        finite_sliding =
          base::value_of(contact::sliding_names, prm.get("Sliding")) ==
          contact::Sliding::finite;
        sliding_tangent = base::value_of(contact::sliding_tangent_names,
                                         prm.get("Sliding tangent"));
        condensation =
          base::value_of(contact::condensation_names, prm.get("Condensation"));
        first.slave_face_text  = base::trim(prm.get("Slave face"));
        first.master_face_text = base::trim(prm.get("Master face"));
        pair_placement = base::value_of(discretization::pair_placement_names,
                                        prm.get("Pair placement"));
        first.pairing =
          base::value_of(contact::pairing_names, prm.get("Pairing"));
        tolerance      = prm.get_double("Tolerance");
        max_iterations = prm.get_integer("Max iterations");
        r_scale        = prm.get_double("r scale");
        verbose        = prm.get_bool("Verbose");
        max_step_cuts  = prm.get_integer("Max step cuts");
        interactions.assign(1, first);
        for (unsigned int k = 2; k <= max_interactions; ++k)
          {
            const std::string name = "Interaction " + std::to_string(k);
            prm.enter_subsection(name);
            if (prm.get_integer("Slave body") > 0 ||
                prm.get_integer("Master body") > 0)
              {
                InteractionParameters c;
                c.name             = "Contact/" + name;
                c.slave_body       = prm.get_integer("Slave body");
                c.master_body      = prm.get_integer("Master body");
                c.slave_face_text  = base::trim(prm.get("Slave face"));
                c.master_face_text = base::trim(prm.get("Master face"));
                // An empty friction coefficient is Contact's; check_scene()
                // reads the text, naming the file.
                c.friction_text = base::trim(prm.get("Friction coefficient"));
                c.friction_coefficient = first.friction_coefficient;
                c.search_text          = base::trim(prm.get("Search distance"));
                c.search_distance      = first.search_distance;
                const std::string pairing_text = prm.get("Pairing");
                c.pairing =
                  pairing_text == "as Contact" ?
                    first.pairing :
                    base::value_of(contact::pairing_names, pairing_text);
                interactions.push_back(c);
              }
            prm.leave_subsection();
          }
      }
      prm.leave_subsection();
    }
  } // namespace scene
} // namespace igabde
