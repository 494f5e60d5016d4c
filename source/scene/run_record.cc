#include <igabde/scene/run_record.h>

#include <iomanip>
#include <sstream>

namespace igabde
{
  namespace scene
  {
    nlohmann::json
    to_json(const StepRecord &r)
    {
      nlohmann::json j;
      j["step"]                = r.step;
      j["load_factor"]         = r.load_factor;
      j["displacement_factor"] = r.displacement_factor;
      if (!r.history_factors.empty())
        {
          nlohmann::json named;
          for (const auto &[name, factor] : r.history_factors)
            named[name] = factor;
          j["history_factors"] = named;
        }
      if (r.contact)
        {
          j["newton_iterations"] = r.newton_iterations;
          j["contact_solves"]    = r.contact_solves;
          j["step_cuts"]         = r.step_cuts;
          j["residual"]          = r.residual;
          j["n_open"]            = r.n_open;
          j["n_stick"]           = r.n_stick;
          j["n_slip"]            = r.n_slip;
          j["n_closed"]          = r.n_closed;
          if (r.max_penetration)
            j["max_penetration"] = *r.max_penetration;
          if (r.multiplier_updates)
            j["multiplier_updates"] = *r.multiplier_updates;
          j["residual_history"] = r.residual_history;
          if (!r.krylov_iterations.empty())
            j["krylov_iterations"] = r.krylov_iterations;
          if (r.failed)
            {
              j["diagnosis"] = r.diagnosis;
              j["status"]    = "failed";
            }
          if (r.condition_check_max_violation)
            j["condition_check_max_violation"] =
              *r.condition_check_max_violation;
        }
      if (r.finite_strain)
        {
          const NewtonRecord &n = *r.finite_strain;
          j["finite_strain"]    = {{"newton_iterations", n.iterations},
                                   {"newton_solves", n.solves},
                                   {"step_cuts", n.step_cuts},
                                   {"residual", n.residual},
                                   {"residual_history", n.residual_history},
                                   {"min_det_F", n.min_det_F}};
          if (r.failed && !r.contact)
            {
              j["diagnosis"] = r.diagnosis;
              j["status"]    = "failed";
            }
        }
      if (r.total_contact_force)
        j["total_contact_force"] = *r.total_contact_force;
      if (!r.interaction_forces.empty())
        j["interaction_forces"] = r.interaction_forces;
      if (r.largest_strain)
        j["largest_strain"] = *r.largest_strain;
      if (r.largest_sliding)
        j["largest_sliding"] = *r.largest_sliding;
      if (r.largest_normal_turn)
        j["largest_normal_turn"] = *r.largest_normal_turn;
      if (!r.failed)
        {
          nlohmann::json per_body = nlohmann::json::array();
          for (const auto &b : r.bodies)
            {
              nlohmann::json entry{{"name", b.name},
                                   {"contact_force", b.contact_force}};
              if (b.support_reaction)
                entry["support_reaction"] = *b.support_reaction;
              if (b.held_moment)
                entry["held_moment"] = *b.held_moment;
              if (!b.face_motion_reactions.empty())
                {
                  nlohmann::json reactions = nlohmann::json::array();
                  for (const auto &m : b.face_motion_reactions)
                    reactions.push_back({{"face", m.face},
                                         {"force", m.force},
                                         {"moment", m.moment}});
                  entry["face_motion_reactions"] = reactions;
                }
              per_body.push_back(entry);
            }
          j["bodies"] = per_body;
        }
      return j;
    }



    nlohmann::json
    to_json(const RunSummary &s)
    {
      nlohmann::json j    = s.setup;
      j["scene"]          = s.scene;
      j["status"]         = s.status;
      j["dim"]            = s.dim;
      j["discretization"] = s.discretization;
      j["degree"]         = s.degree;
      j["refinements"]    = s.refinements;
      // The seconds below depend on it (doc/performance.md).
      j["memory_allocator"] = s.memory_allocator;
      if (!s.error.empty())
        j["error"] = s.error;
      if (s.size_estimate)
        j["size_estimate"] = *s.size_estimate;
      if (s.n_dofs)
        j["n_dofs"] = *s.n_dofs;
      if (s.n_elements)
        j["n_elements"] = *s.n_elements;
      if (!s.load_steps.empty())
        {
          nlohmann::json steps = nlohmann::json::array();
          for (const auto &r : s.load_steps)
            steps.push_back(to_json(r));
          j["load_steps"] = steps;
        }
      if (s.total_contact_force)
        j["total_contact_force"] = *s.total_contact_force;
      if (s.checks)
        j["checks"] = *s.checks;
      if (!s.warnings.empty())
        j["warnings"] = s.warnings;
      if (s.points)
        j["points"] = *s.points;
      if (s.point_stresses)
        j["point_stresses"] = *s.point_stresses;
      if (s.timing)
        j["timing"] = *s.timing;
      j["output_background_seconds"] = s.output_background_seconds;
      j["mpi_ranks"]                 = s.mpi_ranks;
      if (s.ranks)
        j["ranks"] = *s.ranks;
      return j;
    }



    std::map<std::string, double>
    timing_seconds(const dealii::TimerOutput &timer)
    {
      std::map<std::string, double> timing;
      double                        total = 0.;
      for (const auto &[phase, seconds] :
           timer.get_summary_data(dealii::TimerOutput::total_wall_time))
        {
          timing[phase] = seconds;
          total += seconds;
        }
      timing["total"] = total;
      return timing;
    }



    std::string
    step_table(const std::vector<StepRecord>  &records,
               const std::vector<std::string> &histories,
               const bool                      contact,
               const bool                      finite,
               const unsigned int              dim)
    {
      std::ostringstream csv;
      csv << "step,load_factor,displacement_factor";
      // Named load histories, when the scene has any.
      for (const auto &h : histories)
        csv << "," << h << "_factor";
      if (contact)
        {
          csv << ",status,contact_solves,newton_iterations,residual,n_open,"
                 "n_stick,n_slip,n_closed";
          for (const char *c : {"x", "y", "z"})
            if (static_cast<unsigned int>(c[0] - 'x') < dim)
              csv << ",force_" << c;
        }
      // At finite strain the contact columns, where there are any, count
      // the same Newton iterations.
      if (finite && !contact)
        csv << ",status,newton_iterations,step_cuts,residual";
      if (finite)
        csv << ",min_det_F";
      // The face motions' reactions (Body n/Face motions), named from the
      // first finished step; a failed step has zeros.
      std::vector<std::pair<unsigned int, unsigned int>> reactions;
      for (const auto &r : records)
        if (!r.bodies.empty())
          {
            for (unsigned int b = 0; b < r.bodies.size(); ++b)
              for (unsigned int k = 0;
                   k < r.bodies[b].face_motion_reactions.size();
                   ++k)
                {
                  const auto       &m = r.bodies[b].face_motion_reactions[k];
                  const std::string prefix = ",reaction_" + r.bodies[b].name +
                                             "_face" + std::to_string(m.face);
                  for (unsigned int c = 0; c < dim; ++c)
                    csv << prefix << "_force_" << char('x' + c);
                  for (unsigned int a = (dim == 2 ? 2 : 0); a < 3; ++a)
                    csv << prefix << "_moment_" << char('x' + a);
                  reactions.emplace_back(b, k);
                }
            break;
          }
      csv << "\n" << std::setprecision(12);
      for (const auto &r : records)
        {
          csv << double(r.step) << "," << r.load_factor << ","
              << r.displacement_factor;
          for (const auto &h : histories)
            {
              double factor = 0.;
              for (const auto &[name, f] : r.history_factors)
                if (name == h)
                  factor = f;
              csv << "," << factor;
            }
          if (contact)
            {
              // A step without contact figures has zeros.
              const auto value = [&](const double v) {
                return r.contact ? v : 0.;
              };
              csv << "," << (r.failed ? "failed" : "ok") << ","
                  << value(r.contact_solves) << ","
                  << value(r.newton_iterations) << "," << value(r.residual)
                  << "," << value(r.n_open) << "," << value(r.n_stick) << ","
                  << value(r.n_slip) << "," << value(r.n_closed);
              for (unsigned int c = 0; c < dim; ++c)
                csv << ","
                    << (r.total_contact_force ? (*r.total_contact_force)[c] :
                                                0.);
            }
          if (finite)
            {
              const NewtonRecord n =
                r.finite_strain ? *r.finite_strain : NewtonRecord();
              if (!contact)
                csv << "," << (r.failed ? "failed" : "ok") << ","
                    << n.iterations << "," << n.step_cuts << "," << n.residual;
              csv << "," << n.min_det_F;
            }
          for (const auto &[b, k] : reactions)
            if (b < r.bodies.size() &&
                k < r.bodies[b].face_motion_reactions.size())
              {
                const auto &m = r.bodies[b].face_motion_reactions[k];
                for (const double v : m.force)
                  csv << "," << v;
                for (const double v : m.moment)
                  csv << "," << v;
              }
            else
              for (unsigned int c = 0; c < dim + (dim == 2 ? 1 : 3); ++c)
                csv << ",0";
          csv << "\n";
        }
      return csv.str();
    }
  } // namespace scene
} // namespace igabde
