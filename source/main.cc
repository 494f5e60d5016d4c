// igabde: elastic frictional contact of two bodies by isogeometric analysis
// and B-differentiable equations. Thin driver: parse the command line and
// hand the scene to the simulator.

#include <igabde/base/utilities.h>

#include <igabde/scene/parameters.h>
#include <igabde/scene/run_fclib.h>
#include <igabde/scene/simulator.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <iostream>
#include <string>
#include <tbb/global_control.h>
#include <utility>
#include <vector>

#ifdef IGABDE_SANITIZE
// OpenMPI's dynamically loaded components leak at MPI_Finalize from frames
// LeakSanitizer cannot name (unloaded modules), so no suppression file can
// match them: leak checking is off in sanitizer builds; AddressSanitizer's
// memory-error checks and UBSan stay on.
extern "C" const char *
__asan_default_options()
{
  return "detect_leaks=0";
}
#endif



namespace
{
  void
  print_usage(std::ostream &out)
  {
    out
      << "Usage: igabde SCENE.prm [--quiet] [--force] [--export-geometry] "
         "[--restart FOLDER] [--set \"Section/Name=value\"]...\n"
         "       igabde --fclib PROBLEM [--quiet] [--set "
         "\"Section/Name=value\"]...\n"
         "       igabde --print-parameters [prm|json]\n"
         "       igabde --help\n\n"
         "Runs the scene SCENE.prm and writes summary.json, tables, the "
         "log and\nVTU/PVD fields into its output folder (Output/Directory, "
         "default\noutput/<scene name>/). --set overrides any parameter "
         "(repeatable).\n--quiet prints only warnings and errors on screen; log.txt "
         "keeps\nevery line (Output/Quiet = true, Output/Progress = false).\n--export-geometry also writes each body's refined geometry as "
         "a G+Smo\nXML file and its control net as VTU (Output/Export "
         "geometry = true).\n--force runs a scene whose size estimate exceeds the free "
         "memory\n(without it, such a scene stops at once with the estimate); "
         "IGABDE_MEMORY_LIMIT=GiB\nin the environment caps the memory the "
         "estimate is held against.\n"
         "SIGINT or SIGTERM ends a run with the finished load steps written "
         "and\nsummary.json marked 'interrupted'.\n"
         "--restart FOLDER continues the load path of the run whose output "
         "folder is\nFOLDER from its newest checkpoint (a run with "
         "Output/Checkpoint = true\nwrites one per finished step); the "
         "scene must be the same, Output aside.\n"
         "--fclib solves an FCLIB problem (.hdf5, local or global) or a "
         "Siconos\nnumerics .dat local or global problem with the contact solver and "
         "writes\nsummary.json (checks.fclib_error) and solution.csv "
         "(Output/Directory,\ndefault output/<problem name>/; --set "
         "Contact/Tolerance, default 1e-8,\nContact/Max iterations, default "
         "300).\n"
         "Scenes live in prm/; doc/ explains every study.\n";
  }
} // namespace



int
main(int argc, char **argv)
{
  using namespace dealii;
  // The background output jobs run on TBB's worker threads, whose stacks
  // are 4 MiB by default; OpenBLAS' parallel LU (dgetrf, through the dense
  // LU of a face's Greville collocation) recurses with about 0.5 MiB of
  // stack per level and overflowed them on an 800-span face. The workers get
  // twice the main thread's 8 MiB (address space; pages are touched only
  // when used).
  const tbb::global_control worker_stack(tbb::global_control::thread_stack_size,
                                         std::size_t(16) << 20);
  const igabde::base::LightMpiSingleton light_mpi_singleton;
  // The node's cores for the task-based parts (WorkStream assembly, the
  // parallel multi-RHS solves), divided among the ranks under mpirun; the
  // dense linear algebra gets the same share.
  Utilities::MPI::MPI_InitFinalize mpi(argc,
                                       argv,
                                       numbers::invalid_unsigned_int);
  igabde::base::limit_dense_threads_per_rank();
  // deal.II would print a stack trace for every user error; user errors are
  // reported in one line instead.
  deal_II_exceptions::disable_abort_on_exception();
  deal_II_exceptions::suppress_stacktrace_in_exceptions();
  // Under mpirun every rank reads the same command line and refuses it
  // alike: rank 0 says why, once, and every rank ends with status 2.
  std::ostream  silent(nullptr);
  std::ostream &err =
    Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0 ? std::cerr : silent;

  std::string                                      scene_file;
  std::vector<std::pair<std::string, std::string>> overrides;
  bool                                             force = false;
  std::string                                      fclib_file;
  for (int i = 1; i < argc; ++i)
    {
      const std::string arg = argv[i];
      if (arg == "--help" || arg == "-h")
        {
          print_usage(std::cout);
          return 0;
        }
      else if (arg == "--print-parameters")
        {
          std::string format = "prm";
          if (i + 1 < argc && argv[i + 1][0] != '-')
            format = argv[++i];
          if (format != "prm" && format != "json")
            {
              err << "igabde: error: --print-parameters takes 'prm' or "
                     "'json', got '"
                  << format << "'." << std::endl;
              return 2;
            }
          ParameterHandler prm;
          igabde::scene::AllParameters::declare_parameters(prm);
          prm.print_parameters(std::cout,
                               format == "json" ? ParameterHandler::JSON :
                                                  ParameterHandler::PRM);
          return 0;
        }
      else if (arg == "--fclib")
        {
          if (i + 1 >= argc)
            {
              err << "igabde: error: --fclib needs a problem file (.hdf5 "
                     "or .dat)."
                  << std::endl;
              return 2;
            }
          fclib_file = argv[++i];
        }
      else if (arg == "--force")
        force = true;
      else if (arg == "--restart")
        {
          if (i + 1 >= argc)
            {
              err << "igabde: error: --restart needs the output folder of "
                     "the run to continue, e.g. --restart output/f1-elastica"
                  << std::endl;
              return 2;
            }
          overrides.emplace_back("Output/Directory", argv[++i]);
          overrides.emplace_back("Output/Restart", "true");
        }
      else if (arg == "--quiet" || arg == "-q")
        {
          overrides.emplace_back("Output/Progress", "false");
          overrides.emplace_back("Output/Quiet", "true");
        }
      else if (arg == "--export-geometry")
        overrides.emplace_back("Output/Export geometry", "true");
      else if (arg == "--set")
        {
          if (i + 1 >= argc)
            {
              err << "igabde: error: --set needs "
                     "\"Section/Name=value\"."
                  << std::endl;
              return 2;
            }
          const std::string assignment = argv[++i];
          const auto        eq         = assignment.find('=');
          if (eq == std::string::npos)
            {
              err << "igabde: error: --set '" << assignment
                  << "' is not of the form \"Section/Name=value\"."
                  << std::endl;
              return 2;
            }
          overrides.emplace_back(igabde::base::trim(assignment.substr(0, eq)),
                                 igabde::base::trim(assignment.substr(eq + 1)));
        }
      else if (!arg.empty() && arg[0] == '-')
        {
          err << "igabde: error: unknown option '" << arg
              << "'; see igabde --help." << std::endl;
          return 2;
        }
      else if (scene_file.empty())
        scene_file = arg;
      else
        {
          err << "igabde: error: more than one scene file ('" << scene_file
              << "', '" << arg << "'); run one scene at a time." << std::endl;
          return 2;
        }
    }
  if (!fclib_file.empty())
    {
      if (!scene_file.empty() || force)
        {
          err << "igabde: error: --fclib solves a problem file without a "
                 "scene; leave out '"
              << (scene_file.empty() ? std::string("--force") : scene_file)
              << "'." << std::endl;
          return 2;
        }
      return igabde::scene::run_fclib(fclib_file, overrides);
    }
  if (scene_file.empty())
    {
      print_usage(err);
      return 2;
    }
  return igabde::scene::run_scene(scene_file, overrides, force);
}
