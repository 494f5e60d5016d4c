#include <igabde/base/files.h>
#include <igabde/base/utilities.h>

#include <igabde/scene/interrupt.h>
#include <igabde/scene/simulator.h>
#include <igabde/scene/size_estimate.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

namespace igabde
{
  namespace scene
  {
    nlohmann::json
    run_scene_in_process(
      const std::string                                      &scene_file,
      const std::vector<std::pair<std::string, std::string>> &overrides,
      std::ostream                                           &log)
    {
      ParameterHandler    prm;
      const AllParameters parameters = parse_scene(prm, scene_file, overrides);
      std::filesystem::create_directories(parameters.output.directory);
      auto run = [&](auto &simulator) {
        simulator.run();
        return simulator.get_summary();
      };
      if (parameters.dimension == 2)
        {
          Simulator<2> simulator(parameters,
                                 scene_file,
                                 parameters.output.directory,
                                 log);
          return run(simulator);
        }
      Simulator<3> simulator(parameters,
                             scene_file,
                             parameters.output.directory,
                             log);
      return run(simulator);
    }



    int
    run_scene(const std::string &scene_file,
              const std::vector<std::pair<std::string, std::string>> &overrides,
              const bool                                              force)
    {
      ParameterHandler prm;
      AllParameters    parameters;
      try
        {
          parameters = parse_scene(prm, scene_file, overrides);
          // Before anything is built: a scene that cannot fit the memory
          // stops at once (the geometry is checked on the way).
          if (force)
            estimate_size(parameters, scene_file);
          else
            check_size(parameters, scene_file, available_memory_bytes());
        }
      catch (const ExceptionBase &e)
        {
          std::cerr << "igabde: error: " << base::exception_message(e)
                    << std::endl;
          return 2;
        }

      const std::string dir = parameters.output.directory;
      std::error_code   ec;
      std::filesystem::create_directories(dir, ec);
      if (ec)
        {
          std::cerr << "igabde: error: " << scene_file
                    << ": Output/Directory = '" << dir
                    << "' cannot be created (" << ec.message()
                    << "); choose a writable folder." << std::endl;
          return 2;
        }
      {
        std::ofstream echo(dir + "/parameters.prm");
        prm.print_parameters(echo, ParameterHandler::PRM);
        std::ofstream echo_json(dir + "/parameters.json");
        prm.print_parameters(echo_json, ParameterHandler::JSON);
      }

      std::ofstream   log_file(dir + "/log.txt");
      base::TeeBuffer tee(std::cout.rdbuf(), log_file.rdbuf());
      std::ostream    log(&tee);
      log << std::setprecision(6);

      auto run = [&](auto &simulator) -> int {
        try
          {
            simulator.run();
            return 0;
          }
        catch (const ExceptionBase &e)
          {
            const std::string message = base::exception_message(e);
            log_file << "igabde: error: " << message << std::endl;
            std::cerr << "igabde: error: " << message << std::endl;
            simulator.write_failed_summary(message);
          }
        catch (const std::exception &e)
          {
            log_file << "igabde: error: " << e.what() << std::endl;
            std::cerr << "igabde: error: " << e.what() << std::endl;
            simulator.write_failed_summary(e.what());
          }
        return 1;
      };

      // SIGINT/SIGTERM: the finished steps stay, summary.json says
      // 'interrupted' and why.
      const InterruptHandler interrupts;
      if (parameters.dimension == 2)
        {
          Simulator<2> simulator(parameters, scene_file, dir, log);
          return run(simulator);
        }
      Simulator<3> simulator(parameters, scene_file, dir, log);
      return run(simulator);
    }
  } // namespace scene
} // namespace igabde
