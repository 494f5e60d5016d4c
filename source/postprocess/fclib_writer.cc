#include <igabde/postprocess/fclib_writer.h>

#include <deal.II/base/exceptions.h>

#include <filesystem>
#include <fstream>
#include <vector>

extern "C" {
#include <fclib.h>
}

namespace igabde
{
  namespace postprocess
  {
    void
    write_fclib_local(const contact::ContactProblem      &problem,
                      const contact::ContactSolverResult *result,
                      const std::string                  &path)
    {
      const std::string where = "FCLIB writer: '" + path + "': ";
      try
        {
          problem.check_consistency();
        }
      catch (const std::exception &e)
        {
          AssertThrow(false,
                      dealii::ExcMessage(where +
                                         "inconsistent problem: " + e.what()));
        }
      AssertThrow(problem.G.size() == 0 && problem.b.size() == 0,
                  dealii::ExcMessage(
                    where +
                    "a problem with floating bodies (G, b non-empty) is not "
                    "written: it is no FCLIB local problem as "
                    "read_fclib_local() takes them"));
      AssertThrow(problem.n_components == 2 || problem.n_components == 3,
                  dealii::ExcMessage(
                    where + "a frictionless problem (n_components = 1) has "
                            "no FCLIB local form (spacedim is 2 or 3)"));
      const int n = static_cast<int>(problem.n_rows());
      if (result != nullptr)
        AssertThrow(result->p.size() == n && result->u.size() == n &&
                      result->p.allFinite() && result->u.allFinite(),
                    dealii::ExcMessage(
                      where + "the result's p and u must be finite with " +
                      std::to_string(n) + " entries"));

      // W in compressed columns, without its exact zeros.
      std::vector<int>    col_start(n + 1, 0), row;
      std::vector<double> value;
      for (int j = 0; j < n; ++j)
        {
          for (int i = 0; i < n; ++i)
            if (problem.W(i, j) != 0.)
              {
                row.push_back(i);
                value.push_back(problem.W(i, j));
              }
          col_start[j + 1] = static_cast<int>(row.size());
        }
      fclib_matrix W{};
      W.nzmax = static_cast<int>(row.size());
      W.m     = n;
      W.n     = n;
      W.p     = col_start.data();
      W.i     = row.data();
      W.x     = value.data();
      W.nz    = -1;
      W.info  = nullptr;

      std::vector<double> q(problem.q.data(), problem.q.data() + n);
      std::vector<double> mu(problem.mu);
      std::string         title = problem.name;
      fclib_info          info{};
      info.title = title.empty() ? nullptr : &title[0];

      fclib_local local{};
      local.W        = &W;
      local.V        = nullptr;
      local.R        = nullptr;
      local.mu       = mu.data();
      local.q        = q.data();
      local.s        = nullptr;
      local.spacedim = static_cast<int>(problem.n_components);
      local.info     = &info;

      // libfclib adds to an existing file (and refuses one holding a
      // problem); a new file is written here. It ends the process if HDF5
      // cannot create the file, so that is tried first.
      std::error_code error;
      std::filesystem::remove(path, error);
      AssertThrow(std::ofstream(path).good(),
                  dealii::ExcMessage(where + "cannot create the file"));
      std::filesystem::remove(path, error);
      AssertThrow(fclib_write_local(&local, path.c_str()) == 1,
                  dealii::ExcMessage(where + "libfclib could not write the "
                                             "problem"));
      if (result != nullptr)
        {
          std::vector<double> r(result->p.data(), result->p.data() + n);
          std::vector<double> u(result->u.data(), result->u.data() + n);
          fclib_solution      solution{};
          solution.r   = r.data();
          solution.u   = u.data();
          const int ok = result->converged ?
                           fclib_write_solution(&solution, path.c_str()) :
                           fclib_write_guesses(1, &solution, path.c_str());
          AssertThrow(ok == 1,
                      dealii::ExcMessage(where + "libfclib could not write the "
                                                 "solution"));
        }
    }

  } // namespace postprocess
} // namespace igabde
