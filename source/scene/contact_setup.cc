#include <igabde/scene/contact_setup.h>

namespace igabde
{
  namespace scene
  {
    contact::ContactSettings
    make_contact_settings(const AllParameters       &parameters,
                          const std::string         &scene_file,
                          const std::vector<double> &factor_entries,
                          const std::string         &memory_path_reason,
                          std::ostream              &log)
    {
      contact::ContactSettings cs;
      const auto              &c = parameters.contact;
      cs.friction_coefficient    = c.friction_coefficient;
      cs.slave_faces             = c.slave_faces;
      cs.master_faces            = c.master_faces;
      cs.pairing                 = c.pairing;
      cs.solver.algorithm        = c.algorithm;
      cs.solver.path             = c.path;
      cs.schur_condensation = c.condensation == contact::Condensation::schur &&
                              parameters.discretization.linear_solver ==
                                discretization::LinearSolver::direct;
      cs.solver.penalty.normal_factor     = c.penalty_factor;
      cs.solver.penalty.tangential_factor = c.tangential_penalty_factor;
      cs.solver.penalty.line_search       = c.penalty_line_search;
      cs.solver.bnewton.tolerance         = c.tolerance;
      cs.solver.bnewton.max_iterations    = c.max_iterations;
      cs.solver.bnewton.r_factor          = c.r_scale;
      cs.solver.bnewton.log               = c.verbose;
      cs.solver.bnewton.log_stream        = &log;
      cs.context                          = scene_file;
      cs.progress                         = parameters.output.progress;
      cs.log_solves                       = parameters.output.solver_details;
      cs.factor_entries                   = factor_entries;
      cs.memory_path_reason               = memory_path_reason;
      cs.n_load_steps                     = parameters.load_path.steps().size();
      return cs;
    }



    void
    record_setup(const AllParameters           &parameters,
                 const contact::ContactSummary *contact,
                 const bool                     body_force,
                 nlohmann::json                &summary)
    {
      nlohmann::json effects;
      effects["contact"]    = (contact != nullptr);
      effects["friction"]   = contact != nullptr && contact->friction;
      effects["body_force"] = body_force;
      effects["load_steps"] = parameters.load_path.steps().size();
      if (contact == nullptr)
        {
          summary["effects"] = effects;
          return;
        }
      const contact::ContactSummary &s = *contact;
      const auto                    &c = parameters.contact;
      effects["tangential_unknowns"]   = s.friction;
      effects["rigid_obstacle"]        = s.rigid_obstacle;
      if (s.rigid_obstacle)
        {
          effects["obstacle_motion"] = s.obstacle_moves;
          summary["obstacle"]        = s.obstacle_kind;
        }
      effects["initial_gaps"]             = s.initial_gaps;
      effects["floating_rigid_modes"]     = s.floating_rigid_modes;
      effects["pairs_left_out_supported"] = s.pairs_left_out;
      summary["effects"]                  = effects;
      if (s.left_out_not_facing + s.left_out_outside + s.left_out_unprojected >
          0)
        summary["contact_points_left_out"] = {
          {"candidates", s.slave_candidates},
          {"not_facing", s.left_out_not_facing},
          {"outside_master", s.left_out_outside},
          {"unprojected", s.left_out_unprojected},
          {"points",
           s.left_out_of_quadrature ? "quadrature points" : "slave points"}};
      summary["n_contact_pairs"]     = s.n_pairs;
      summary["n_contact_unknowns"]  = s.n_unknowns;
      summary["contact_algorithm"]   = contact::to_string(s.algorithm);
      summary["contact_path"]        = contact::to_string(s.path);
      summary["contact_path_reason"] = s.path_reason;
      if (s.estimated_condensed_seconds > 0. || s.estimated_full_seconds > 0.)
        summary["contact_path_estimated_seconds"] = {
          {"condensed", s.estimated_condensed_seconds},
          {"full", s.estimated_full_seconds}};
      summary["contact_path_cost_inputs"] = {
        {"contact_unknowns", s.cost_inputs.contact_unknowns},
        {"face_unknowns", s.cost_inputs.face_unknowns},
        {"factor_entries", s.cost_inputs.factor_entries},
        {"newton_iterations", s.cost_inputs.newton_iterations},
        {"dimension", s.cost_inputs.dimension}};
      const bool full = (s.path == contact::Path::full);
      if (c.full_system_solver != coupled::Solver::mumps && full)
        summary["full_system_solver"] = to_string(c.full_system_solver);
      if (full)
        summary["coupled_matrix_nonzeros"] = s.coupled_nonzeros;
      if (s.algorithm != contact::Algorithm::bde)
        {
          summary["penalty_factor_fkn"] = c.penalty_factor;
          summary["tangential_penalty_factor_fkt"] =
            c.tangential_penalty_factor;
        }
    }
  } // namespace scene
} // namespace igabde
