#ifndef igabde_postprocess_fclib_writer_h
#define igabde_postprocess_fclib_writer_h

#include <igabde/contact/contact_problem.h>
#include <igabde/contact/contact_solver.h>

#include <string>

namespace igabde
{
  namespace postprocess
  {
    /**
     * @brief Write the condensed contact problem @p problem as an FCLIB
     * HDF5 local problem with libfclib (fclib_write_local()): W as a
     * compressed-column sparse matrix without its exact zeros, q, mu,
     * spacedim = n_components, the problem's name as the title;
     * contact::read_fclib_local() reads it back. An existing file at
     * @p path is replaced.
     *
     * If @p result is given, its contact forces and relative displacements
     * are stored with it (r = p, u = u): as the reference solution (the
     * HDF5 group "solution", read by contact::read_fclib_solution()) if it
     * converged, else as the one initial guess (the group "guesses", entry
     * 1).
     *
     * Refused (AssertThrow naming the file): frictionless problems
     * (n_components = 1; FCLIB's spacedim is 2 or 3), problems with
     * floating bodies (G, b non-empty: not an FCLIB local problem as
     * contact::read_fclib_local() takes them), inconsistent problems,
     * results of the wrong size, a path that cannot be created.
     */
    void
    write_fclib_local(const contact::ContactProblem      &problem,
                      const contact::ContactSolverResult *result,
                      const std::string                  &path);

  } // namespace postprocess
} // namespace igabde

#endif
