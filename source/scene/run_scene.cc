#include <igabde/base/files.h>
#include <igabde/base/utilities.h>

#include <igabde/scene/checkpoint.h>
#include <igabde/scene/interrupt.h>
#include <igabde/scene/simulator.h>
#include <igabde/scene/size_estimate.h>

#include <deal.II/base/mpi.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /**
       * A scene that cannot be read leaves no older run's "ok" in the output
       * folder it names (--set Output/Directory or its Output section):
       * when that folder exists, its summary.json gets status "failed" and
       * @p message. Nothing is created.
       */
      void
      mark_failed_read(
        ParameterHandler                                       &prm,
        const std::string                                      &scene_file,
        const std::vector<std::pair<std::string, std::string>> &overrides,
        const std::string                                      &message)
      {
        // The values read so far, whichever subsection the reader stopped
        // in.
        std::string        directory, name, line;
        std::ostringstream listing;
        prm.print_parameters(listing, ParameterHandler::ShortPRM);
        std::istringstream       in(listing.str());
        std::vector<std::string> sections;
        while (std::getline(in, line))
          {
            line = base::trim(line);
            if (line.rfind("subsection ", 0) == 0)
              sections.push_back(base::trim(line.substr(11)));
            else if (line == "end" && !sections.empty())
              sections.pop_back();
            else if (line.rfind("set ", 0) == 0 &&
                     line.find('=') != std::string::npos)
              {
                const std::string key =
                  base::trim(line.substr(4, line.find('=') - 4));
                const std::string value =
                  base::trim(line.substr(line.find('=') + 1));
                if (sections.empty() && key == "Scene name")
                  name = value;
                else if (sections == std::vector<std::string>{"Output"} &&
                         key == "Directory")
                  directory = value;
              }
          }
        for (const auto &[path, value] : overrides)
          if (path == "Output/Directory")
            directory = base::trim(value);
        std::error_code ec;
        if (directory.empty() || !std::filesystem::is_directory(directory, ec))
          return;
        if (name.empty())
          name = std::filesystem::path(scene_file).stem();
        const nlohmann::json summary = {{"scene", name},
                                        {"status", "failed"},
                                        {"error", message}};
        try
          {
            base::write_file_atomically(directory + "/summary.json",
                                        summary.dump(2) + "\n");
          }
        catch (...)
          {}
      }
    } // namespace



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
      // Under mpirun every rank runs this: rank 0 writes the files and
      // reports input errors (every rank finds the same and ends with
      // status 2); an error during the run is reported by the rank that
      // meets it, and ends all ranks.
      const unsigned int rank =
        Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
      const unsigned int n_ranks =
        Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
      const bool       root = (rank == 0);
      std::ostream     silent(nullptr);
      std::ostream    &err = root ? std::cerr : silent;
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
          const std::string message = base::exception_message(e);
          err << "igabde: error: " << message << std::endl;
          if (root)
            mark_failed_read(prm, scene_file, overrides, message);
          return 2;
        }

      const std::string dir = parameters.output.directory;
      std::error_code   ec;
      if (root)
        std::filesystem::create_directories(dir, ec);
      if (Utilities::MPI::max(ec ? 1u : 0u, MPI_COMM_WORLD) > 0)
        {
          err << "igabde: error: " << scene_file << ": Output/Directory = '"
              << dir << "' cannot be created (" << ec.message()
              << "); choose a writable folder." << std::endl;
          return 2;
        }
      // A restart continues the scene that wrote the folder's checkpoint:
      // refused now, before the folder's files are touched.
      if (parameters.output.restart)
        try
          {
            std::ostringstream text;
            prm.print_parameters(text, ParameterHandler::JSON);
            check_restart(dir, scene_parameters_of(text.str()));
          }
        catch (const ExceptionBase &e)
          {
            err << "igabde: error: " << base::exception_message(e) << std::endl;
            return 2;
          }
      if (root)
        {
          std::ofstream echo(dir + "/parameters.prm");
          prm.print_parameters(echo, ParameterHandler::PRM);
          std::ofstream echo_json(dir + "/parameters.json");
          prm.print_parameters(echo_json, ParameterHandler::JSON);
        }

      std::ofstream log_file;
      if (root)
        log_file.open(dir + "/log.txt");
      // With --quiet the screen gets the warnings and errors only.
      base::WarningLines warnings_only(std::cout.rdbuf());
      base::TeeBuffer    tee(parameters.output.quiet ? &warnings_only :
                                                    std::cout.rdbuf(),
                          log_file.rdbuf());
      std::ostream log(&tee);
      log << std::setprecision(6);

      // The failing rank's message; with several ranks, the others are
      // ended at once (they may wait for it in a collective call).
      const auto fail =
        [&](auto &simulator, const std::string &message, const int status) {
          const std::string line =
            "igabde: error: " +
            (n_ranks > 1 ? "[rank " + std::to_string(rank) + " of " +
                             std::to_string(n_ranks) + "] " :
                           std::string()) +
            message;
          if (root)
            log_file << line << std::endl;
          std::cerr << line << std::endl;
          simulator.write_failed_summary(message);
          if (n_ranks > 1)
            MPI_Abort(MPI_COMM_WORLD, status);
          return status;
        };
      auto run = [&](auto &simulator) -> int {
        try
          {
            simulator.run();
            return 0;
          }
        // A scene that reads but cannot be set up (faces that do not face
        // each other, a load nothing can balance) is an input error too.
        catch (const base::ExcInput &e)
          {
            // Named by the scene file like the reader's errors, also when
            // found while the bodies are built.
            std::string message = base::exception_message(e);
            if (message.rfind(scene_file, 0) != 0)
              message = scene_file + ": " + message;
            return fail(simulator, message, 2);
          }
        catch (const ExceptionBase &e)
          {
            return fail(simulator, base::exception_message(e), 1);
          }
        catch (const std::exception &e)
          {
            return fail(simulator, e.what(), 1);
          }
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
