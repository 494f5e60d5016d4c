#ifndef igabde_base_utilities_h
#define igabde_base_utilities_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace base
  {
    using namespace dealii;

    /**
     * @brief A user-facing input error: one line naming the file, the
     * parameter and what is accepted.
     */
    DeclException1(ExcInput, std::string, << arg1);

    /// Trims white space at both ends.
    std::string
    trim(const std::string &s);

    /// Splits at @p separator and trims; empty pieces are dropped.
    std::vector<std::string>
    split(const std::string &s, const char separator);

    /**
     * @brief Reads a comma- or space-separated list of numbers; @p where
     * names the parameter in the error message.
     */
    std::vector<double>
    parse_doubles(const std::string &text, const std::string &where);

    /**
     * @brief Splits a list item "key: value" at its first ':' into the
     * trimmed key and value; throws naming @p where, the item and the
     * expected @p form when there is no ':'.
     */
    std::pair<std::string, std::string>
    split_entry(const std::string &item,
                const std::string &where,
                const std::string &form);

    /// A number as a user wrote it, for messages (six significant digits).
    std::string
    number_text(const double x);

    /**
     * @brief The largest magnitude among @p n values at @p data, or infinity
     * if one is not finite.
     */
    double
    largest_magnitude(const double *data, const std::size_t n);

    /**
     * @brief The largest entry a vector of @p n entries may hold for its
     * squared Euclidean norm to stay finite in double precision:
     * sqrt(DBL_MAX / n). The solvers' norms square the entries, so data
     * past it have no answer in double arithmetic.
     */
    double
    largest_squarable_entry(const std::size_t n);

    /// A point as messages write it: "0.5, 0" (the parentheses are the
    /// caller's).
    template <int dim>
    std::string
    to_string(const Point<dim> &x);

    /**
     * @brief The message of a deal.II exception without the banner (file,
     * line, function), on one line.
     */
    std::string
    exception_message(const ExceptionBase &e);

    /**
     * @brief Constructed before MPI is initialised and destroyed after it is
     * finalised: a process started without an MPI launcher runs as a light
     * Open MPI singleton in a session directory of its own.
     *
     * By default an Open MPI singleton starts a helper daemon and probes the
     * UCX network layer: most of the process start-up (doc/performance.md),
     * for a process that only talks to itself (MUMPS and Trilinos run on
     * MPI_COMM_SELF). This sets
     * OMPI_MCA_ess_singleton_isolated = 1 and OMPI_MCA_pml = ob1 unless the
     * user has set them.
     *
     * Isolated singletons all name their session directory jf.0/1 under the
     * same base; at MPI_Finalize one process removes the directory another
     * one is creating, and the other's MPI_Init fails (two runs started
     * together, as ctest -j2 or a study driver does). Unless the user has
     * set OMPI_MCA_orte_tmpdir_base, each process therefore gets a base of
     * its own in the temporary folder (TMPDIR), removed again by the
     * destructor.
     *
     * Under a launcher (mpirun, srun) nothing changes; other MPI
     * implementations ignore the variables.
     */
    /**
     * @brief The memory allocator this process runs on: `"jemalloc
     * <version>, transparent huge pages <opt.thp>"` when jemalloc serves
     * malloc (the executables link it unless configured with
     * IGABDE_JEMALLOC=OFF or the sanitizers: doc/performance.md), else
     * `"system"`.
     *
     * Looked up at run time (dlsym of jemalloc's `mallctl`), so that a
     * program linked without jemalloc reports what it really uses.
     */
    std::string
    memory_allocator();



    class LightMpiSingleton
    {
    public:
      LightMpiSingleton();
      ~LightMpiSingleton();
      LightMpiSingleton(const LightMpiSingleton &) = delete;
      LightMpiSingleton &
      operator=(const LightMpiSingleton &) = delete;

    private:
      /** The private session base this object created; empty if none. */
      std::string session_base;
    };

    /**
     * @brief Under mpirun, limits the dense linear algebra's threads
     * (OpenBLAS, OpenMP) of this process to deal.II's thread count for it
     * (the node's cores divided among its ranks), so that ranks × threads
     * does not exceed the cores. OPENBLAS_NUM_THREADS or OMP_NUM_THREADS in
     * the environment override it. Returns the number set (0: left alone).
     */
    unsigned int
    limit_dense_threads_per_rank();

    /**
     * @brief OpenBLAS on one thread while this object lives, if the dense
     * matrix at hand has fewer than serial_dense_rows rows; restored at
     * the end of the scope.
     *
     * Below that size OpenBLAS' second thread costs more than it brings
     * (Cholesky and LU on the 2-core machine: doc/contact-solver.md), and
     * the contact Newton factorises matrices of tens to hundreds of rows
     * many times. Does nothing where the BLAS is not OpenBLAS or already
     * runs on one thread. Meant for the thread that runs the contact solve:
     * OpenBLAS' thread count is the process's, so a BLAS call another
     * thread makes meanwhile runs on one thread too (the same answer).
     */
    class SerialDenseAlgebra
    {
    public:
      /** Rows from which two threads pay off. */
      static constexpr std::size_t serial_dense_rows = 500;

      explicit SerialDenseAlgebra(const std::size_t rows);
      ~SerialDenseAlgebra();
      SerialDenseAlgebra(const SerialDenseAlgebra &) = delete;
      SerialDenseAlgebra &
      operator=(const SerialDenseAlgebra &) = delete;

    private:
      /** The thread count to restore (0: nothing changed). */
      int previous = 0;
    };
  } // namespace base
} // namespace igabde

#endif
