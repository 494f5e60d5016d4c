#include <igabde/base/utilities.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <system_error>

namespace igabde
{
  namespace base
  {
    std::string
    number_text(const double x)
    {
      std::ostringstream out;
      out << x;
      return out.str();
    }



    double
    largest_magnitude(const double *data, const std::size_t n)
    {
      double largest = 0.;
      for (std::size_t i = 0; i < n; ++i)
        {
          if (!std::isfinite(data[i]))
            return std::numeric_limits<double>::infinity();
          largest = std::max(largest, std::abs(data[i]));
        }
      return largest;
    }



    double
    largest_squarable_entry(const std::size_t n)
    {
      return std::sqrt(std::numeric_limits<double>::max() /
                       static_cast<double>(std::max<std::size_t>(n, 1)));
    }



    std::string
    trim(const std::string &s)
    {
      const auto begin = s.find_first_not_of(" \t\r\n");
      if (begin == std::string::npos)
        return "";
      const auto end = s.find_last_not_of(" \t\r\n");
      return s.substr(begin, end - begin + 1);
    }



    std::vector<std::string>
    split(const std::string &s, const char separator)
    {
      std::vector<std::string> pieces;
      std::string              piece;
      std::istringstream       in(s);
      while (std::getline(in, piece, separator))
        {
          piece = trim(piece);
          if (!piece.empty())
            pieces.push_back(piece);
        }
      return pieces;
    }



    std::vector<double>
    parse_doubles(const std::string &text, const std::string &where)
    {
      std::string cleaned = text;
      for (char &c : cleaned)
        if (c == ',')
          c = ' ';
      std::istringstream  in(cleaned);
      std::vector<double> values;
      std::string         token;
      while (in >> token)
        {
          std::size_t used = 0;
          double      v    = 0;
          try
            {
              v = std::stod(token, &used);
            }
          catch (...)
            {
              used = 0;
            }
          AssertThrow(used == token.size() && std::isfinite(v),
                      ExcInput(where + ": '" + token +
                               "' is not a number; expected a comma-separated "
                               "list of numbers."));
          values.push_back(v);
        }
      return values;
    }



    std::pair<std::string, std::string>
    split_entry(const std::string &item,
                const std::string &where,
                const std::string &form)
    {
      const auto colon = item.find(':');
      AssertThrow(colon != std::string::npos,
                  ExcInput(where + ": '" + item + "' must read " + form + "."));
      return {trim(item.substr(0, colon)), trim(item.substr(colon + 1))};
    }



    template <int dim>
    std::string
    to_string(const Point<dim> &x)
    {
      std::ostringstream out;
      out << std::setprecision(4);
      for (unsigned int d = 0; d < dim; ++d)
        out << (d > 0 ? ", " : "") << x[d];
      return out.str();
    }



    std::string
    exception_message(const ExceptionBase &e)
    {
      std::ostringstream out;
      e.print_info(out);
      std::string message = out.str();
      // deal.II's messages span several lines and start with "    ";
      // collapse them into one.
      std::string result;
      bool        space = false;
      for (const char c : message)
        if (c == '\n' || c == ' ' || c == '\t')
          space = !result.empty();
        else
          {
            if (space)
              result += ' ';
            result += c;
            space = false;
          }
      const std::string prefix = "Additional information: ";
      if (result.rfind(prefix, 0) == 0)
        result = result.substr(prefix.size());
      return result;
    }



    template std::string
    to_string<2>(const Point<2> &);
    template std::string
    to_string<3>(const Point<3> &);


    std::string
    memory_allocator()
    {
      using mallctl_type =
        int (*)(const char *, void *, std::size_t *, void *, std::size_t);
      const auto mallctl =
        reinterpret_cast<mallctl_type>(dlsym(RTLD_DEFAULT, "mallctl"));
      if (mallctl == nullptr)
        return "system";
      const char *version = nullptr;
      const char *thp     = nullptr;
      std::size_t size    = sizeof(const char *);
      std::string result  = "jemalloc";
      if (mallctl("version", &version, &size, nullptr, 0) == 0 && version)
        result += " " + std::string(version);
      size = sizeof(const char *);
      if (mallctl("opt.thp", &thp, &size, nullptr, 0) == 0 && thp)
        result += ", transparent huge pages " + std::string(thp);
      return result;
    }



    unsigned int
    limit_dense_threads_per_rank()
    {
      if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1 ||
          std::getenv("OPENBLAS_NUM_THREADS") != nullptr ||
          std::getenv("OMP_NUM_THREADS") != nullptr)
        return 0;
      const int threads = std::max(1u, dealii::MultithreadInfo::n_threads());
      // Looked up at run time: the BLAS behind libblas.so.3 may not be
      // OpenBLAS, and OpenMP may not be loaded.
      using set_threads_type = void (*)(int);
      for (const char *name :
           {"openblas_set_num_threads", "omp_set_num_threads"})
        if (const auto set =
              reinterpret_cast<set_threads_type>(dlsym(RTLD_DEFAULT, name)))
          set(threads);
      return threads;
    }



    namespace
    {
      // OpenBLAS' thread-count functions, looked up once (null where the
      // BLAS behind libblas.so.3 is not OpenBLAS).
      struct OpenBlasThreads
      {
        using get_type = int (*)();
        using set_type = void (*)(int);
        get_type get   = reinterpret_cast<get_type>(
          dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
        set_type set = reinterpret_cast<set_type>(
          dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
      };

      const OpenBlasThreads &
      openblas_threads()
      {
        static const OpenBlasThreads functions;
        return functions;
      }
    } // namespace



    SerialDenseAlgebra::SerialDenseAlgebra(const std::size_t rows)
    {
      const OpenBlasThreads &openblas = openblas_threads();
      if (rows >= serial_dense_rows || openblas.get == nullptr ||
          openblas.set == nullptr)
        return;
      const int threads = openblas.get();
      if (threads <= 1)
        return;
      openblas.set(1);
      previous = threads;
    }



    SerialDenseAlgebra::~SerialDenseAlgebra()
    {
      if (previous > 0)
        openblas_threads().set(previous);
    }



    LightMpiSingleton::LightMpiSingleton()
    {
      for (const char *launcher_variable :
           {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (std::getenv(launcher_variable) != nullptr)
          return;
      const int keep_user_value = 0;
      setenv("OMPI_MCA_ess_singleton_isolated", "1", keep_user_value);
      setenv("OMPI_MCA_pml", "ob1", keep_user_value);
      if (std::getenv("OMPI_MCA_orte_tmpdir_base") != nullptr)
        return;
      // TMPDIR, else the system's temporary folder.
      std::error_code no_temporary_folder;
      const auto      temporary =
        std::filesystem::temp_directory_path(no_temporary_folder);
      if (no_temporary_folder)
        return;
      std::string pattern = (temporary / "igabde-mpi-XXXXXX").string();
      // Without a private base the run still works, only with the shared
      // one: no reason to stop here.
      if (mkdtemp(pattern.data()) == nullptr)
        return;
      session_base = pattern;
      setenv("OMPI_MCA_orte_tmpdir_base", session_base.c_str(), 1);
    }



    LightMpiSingleton::~LightMpiSingleton()
    {
      if (session_base.empty())
        return;
      std::error_code ignored;
      std::filesystem::remove_all(session_base, ignored);
    }
  } // namespace base
} // namespace igabde
