#include <igabde/base/disjoint_sets.h>
#include <igabde/base/utilities.h>

#include <igabde/contact/contact_solver.h>
#include <igabde/contact/pairing.h>

#include <igabde/scene/parameters.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /**
       * Refuses what a body at finite strain cannot follow (yet): contact
       * on the condensed path or with the iterative full-system solver,
       * a held mean rotation and face moments (distributing couplings
       * linearised about the reference configuration), tractions from a
       * small-strain exact solution, and more than one MPI process.
       */
      void
      check_finite_strain(const AllParameters &parameters, const std::string &f)
      {
        for (unsigned int b = 0; b < parameters.bodies.size(); ++b)
          {
            const BodyParameters *body = &parameters.bodies[b];
            if (body->type != BodyType::deformable ||
                body->kinematics != elasticity::Kinematics::finite)
              continue;
            const std::string where = f + "Body " + std::to_string(b + 1) + "/";
            AssertThrow(
              parameters.dimension == 3 ||
                parameters.plane_model ==
                  elasticity::PlaneModel::plane_strain ||
                elasticity::HyperelasticMaterial<2>::supports_plane_stress(
                  body->material),
              base::ExcInput(
                where + "Material = " + elasticity::to_string(body->material) +
                " has no plane-stress form (its C_33 would be "
                "solved at every point); set Plane model = "
                "plane strain, or Material = saint "
                "venant-kirchhoff."));
            AssertThrow(!parameters.contact.enabled ||
                          parameters.contact.path != contact::Path::condensed,
                        base::ExcInput(
                          where +
                          "Kinematics = finite with Contact/Path = condensed: "
                          "the condensation takes the small-strain stiffness "
                          "once, and a body at finite strain changes its "
                          "tangent in every Newton iteration; set "
                          "Contact/Path = full (or auto)."));
            AssertThrow(!parameters.contact.enabled ||
                          parameters.contact.full_system_solver !=
                            coupled::Solver::gmres_amg,
                        base::ExcInput(
                          where +
                          "Kinematics = finite with Contact/Full system "
                          "solver = gmres-amg: its multigrid is built once "
                          "on the small-strain stiffness; set Contact/Full "
                          "system solver = mumps (or klu)."));
            AssertThrow(body->hold_rotation_face < 0,
                        base::ExcInput(
                          where +
                          "Hold rotation holds the mean small rotation of a "
                          "face, which does not follow a finite rotation; "
                          "with Kinematics = finite hold the face by "
                          "Supports or Face motions instead."));
            AssertThrow(body->moments.empty(),
                        base::ExcInput(
                          where +
                          "Moments are spread over the face as a linear "
                          "traction of the reference configuration, which "
                          "does not follow a finite rotation; with "
                          "Kinematics = finite apply the load as Tractions "
                          "or Point loads."));
            for (const auto &traction : body->tractions)
              AssertThrow(traction.kind != TractionParameters::Kind::exact,
                          base::ExcInput(
                            where + "Tractions: face " +
                            std::to_string(traction.face) +
                            ": 'exact' is the traction of a small-strain "
                            "exact solution; with Kinematics = finite give "
                            "the traction as 'vector' or 'function'."));
          }
        if (!parameters.finite_strain())
          return;
        AssertThrow(parameters.exact.type == ExactSolutionType::none,
                    base::ExcInput(
                      f + "Exact solution/Type = " +
                      to_string(parameters.exact.type) +
                      " is a solution of linear elasticity, which a body at "
                      "Kinematics = finite does not follow; set Exact "
                      "solution/Type = none."));
        AssertThrow(parameters.nonlinear_solver.tolerance > 0.,
                    base::ExcInput(
                      f + "Nonlinear solver/Tolerance = " +
                      base::number_text(parameters.nonlinear_solver.tolerance) +
                      " must be > 0 (the residual relative to the largest "
                      "force at which Newton's method stops; e.g. 1e-10)."));
        // (A scene read without MPI, as the fuzz target reads them, runs
        // in one process.)
        AssertThrow(!dealii::Utilities::MPI::job_supports_mpi() ||
                      dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) ==
                        1,
                    base::ExcInput(
                      f + "Kinematics = finite runs in one process (its Newton "
                          "solves are threaded, not distributed); run it "
                          "without mpirun."));
      }



      /**
       * Contact/Sliding = finite with what it cannot follow yet: refused with
       * the fix.
       */
      void
      check_finite_sliding(const AllParameters &parameters,
                           const std::string   &f)
      {
        const ContactParameters &contact = parameters.contact;
        const std::string        what    = f + "Contact/Sliding = finite ";
        AssertThrow(contact.path != contact::Path::condensed,
                    base::ExcInput(what +
                                   "forms the pairs at every Newton iterate, "
                                   "which only the full path follows; set "
                                   "Contact/Path = full or auto."));
        AssertThrow(contact.algorithm == contact::Algorithm::bde,
                    base::ExcInput(what + "is solved by the B-Newton; set "
                                          "Contact/Algorithm = bde."));
        AssertThrow(contact.full_system_solver != coupled::Solver::gmres_amg,
                    base::ExcInput(what +
                                   "factorises its Newton matrix; set Contact/"
                                   "Full system solver = mumps or klu."));
        for (const InteractionParameters &c : contact.interactions)
          {
            AssertThrow(c.pairing == contact::Pairing::weighted_gap ||
                          c.pairing == contact::Pairing::weighted_gap_standard,
                        base::ExcInput(
                          what + "pairs by the weighted gap, but " + c.name +
                          "/Pairing = " + contact::to_string(c.pairing) +
                          "; set it to weighted-gap."));
          }
        for (unsigned int b = 0; b < parameters.bodies.size(); ++b)
          AssertThrow(parameters.bodies[b].type != BodyType::deformable ||
                        parameters.bodies[b].hold_rotation_face < 0,
                      base::ExcInput(what +
                                     "runs on the full path, which has "
                                     "no rows for Body " +
                                     std::to_string(b + 1) +
                                     "/Hold rotation; hold the body by "
                                     "Supports or Face motions."));
      }
    } // namespace


    void
    check_scene(AllParameters &parameters, const std::string &f)
    {
      const unsigned int dimension = parameters.dimension;
      auto              &bodies    = parameters.bodies;
      auto              &body1     = bodies[0];
      auto              &contact   = parameters.contact;
      auto              &exact     = parameters.exact;
      auto              &checks    = parameters.checks;
      auto              &load_path = parameters.load_path;
      const auto        &output    = parameters.output;
      check_finite_strain(parameters, f);
      AssertThrow(body1.type == BodyType::deformable,
                  base::ExcInput(f +
                                 "Body 1/Type must be 'deformable'; only "
                                 "Body 2 ... Body " +
                                 std::to_string(max_bodies) +
                                 " may be rigid obstacles (rigid "
                                 "plane, cylinder, sphere or "
                                 "surface)."));
      const unsigned int n_bodies  = parameters.n_bodies();
      const auto         body_name = [](const unsigned int b) {
        return "Body " + std::to_string(b + 1);
      };
      for (unsigned int b = n_bodies; b < bodies.size(); ++b)
        AssertThrow(bodies[b].type == BodyType::none,
                    base::ExcInput(f + body_name(b) + "/Type is '" +
                                   to_string(bodies[b].type) + "' but " +
                                   body_name(n_bodies) +
                                   "/Type is 'none'; number the bodies from "
                                   "Body 1 without gaps."));
      auto &interactions = contact.interactions;
      // The interactions' friction coefficients as written.
      for (InteractionParameters &c : interactions)
        if (!c.friction_text.empty())
          {
            const std::vector<double> mu =
              base::parse_doubles(c.friction_text,
                                  f + c.name + "/Friction coefficient");
            AssertThrow(mu.size() == 1,
                        base::ExcInput(f + c.name + "/Friction coefficient = " +
                                       c.friction_text +
                                       " is not one number; give mu >= 0 "
                                       "or leave it empty for Contact's."));
            c.friction_coefficient = mu[0];
          }
      for (InteractionParameters &c : interactions)
        if (!c.search_text.empty())
          {
            const std::vector<double> d =
              base::parse_doubles(c.search_text,
                                  f + c.name + "/Search distance");
            AssertThrow(d.size() == 1 && d[0] >= 0.,
                        base::ExcInput(f + c.name +
                                       "/Search distance = " + c.search_text +
                                       " is not one length >= 0; give the "
                                       "distance (m), 0 for no limit, or "
                                       "leave it empty for Contact's."));
            c.search_distance = d[0];
          }
      for (const InteractionParameters &c : interactions)
        AssertThrow(c.friction_coefficient >= 0.,
                    base::ExcInput(
                      f + c.name + "/Friction coefficient = " +
                      base::number_text(c.friction_coefficient) +
                      " is negative; use mu >= 0 (0 for frictionless)."));
      const bool friction =
        std::any_of(interactions.begin(), interactions.end(), [](auto &c) {
          return c.friction_coefficient > 0.;
        });
      AssertThrow(!output.fclib_export ||
                    (contact.enabled && friction &&
                     contact.algorithm == contact::Algorithm::bde &&
                     contact.path != contact::Path::full),
                  base::ExcInput(
                    f + "Output/FCLIB export = true needs a contact problem "
                        "with friction on the condensed path (Contact/Enabled "
                        "= true, Friction coefficient > 0, Algorithm = bde, "
                        "Path = condensed or auto): FCLIB's local problems "
                        "have two or three components per contact and a "
                        "flexibility W; set it to false for this scene."));
      AssertThrow(!contact.enabled || n_bodies >= 2,
                  base::ExcInput(f + "Contact/Enabled is true but Body 2/Type "
                                     "is 'none'; set Body 2/Type to "
                                     "'deformable' or a rigid obstacle "
                                     "('rigid plane', 'rigid cylinder', "
                                     "'rigid sphere', 'rigid surface')."));
      if (contact.enabled)
        for (const InteractionParameters &c : interactions)
          {
            const std::string bodies_known =
              "; the scene has Body 1 ... " + body_name(n_bodies - 1) +
              " (those before the first Type = none)";
            AssertThrow(c.slave_body >= 1 && c.slave_body <= n_bodies,
                        base::ExcInput(f + c.name + "/Slave body = " +
                                       std::to_string(c.slave_body) +
                                       " names no body" + bodies_known + "."));
            AssertThrow(c.master_body >= 1 && c.master_body <= n_bodies,
                        base::ExcInput(f + c.name + "/Master body = " +
                                       std::to_string(c.master_body) +
                                       " names no body" + bodies_known + "."));
            AssertThrow(bodies[c.slave_body - 1].type == BodyType::deformable,
                        base::ExcInput(
                          f + c.name +
                          "/Slave body = " + std::to_string(c.slave_body) +
                          " is a " + to_string(bodies[c.slave_body - 1].type) +
                          ", which has no unknowns; make the deformable "
                          "body the slave and the obstacle the master."));
            AssertThrow(c.master_body != c.slave_body,
                        base::ExcInput(
                          f + c.name + "/Master body = Slave body = " +
                          std::to_string(c.slave_body) +
                          ": a body in contact with itself is not modelled; "
                          "name another body as the master."));
            AssertThrow(!c.slave_face_text.empty() &&
                          !c.master_face_text.empty(),
                        base::ExcInput(f + c.name +
                                       "/Slave face and Master face must "
                                       "both name patch faces (f or p.f)."));
          }
      if (contact.enabled)
        for (unsigned int k = 0; k < interactions.size(); ++k)
          for (unsigned int l = 0; l < k; ++l)
            AssertThrow(
              !(interactions[k].slave_body == interactions[l].slave_body &&
                interactions[k].master_body == interactions[l].master_body &&
                interactions[k].slave_face_text ==
                  interactions[l].slave_face_text &&
                interactions[k].master_face_text ==
                  interactions[l].master_face_text),
              base::ExcInput(f + interactions[k].name + " repeats " +
                             interactions[l].name +
                             " (the same faces of the same bodies); remove "
                             "one of them."));
      AssertThrow(contact.algorithm == contact::Algorithm::bde ||
                    contact.path != contact::Path::condensed,
                  base::ExcInput(f + "Contact/Algorithm = " +
                                 contact::to_string(contact.algorithm) +
                                 " solves the full system; set Contact/Path "
                                 "to 'full' or 'auto' (or use Algorithm = "
                                 "bde for the condensed path)."));
      // A held rotation is a constraint the coupled system has no rows for.
      for (unsigned int b = 0; b < n_bodies; ++b)
        if (const BodyParameters *body = &bodies[b];
            contact.enabled && body->type == BodyType::deformable &&
            body->hold_rotation_face >= 0)
          {
            const std::string name = body_name(b);
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
      if (contact.enabled && contact.finite_sliding)
        check_finite_sliding(parameters, f);
      // What the contact solver would refuse only when it is built.
      AssertThrow(contact.tolerance > 0.,
                  base::ExcInput(f + "Contact/Tolerance = " +
                                 base::number_text(contact.tolerance) +
                                 " must be > 0 (the natural-map residual "
                                 "relative to ||q|| at which a solve stops; "
                                 "e.g. 1e-10)."));
      AssertThrow(contact.r_scale > 0.,
                  base::ExcInput(f + "Contact/r scale = " +
                                 base::number_text(contact.r_scale) +
                                 " must be > 0 (a factor on the per-pair "
                                 "r; 1 is the default)."));
      AssertThrow(contact.penalty_factor > 0. &&
                    contact.tangential_penalty_factor > 0.,
                  base::ExcInput(f + "Contact/Penalty factor and Contact/"
                                     "Tangential penalty factor must be "
                                     "positive (FKN = 0.01 to 10 is the "
                                     "usual range)."));
      for (unsigned int b = 0; b < n_bodies; ++b)
        for (const auto &traction : bodies[b].tractions)
          AssertThrow(traction.kind != TractionParameters::Kind::exact ||
                        exact.type != ExactSolutionType::none,
                      base::ExcInput(f + body_name(b) +
                                     "/Tractions: 'exact' needs Exact "
                                     "solution/Type other than none."));
      for (const InteractionParameters &c : interactions)
        AssertThrow(
          (c.pairing != contact::Pairing::weighted_gap &&
           c.pairing != contact::Pairing::weighted_gap_standard) ||
            contact.pair_placement == discretization::PairPlacement::greville,
          base::ExcInput(f + "Contact/Pair placement = " +
                         to_string(contact.pair_placement) +
                         " places point pairs, but " + c.name +
                         "/Pairing = " + contact::to_string(c.pairing) +
                         " has one pair per basis function of the slave face; "
                         "remove Contact/Pair placement or use Pairing = "
                         "node-to-surface."));
      const auto has_faces = [](const BodyParameters &body) {
        return body.type == BodyType::deformable ||
               body.type == BodyType::rigid_surface;
      };
      if (contact.enabled)
        for (InteractionParameters &c : interactions)
          {
            // The contact faces must exist on the bodies that carry them.
            const auto read_contact_face = [&](const unsigned int b,
                                               const std::string &parameter,
                                               const std::string &text) {
              return read_faces(text,
                                patch_faces_of(bodies[b], dimension),
                                f + c.name + "/" + parameter + " (" +
                                  body_name(b) + ")",
                                text);
            };
            const unsigned int s = c.slave_body - 1, m = c.master_body - 1;
            c.slave_faces =
              read_contact_face(s, "Slave face", c.slave_face_text);
            if (has_faces(bodies[m]))
              c.master_faces =
                read_contact_face(m, "Master face", c.master_face_text);
            // A face of a patch the geometry file does not have.
            check_face_patches(bodies[s],
                               c.slave_faces,
                               dimension,
                               f + body_name(s));
            if (has_faces(bodies[m]))
              check_face_patches(bodies[m],
                                 c.master_faces,
                                 dimension,
                                 f + body_name(m));
          }
      // A body is held against rigid motion by its supports, or through
      // the contact interactions by a body that is or by an obstacle: the
      // deformable bodies the interactions join, each group with one held
      // body at least.
      const auto supported = [](const BodyParameters &body) {
        return !body.supports.empty() || !body.point_supports.empty() ||
               !body.face_motions.empty();
      };
      base::DisjointSets groups(n_bodies);
      std::vector<bool>  in_interaction(n_bodies, false);
      if (contact.enabled)
        for (const InteractionParameters &c : interactions)
          {
            in_interaction[c.slave_body - 1]  = true;
            in_interaction[c.master_body - 1] = true;
            groups.join(c.slave_body - 1, c.master_body - 1);
          }
      std::vector<bool> held(n_bodies, false);
      for (unsigned int b = 0; b < n_bodies; ++b)
        if (bodies[b].type != BodyType::deformable || supported(bodies[b]))
          held[groups.find(b)] = true;
      for (unsigned int b = 0; b < n_bodies; ++b)
        {
          if (bodies[b].type != BodyType::deformable || supported(bodies[b]))
            continue;
          const std::string name = body_name(b);
          AssertThrow(contact.enabled,
                      base::ExcInput(
                        f + name +
                        "/Supports is empty and the scene has no contact "
                        "(Contact/Enabled = false): nothing holds " +
                        name +
                        " against rigid motion; add Supports, e.g. "
                        "'0: x; 2: y'."));
          AssertThrow(in_interaction[b],
                      base::ExcInput(
                        f + name +
                        "/Supports is empty and no contact interaction "
                        "names " +
                        name +
                        ": nothing holds it against rigid motion; add "
                        "Supports or an interaction (Contact/Interaction k "
                        "with Slave body or Master body = " +
                        std::to_string(b + 1) + ")."));
          if (n_bodies == 2 && bodies[1].type == BodyType::deformable)
            AssertThrow(held[groups.find(b)],
                        base::ExcInput(
                          f + "Body 1/Supports and Body 2/Supports are both "
                              "empty: contact only acts between the two "
                              "bodies, so nothing holds them against rigid "
                              "motion; add Supports to Body 2, e.g. '2: x "
                              "y'."));
          AssertThrow(held[groups.find(b)],
                      base::ExcInput(
                        f + name +
                        "/Supports is empty and so are those of every body "
                        "its contact interactions join it to, none of "
                        "which touches a rigid obstacle: contact only acts "
                        "between these bodies, so nothing holds them "
                        "against rigid motion; add Supports to one of "
                        "them."));
        }
      if (checks.rounded_punch_load > 0.)
        {
          AssertThrow(dimension == 2,
                      base::ExcInput(f + "Checks/Rounded punch load is a "
                                         "2D line contact; set it to 0 in "
                                         "3D."));
          AssertThrow(checks.rounded_punch_corner_radius > 0.,
                      base::ExcInput(f + "Checks/Rounded punch corner radius "
                                         "must be > 0 (m) with a Rounded "
                                         "punch load; give the radius of "
                                         "the punch's corners."));
        }
      AssertThrow(checks.hertz_line_load == 0. || dimension == 2,
                  base::ExcInput(f + "Checks/Hertz line load is the 2D "
                                     "line contact; in 3D set Checks/Hertz "
                                     "point load (a sphere) instead."));
      AssertThrow(checks.hertz_point_load == 0. || dimension == 3,
                  base::ExcInput(f + "Checks/Hertz point load is the 3D "
                                     "point contact of a sphere; in 2D set "
                                     "Checks/Hertz line load instead."));
      AssertThrow(base::trim(checks.hertz_radii_text).empty() ||
                    checks.hertz_point_load > 0.,
                  base::ExcInput(f + "Checks/Hertz radii describes an "
                                     "elliptical point contact (3D): set "
                                     "Checks/Hertz point load too."));
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
          if (!base::trim(checks.hertz_radii_text).empty())
            {
              const std::string where = f + "Checks/Hertz radii";
              const auto bodies = base::split(checks.hertz_radii_text, ';');
              AssertThrow(bodies.size() <= 2,
                          base::ExcInput(where + " = '" +
                                         checks.hertz_radii_text +
                                         "' names more than two bodies; "
                                         "write 'R1x, R1y; R2x, R2y'."));
              std::vector<double> k(4, 0.);
              for (unsigned int b = 0; b < bodies.size(); ++b)
                {
                  const auto radii = base::split(bodies[b], ',');
                  AssertThrow(radii.size() == 2,
                              base::ExcInput(where + " = '" +
                                             checks.hertz_radii_text +
                                             "': give two radii per body "
                                             "(along Hertz principal "
                                             "direction and across it), "
                                             "e.g. '2, 1' or '2, 1; flat, "
                                             "flat'."));
                  for (unsigned int d = 0; d < 2; ++d)
                    {
                      const std::string r = base::trim(radii[d]);
                      if (r == "flat")
                        continue;
                      const double R = base::parse_doubles(r, where).at(0);
                      AssertThrow(R > 0.,
                                  base::ExcInput(where + ": radius '" + r +
                                                 "' must be positive (a "
                                                 "concave surface is not "
                                                 "a Hertz contact), or "
                                                 "'flat'."));
                      k[2 * b + d] = 1. / R;
                    }
                }
              AssertThrow(k[0] + k[2] > 0. && k[1] + k[3] > 0.,
                          base::ExcInput(where + " = '" +
                                         checks.hertz_radii_text +
                                         "': the surfaces are flat along "
                                         "one direction together, a line "
                                         "contact; use Hertz line load in "
                                         "a 2D scene."));
              checks.hertz_curvatures = k;
              checks.hertz_principal_direction =
                base::trim(checks.hertz_principal_direction_text).empty() ?
                  std::vector<double>{1., 0., 0.} :
                  read_direction(checks.hertz_principal_direction_text,
                                 dimension,
                                 f + "Checks/Hertz principal direction");
              std::vector<double> axis = checks.hertz_axis_direction;
              if (axis.empty())
                axis = {0., 0., 1.};
              const auto  &t = checks.hertz_principal_direction;
              const double dot =
                t[0] * axis[0] + t[1] * axis[1] + t[2] * axis[2];
              const double norms = std::sqrt(
                (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]) *
                (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]));
              AssertThrow(std::abs(dot) < 1e-6 * norms,
                          base::ExcInput(
                            f + "Checks/Hertz principal direction must lie "
                                "at right angles to Checks/Hertz axis "
                                "direction (the load direction)."));
            }
          AssertThrow(checks.hertz_radius > 0. ||
                        !checks.hertz_curvatures.empty() ||
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
      for (unsigned int b = 0; b < n_bodies; ++b)
        {
          const BodyParameters *body  = &bodies[b];
          const std::string     where = f + body_name(b) + ": ";
          const auto            known = [&](const std::string &name) {
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
          for (const auto &m : body->motion)
            known(m.history);
        }
      // A traction that depends on t gets one history per step: factor 1
      // at its step, 0 elsewhere, the expression evaluated at that step's
      // factor of the history it names.
      const auto factors = load_path.history_factors();
      for (BodyParameters &body : bodies)
        for (auto &traction : body.tractions)
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
