#ifndef igabde_scene_run_fclib_h
#define igabde_scene_run_fclib_h

#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief `igabde --fclib FILE`: solves a published contact problem with
     * the contact layer's B-Newton, exactly as the condensed path solves a
     * scene's load step, and writes what a scene run writes about its
     * contact solve.
     *
     * FILE is an FCLIB HDF5 local problem (W, q, mu), an FCLIB HDF5 global
     * problem (condensed through its sparse M on reading) or a Siconos
     * numerics `.dat` local or global problem (the same condensation). The
     * output folder (Output/Directory, default `output/<file stem>`) receives
     * summary.json (the problem's sizes, the solver's outcome,
     * `checks.fclib_error` = |r - P_K(r - (W r + q + mu |u_t| e_n))| / |q|, the
     * condition check, the distance to a reference solution stored in the file,
     * seconds per phase), solution.csv (per contact its status, force r and
     * relative velocity u in the contact's local frame) and log.txt.
     *
     * Of the parameters, the solver's are read from @p overrides
     * (`--set`): Contact/Tolerance (default 1e-8, the FCLIB measure's
     * customary threshold), Contact/Max iterations (default 300),
     * Contact/r scale, Contact/Verbose, and Output/Directory,
     * Output/Progress; a parameter of a scene (a body, the mesh, the load
     * path) means nothing here and is refused.
     *
     * Returns the exit status: 0 solved (the FCLIB error at most the
     * tolerance), 1 not solved (summary.json says why, status "failed"),
     * 2 bad input (one line naming the file or parameter and the fix).
     * Under mpirun every rank solves and rank 0 writes.
     */
    int
    run_fclib(
      const std::string                                      &file,
      const std::vector<std::pair<std::string, std::string>> &overrides);
  } // namespace scene
} // namespace igabde

#endif
