#include <igabde/base/files.h>
#include <igabde/base/utilities.h>

#include <igabde/contact/bnewton.h>
#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_law.h>
#include <igabde/contact/fclib_reader.h>

#include <igabde/scene/parameters.h>
#include <igabde/scene/run_fclib.h>
#include <igabde/scene/scene_reader.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      using Clock = std::chrono::steady_clock;

      double
      seconds_since(const Clock::time_point start)
      {
        return std::chrono::duration<double>(Clock::now() - start).count();
      }

      /// What --fclib reads of the parameters.
      struct FclibRunSettings
      {
        double       tolerance      = 1e-8;
        unsigned int max_iterations = 300;
        double       r_scale        = 1.;
        bool         verbose        = false;
        bool         progress       = true;
        bool         quiet          = false;
        std::string  directory;
      };

      FclibRunSettings
      read_settings(
        const std::string                                      &file,
        const std::vector<std::pair<std::string, std::string>> &overrides)
      {
        const std::set<std::string> read = {"Contact/Tolerance",
                                            "Contact/Max iterations",
                                            "Contact/r scale",
                                            "Contact/Verbose",
                                            "Output/Directory",
                                            "Output/Progress",
                                            "Output/Quiet"};
        ParameterHandler            prm;
        AllParameters::declare_parameters(prm);
        std::set<std::string> given;
        for (const auto &[path, value] : overrides)
          {
            AssertThrow(read.count(path) > 0,
                        base::ExcInput(
                          "--set " + path +
                          ": not a parameter of an FCLIB problem, which "
                          "has no bodies, mesh or load path; --fclib reads "
                          "Contact/Tolerance, Contact/Max iterations, "
                          "Contact/r scale, Contact/Verbose, "
                          "Output/Directory, Output/Progress and "
                          "Output/Quiet."));
            apply_override(prm, path, value);
            given.insert(path);
          }
        FclibRunSettings s;
        prm.enter_subsection("Contact");
        if (given.count("Contact/Tolerance"))
          s.tolerance = prm.get_double("Tolerance");
        if (given.count("Contact/Max iterations"))
          s.max_iterations = prm.get_integer("Max iterations");
        s.r_scale = prm.get_double("r scale");
        s.verbose = prm.get_bool("Verbose");
        prm.leave_subsection();
        prm.enter_subsection("Output");
        s.directory = base::trim(prm.get("Directory"));
        s.progress  = prm.get_bool("Progress");
        s.quiet     = prm.get_bool("Quiet");
        prm.leave_subsection();
        if (s.directory.empty())
          s.directory = "output/" + std::filesystem::path(file).stem().string();
        AssertThrow(s.tolerance > 0.,
                    base::ExcInput("--set Contact/Tolerance must be > 0 (the "
                                   "FCLIB error at which the solve stops, "
                                   "e.g. 1e-8)."));
        AssertThrow(s.max_iterations > 0,
                    base::ExcInput("--set Contact/Max iterations must be at "
                                   "least 1."));
        AssertThrow(s.r_scale > 0.,
                    base::ExcInput("--set Contact/r scale must be > 0."));
        return s;
      }

      /// The problem, or an input error naming the file.
      contact::ContactProblem
      read_problem(const std::string &file, std::string &kind)
      {
        AssertThrow(std::filesystem::is_regular_file(file),
                    base::ExcInput(file + ": no such file; give an FCLIB "
                                          "HDF5 problem (.hdf5) or a Siconos "
                                          "numerics .dat problem."));
        switch (contact::classify_fclib_file(file))
          {
            case contact::FclibFileKind::hdf5_local:
              kind = "fclib local";
              break;
            case contact::FclibFileKind::hdf5_global:
              kind = "fclib global";
              break;
            case contact::FclibFileKind::siconos_local_dat:
              kind = "siconos local";
              break;
            case contact::FclibFileKind::hdf5_global_rolling:
              AssertThrow(false,
                          base::ExcInput(file +
                                         ": a global problem with rolling "
                                         "friction, which igabde does not "
                                         "model; give a local or global "
                                         "Coulomb problem."));
              break;
            case contact::FclibFileKind::siconos_global_dat:
              kind = "siconos global";
              break;
            default:
              AssertThrow(false,
                          base::ExcInput(
                            file + ": neither an FCLIB HDF5 problem "
                                   "(fclib_local or fclib_global group) nor "
                                   "a Siconos numerics .dat problem."));
          }
        try
          {
            contact::ContactProblem problem = contact::read_fclib_problem(file);
            problem.check_consistency();
            return problem;
          }
        catch (const ExceptionBase &e)
          {
            throw base::ExcInput(base::exception_message(e));
          }
      }

      std::string
      rounded(const double x, const int digits = 3)
      {
        std::ostringstream s;
        s << std::setprecision(digits) << x;
        return s.str();
      }
    } // namespace



    int
    run_fclib(const std::string                                      &file,
              const std::vector<std::pair<std::string, std::string>> &overrides)
    {
      const auto   start = Clock::now();
      const bool   root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
      std::ostream silent(nullptr);
      std::ostream &err = root ? std::cerr : silent;

      FclibRunSettings        settings;
      contact::ContactProblem problem;
      std::string             kind;
      double                  read_seconds = 0.;
      try
        {
          settings             = read_settings(file, overrides);
          const auto read_from = Clock::now();
          problem              = read_problem(file, kind);
          read_seconds         = seconds_since(read_from);
        }
      catch (const ExceptionBase &e)
        {
          err << "igabde: error: " << base::exception_message(e) << std::endl;
          return 2;
        }

      const std::string &dir = settings.directory;
      std::error_code    ec;
      if (root)
        std::filesystem::create_directories(dir, ec);
      if (ec)
        {
          err << "igabde: error: " << file << ": Output/Directory = '" << dir
              << "' cannot be created (" << ec.message()
              << "); choose a writable folder." << std::endl;
          return 2;
        }
      std::ofstream log_file;
      if (root)
        log_file.open(dir + "/log.txt");
      // Rank 0 prints and logs; the other ranks' log discards.
      base::WarningLines warnings_only(std::cout.rdbuf());
      base::TeeBuffer tee(settings.quiet ? &warnings_only : std::cout.rdbuf(),
                          log_file.rdbuf());
      std::ostream log(root ? static_cast<std::streambuf *>(&tee) : nullptr);

      nlohmann::json summary;
      summary["mode"]    = "fclib";
      summary["problem"] = file;
      summary["kind"]    = kind;
      summary["status"]  = "running";
      if (root)
        base::write_file_atomically(dir + "/summary.json",
                                    summary.dump(2) + "\n");

      const unsigned int d      = problem.n_components;
      double             mu_min = 0., mu_max = 0.;
      if (!problem.mu.empty())
        {
          mu_min = *std::min_element(problem.mu.begin(), problem.mu.end());
          mu_max = *std::max_element(problem.mu.begin(), problem.mu.end());
        }
      log << "FCLIB problem " << file << " (" << kind << "): " << d
          << " components per contact, " << problem.n_contacts << " contacts, "
          << problem.n_rows() << " rows, mu " << rounded(mu_min)
          << (mu_max > mu_min ? "-" + rounded(mu_max) : "") << std::endl;

      contact::BNewtonSolver::Settings solver_settings;
      solver_settings.tolerance      = settings.tolerance;
      solver_settings.max_iterations = settings.max_iterations;
      solver_settings.fclib_stopping = true;
      solver_settings.r_factor       = settings.r_scale;
      solver_settings.log            = settings.verbose;
      solver_settings.log_stream     = &log;
      // A solve that takes more than a second says how it goes, once a
      // second.
      const auto solve_from = Clock::now();
      auto       last_line  = solve_from;
      if (settings.progress)
        solver_settings.on_iteration = [&](const unsigned int it,
                                           const double       residual) {
          const auto now = Clock::now();
          if (now - last_line >= std::chrono::seconds(1))
            {
              last_line = now;
              log << "  [progress] B-Newton iteration " << it
                  << ", FCLIB error " << std::scientific << std::setprecision(2)
                  << residual << std::defaultfloat << std::setprecision(6)
                  << std::endl;
            }
        };
      const contact::BNewtonSolver         solver(solver_settings);
      const contact::BNewtonSolver::Result result = solver.solve(problem);
      const double solve_seconds                  = seconds_since(solve_from);

      const auto   output_from = Clock::now();
      const double error =
        contact::relative_natural_map_error(problem, result.p, result.u);
      const bool solved = result.p.allFinite() && error <= settings.tolerance;
      const contact::ConditionReport conditions =
        contact::check_contact_conditions(problem, result.p, result.u);

      log << "  B-Newton: " << (solved ? "solved" : "not solved") << " after "
          << result.iterations << " iterations"
          << (result.sweeps > 0 ? " and " + std::to_string(result.sweeps) +
                                    " Gauss-Seidel sweeps" :
                                  std::string())
          << ", FCLIB error " << std::scientific << std::setprecision(4)
          << error << " (balanced " << result.balanced_residual << ")"
          << std::defaultfloat << std::setprecision(6)
          << ", open/stick/slip/closed " << result.n_open << "/"
          << result.n_stick << "/" << result.n_slip << "/" << result.n_closed
          << (solved ? std::string() : ": " + result.diagnosis) << std::endl;

      summary["status"]           = solved ? "ok" : "failed";
      summary["n_components"]     = d;
      summary["n_contacts"]       = problem.n_contacts;
      summary["n_rows"]           = problem.n_rows();
      summary["mu"]               = {mu_min, mu_max};
      summary["tolerance"]        = settings.tolerance;
      summary["max_iterations"]   = settings.max_iterations;
      summary["iterations"]       = result.iterations;
      summary["sweeps"]           = result.sweeps;
      summary["n_open"]           = result.n_open;
      summary["n_stick"]          = result.n_stick;
      summary["n_slip"]           = result.n_slip;
      summary["n_closed"]         = result.n_closed;
      summary["diagnosis"]        = solved ? "" : result.diagnosis;
      summary["residual_history"] = nlohmann::json::array();
      for (const auto &record : result.history)
        summary["residual_history"].push_back(record.residual);
      nlohmann::json checks;
      checks["fclib_error"]       = error;
      checks["balanced_error"]    = result.balanced_residual;
      checks["conditions_passed"] = conditions.passed();
      double worst                = 0.;
      for (const auto &condition : conditions.conditions)
        worst = std::max(worst, condition.max_violation);
      checks["conditions_max_violation"] = worst;
      const contact::FclibSolution reference =
        kind.rfind("siconos", 0) == 0 ? contact::FclibSolution() :
                                        contact::read_fclib_solution(file);
      if (reference.available && reference.r.size() == result.p.size())
        {
          const double r_norm = reference.r.norm();
          checks["reference_relative_difference"] =
            (result.p - reference.r).norm() / (r_norm > 0. ? r_norm : 1.);
          checks["reference_fclib_error"] =
            contact::relative_natural_map_error(problem,
                                                reference.r,
                                                problem.relative_displacement(
                                                  reference.r));
          log << "  the file's reference solution: |r - r_ref| / |r_ref| = "
              << rounded(checks["reference_relative_difference"].get<double>())
              << ", its FCLIB error "
              << rounded(checks["reference_fclib_error"].get<double>())
              << std::endl;
        }
      summary["checks"] = checks;

      if (root)
        {
          std::ostringstream csv;
          csv << "contact,status,r_n";
          for (unsigned int c = 1; c < d; ++c)
            csv << ",r_t" << c;
          csv << ",u_n";
          for (unsigned int c = 1; c < d; ++c)
            csv << ",u_t" << c;
          csv << "\n" << std::setprecision(17);
          for (unsigned int i = 0; i < problem.n_contacts; ++i)
            {
              csv << i << ","
                  << (i < result.status.size() ?
                        contact::to_string(result.status[i]) :
                        std::string("unknown"));
              for (unsigned int c = 0; c < d; ++c)
                csv << "," << result.p[d * i + c];
              for (unsigned int c = 0; c < d; ++c)
                csv << "," << result.u[d * i + c];
              csv << "\n";
            }
          base::open_for_writing(dir + "/solution.csv") << csv.str();
        }
      summary["timing"] = {{"read", read_seconds},
                           {"contact: B-Newton", solve_seconds},
                           {"output", seconds_since(output_from)},
                           {"total", seconds_since(start)}};
      if (root)
        base::write_file_atomically(dir + "/summary.json",
                                    summary.dump(2) + "\n");
      if (!solved)
        {
          err << "igabde: error: " << file << ": not solved to the FCLIB error "
              << rounded(settings.tolerance) << " (reached " << rounded(error)
              << " after " << result.iterations
              << " iterations): " << result.diagnosis
              << ". Try a larger Contact/Max iterations, or a looser "
                 "Contact/Tolerance."
              << std::endl;
          return 1;
        }
      return 0;
    }
  } // namespace scene
} // namespace igabde
