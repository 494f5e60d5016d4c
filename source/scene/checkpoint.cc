#include <igabde/base/files.h>
#include <igabde/base/utilities.h>

#include <igabde/scene/checkpoint.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /// The format's name and version, the first entry of every file.
      const std::string format = "igabde checkpoint 2";

      std::vector<double>
      to_vector(const Eigen::VectorXd &v)
      {
        return std::vector<double>(v.data(), v.data() + v.size());
      }

      Eigen::VectorXd
      to_eigen(const nlohmann::json &j)
      {
        const std::vector<double> v = j.get<std::vector<double>>();
        Eigen::VectorXd           result(v.size());
        for (std::size_t i = 0; i < v.size(); ++i)
          result[i] = v[i];
        return result;
      }
    } // namespace



    std::string
    checkpoint_file(const std::string &directory, const unsigned int step)
    {
      std::ostringstream name;
      name << directory << "/checkpoint-" << std::setw(4) << std::setfill('0')
           << step << ".json";
      return name.str();
    }



    void
    write_checkpoint(const std::string &directory, const Checkpoint &checkpoint)
    {
      nlohmann::json j;
      j["format"]           = format;
      j["step"]             = checkpoint.step;
      j["factors"]          = checkpoint.factors;
      nlohmann::json bodies = nlohmann::json::array();
      for (const Vector<double> &u : checkpoint.finite_state)
        bodies.push_back(std::vector<double>(u.begin(), u.end()));
      j["finite_state"] = bodies;
      if (checkpoint.contact)
        j["contact"] = *checkpoint.contact;
      nlohmann::json records = nlohmann::json::array();
      for (const StepRecord &record : checkpoint.records)
        records.push_back(to_json(record));
      j["records"]    = records;
      j["warnings"]   = checkpoint.warnings;
      j["parameters"] = checkpoint.parameters;
      base::write_file_atomically(checkpoint_file(directory, checkpoint.step),
                                  j.dump() + "\n");
    }



    Checkpoint
    read_checkpoint(const std::string &directory)
    {
      // The newest: the highest step number among the folder's files.
      unsigned int    newest = 0;
      std::error_code ec;
      for (const auto &entry :
           std::filesystem::directory_iterator(directory, ec))
        {
          const std::string name = entry.path().filename().string();
          if (name.rfind("checkpoint-", 0) == 0 && name.size() == 20 &&
              name.substr(15) == ".json")
            {
              try
                {
                  newest =
                    std::max<unsigned int>(newest,
                                           std::stoul(name.substr(11, 4)));
                }
              catch (const std::exception &)
                {}
            }
        }
      AssertThrow(!ec && newest > 0,
                  base::ExcInput(
                    "--restart " + directory +
                    ": the folder holds no checkpoint-NNNN.json; run the "
                    "scene with Output/Checkpoint = true first (each "
                    "finished step writes one)."));
      const std::string file = checkpoint_file(directory, newest);
      std::ifstream     in(file);
      nlohmann::json    j = nlohmann::json::parse(in, nullptr, false);
      AssertThrow(!j.is_discarded() && j.value("format", "") == format,
                  base::ExcInput("--restart " + directory + ": " + file +
                                 " is not an igabde checkpoint (expected '" +
                                 format + "')."));
      Checkpoint checkpoint;
      checkpoint.step    = j.at("step").get<unsigned int>();
      checkpoint.factors = j.at("factors").get<std::vector<double>>();
      for (const auto &u : j.at("finite_state"))
        {
          const std::vector<double> v = u.get<std::vector<double>>();
          checkpoint.finite_state.emplace_back(v.begin(), v.end());
        }
      if (j.contains("contact"))
        checkpoint.contact = j.at("contact");
      for (const auto &record : j.at("records"))
        checkpoint.records.push_back(step_record_from_json(record));
      checkpoint.warnings   = j.at("warnings").get<std::vector<std::string>>();
      checkpoint.parameters = j.at("parameters");
      return checkpoint;
    }



    nlohmann::json
    scene_parameters_of(const std::string &text)
    {
      nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
      if (j.is_discarded())
        return nlohmann::json::object();
      j.erase("Output");
      return j;
    }



    nlohmann::json
    scene_parameters(const std::string &directory)
    {
      std::ifstream      in(directory + "/parameters.json");
      std::ostringstream text;
      text << in.rdbuf();
      return scene_parameters_of(text.str());
    }



    void
    check_restart(const std::string &directory, const nlohmann::json &scene)
    {
      const Checkpoint     checkpoint = read_checkpoint(directory);
      const nlohmann::json difference =
        nlohmann::json::diff(checkpoint.parameters, scene);
      // The parameter as a scene names it: '/Contact/Friction
      // coefficient/value' is Contact/Friction coefficient.
      std::string parameter = difference.empty() ?
                                std::string() :
                                difference.front().value("path", std::string());
      if (!parameter.empty() && parameter.front() == '/')
        parameter.erase(0, 1);
      const std::string value = "/value";
      if (parameter.size() > value.size() &&
          parameter.compare(parameter.size() - value.size(),
                            value.size(),
                            value) == 0)
        parameter.resize(parameter.size() - value.size());
      AssertThrow(difference.empty(),
                  base::ExcInput(
                    "--restart " + directory + ": " +
                    checkpoint_file(directory, checkpoint.step) +
                    " was written by another scene (" + parameter +
                    " differs); restart with the scene that wrote it (only "
                    "Output may change)."));
    }



    template <int dim>
    nlohmann::json
    contact_state_to_json(const contact::ContactStage<dim> &stage)
    {
      const typename contact::ContactStage<dim>::State state =
        stage.save_state();
      std::vector<int> status;
      for (const contact::ContactStatus s : state.status)
        status.push_back(static_cast<int>(s));
      nlohmann::json finite_u = nlohmann::json::array();
      for (const Vector<double> &u : state.finite_u)
        finite_u.push_back(std::vector<double>(u.begin(), u.end()));
      // Finite sliding: the configuration the next step pairs on, the
      // factors that place the moving obstacles there, and which pairs the
      // forces belong to.
      nlohmann::json sliding_u = nlohmann::json::array();
      for (const Vector<double> &u : state.sliding_u)
        sliding_u.push_back(std::vector<double>(u.begin(), u.end()));
      nlohmann::json keys = nlohmann::json::array();
      for (const auto &[interaction, key] : state.keys)
        keys.push_back({interaction, key});
      return {{"p", to_vector(state.x.p)},
              {"finite_u", finite_u},
              {"sliding_u", sliding_u},
              {"sliding_keys", keys},
              {"sliding_factors", state.sliding_factors},
              {"alpha", to_vector(state.x.alpha)},
              {"w", to_vector(state.x.w)},
              {"u_rel", to_vector(state.u_rel)},
              {"previous_external", to_vector(state.previous_external)},
              {"status", status},
              {"has_previous", state.has_previous}};
    }



    template <int dim>
    void
    restore_contact_state(contact::ContactStage<dim> &stage,
                          const nlohmann::json       &j)
    {
      typename contact::ContactStage<dim>::State state;
      state.x.p               = to_eigen(j.at("p"));
      state.x.alpha           = to_eigen(j.at("alpha"));
      state.x.w               = to_eigen(j.at("w"));
      state.u_rel             = to_eigen(j.at("u_rel"));
      state.previous_external = to_eigen(j.at("previous_external"));
      for (const int s : j.at("status").get<std::vector<int>>())
        state.status.push_back(static_cast<contact::ContactStatus>(s));
      state.has_previous = j.at("has_previous").get<bool>();
      for (const auto &u : j.at("finite_u"))
        {
          const std::vector<double> v = u.get<std::vector<double>>();
          state.finite_u.emplace_back(v.begin(), v.end());
        }
      if (j.contains("sliding_u"))
        {
          for (const auto &u : j.at("sliding_u"))
            {
              const std::vector<double> v = u.get<std::vector<double>>();
              state.sliding_u.emplace_back(v.begin(), v.end());
            }
          for (const auto &k : j.at("sliding_keys"))
            state.keys.emplace_back(k.at(0).get<unsigned int>(),
                                    k.at(1).get<types::global_dof_index>());
          state.sliding_factors =
            j.at("sliding_factors").get<std::vector<double>>();
        }
      stage.restore_state(state);
    }



    StepRecord
    step_record_from_json(const nlohmann::json &j)
    {
      const auto numbers = [](const nlohmann::json &v) {
        return v.get<std::vector<double>>();
      };
      StepRecord r;
      r.step                = j.at("step").get<unsigned int>();
      r.load_factor         = j.at("load_factor").get<double>();
      r.displacement_factor = j.at("displacement_factor").get<double>();
      if (j.contains("history_factors"))
        for (const auto &[name, factor] : j.at("history_factors").items())
          r.history_factors.emplace_back(name, factor.get<double>());
      r.contact = j.contains("contact_solves");
      if (r.contact)
        {
          r.newton_iterations = j.at("newton_iterations").get<unsigned int>();
          r.contact_solves    = j.at("contact_solves").get<unsigned int>();
          r.step_cuts         = j.at("step_cuts").get<unsigned int>();
          r.residual          = j.at("residual").get<double>();
          r.n_open            = j.at("n_open").get<unsigned int>();
          r.n_stick           = j.at("n_stick").get<unsigned int>();
          r.n_slip            = j.at("n_slip").get<unsigned int>();
          r.n_closed          = j.at("n_closed").get<unsigned int>();
          if (j.contains("max_penetration"))
            r.max_penetration = j.at("max_penetration").get<double>();
          if (j.contains("multiplier_updates"))
            r.multiplier_updates =
              j.at("multiplier_updates").get<unsigned int>();
          r.residual_history = numbers(j.at("residual_history"));
          if (j.contains("krylov_iterations"))
            r.krylov_iterations =
              j.at("krylov_iterations").get<std::vector<unsigned int>>();
          if (j.contains("condition_check_max_violation"))
            r.condition_check_max_violation =
              j.at("condition_check_max_violation").get<double>();
        }
      if (j.contains("finite_strain"))
        {
          const auto  &n = j.at("finite_strain");
          NewtonRecord newton;
          newton.iterations       = n.at("newton_iterations");
          newton.solves           = n.at("newton_solves");
          newton.step_cuts        = n.at("step_cuts");
          newton.residual         = n.at("residual");
          newton.residual_history = numbers(n.at("residual_history"));
          newton.min_det_F        = n.at("min_det_F");
          r.finite_strain         = newton;
        }
      r.failed = j.value("status", "") == "failed";
      if (r.failed)
        r.diagnosis = j.value("diagnosis", "");
      if (j.contains("total_contact_force"))
        r.total_contact_force = numbers(j.at("total_contact_force"));
      if (j.contains("interaction_forces"))
        for (const auto &f : j.at("interaction_forces"))
          r.interaction_forces.push_back(numbers(f));
      if (j.contains("largest_strain"))
        r.largest_strain = j.at("largest_strain").get<double>();
      if (j.contains("largest_sliding"))
        r.largest_sliding = j.at("largest_sliding").get<double>();
      if (j.contains("largest_normal_turn"))
        r.largest_normal_turn = j.at("largest_normal_turn").get<double>();
      if (j.contains("bodies"))
        for (const auto &b : j.at("bodies"))
          {
            BodyForceRecord forces;
            forces.name          = b.at("name");
            forces.contact_force = numbers(b.at("contact_force"));
            if (b.contains("support_reaction"))
              forces.support_reaction = numbers(b.at("support_reaction"));
            if (b.contains("held_moment"))
              forces.held_moment = numbers(b.at("held_moment"));
            if (b.contains("face_motion_reactions"))
              for (const auto &m : b.at("face_motion_reactions"))
                forces.face_motion_reactions.push_back(
                  {m.at("face").get<unsigned int>(),
                   numbers(m.at("force")),
                   numbers(m.at("moment"))});
            r.bodies.push_back(forces);
          }
      return r;
    }



    template nlohmann::json
    contact_state_to_json(const contact::ContactStage<2> &);
    template nlohmann::json
    contact_state_to_json(const contact::ContactStage<3> &);
    template void
    restore_contact_state(contact::ContactStage<2> &, const nlohmann::json &);
    template void
    restore_contact_state(contact::ContactStage<3> &, const nlohmann::json &);
  } // namespace scene
} // namespace igabde
