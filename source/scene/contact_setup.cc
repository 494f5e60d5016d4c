#include <igabde/scene/contact_setup.h>

#include <algorithm>

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
      // The scene numbers bodies 1 ... N; the stage its deformable bodies
      // and its obstacles apart, from 0.
      const std::vector<unsigned int> deformable =
        parameters.deformable_bodies();
      const std::vector<unsigned int> obstacles = parameters.obstacle_bodies();
      const auto position = [](const std::vector<unsigned int> &list,
                               const unsigned int               b) {
        const auto i = std::find(list.begin(), list.end(), b);
        return i == list.end() ? numbers::invalid_unsigned_int :
                                 static_cast<unsigned int>(i - list.begin());
      };
      cs.interactions.clear();
      for (const InteractionParameters &p : c.interactions)
        {
          contact::ContactInteraction ci;
          ci.name                 = p.name;
          ci.slave_body           = position(deformable, p.slave_body - 1);
          ci.master_body          = position(deformable, p.master_body - 1);
          ci.obstacle             = position(obstacles, p.master_body - 1);
          ci.slave_faces          = p.slave_faces;
          ci.master_faces         = p.master_faces;
          ci.pairing              = p.pairing;
          ci.friction_coefficient = p.friction_coefficient;
          ci.search_distance      = p.search_distance;
          cs.interactions.push_back(ci);
        }
      for (const unsigned int b : deformable)
        cs.body_labels.push_back("Body " + std::to_string(b + 1));
      cs.solver.algorithm   = c.algorithm;
      cs.solver.path        = c.path;
      cs.finite_sliding     = c.finite_sliding;
      cs.sliding_tangent    = c.sliding_tangent;
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
      effects["finite_sliding"]           = c.finite_sliding;
      effects["initial_gaps"]             = s.initial_gaps;
      effects["floating_rigid_modes"]     = s.floating_rigid_modes;
      effects["pairs_left_out_supported"] = s.pairs_left_out;
      summary["effects"]                  = effects;
      if (s.left_out_not_facing + s.left_out_outside + s.left_out_unprojected +
            s.left_out_degenerate + s.left_out_beyond >
          0)
        summary["contact_points_left_out"] = {
          {"candidates", s.slave_candidates},
          {"not_facing", s.left_out_not_facing},
          {"outside_master", s.left_out_outside},
          {"unprojected", s.left_out_unprojected},
          {"degenerate_normal", s.left_out_degenerate},
          {"beyond_search_distance", s.left_out_beyond},
          {"points",
           s.left_out_of_quadrature ? "quadrature points" : "slave points"}};
      if (s.n_interactions > 1)
        {
          nlohmann::json list = nlohmann::json::array();
          for (unsigned int k = 0; k < s.n_interactions; ++k)
            {
              const InteractionParameters &p = c.interactions[k];
              list.push_back({{"name", p.name},
                              {"slave_body", p.slave_body},
                              {"master_body", p.master_body},
                              {"friction_coefficient", p.friction_coefficient},
                              {"pairing", contact::to_string(p.pairing)},
                              {"n_pairs", s.interaction_pairs[k]}});
            }
          summary["contact_interactions"] = list;
        }
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
