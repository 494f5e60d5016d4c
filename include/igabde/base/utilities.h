#ifndef igabde_base_utilities_h
#define igabde_base_utilities_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

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

    /**
     * @brief Reads a patch face number 0..n_faces-1 from @p text (the key of
     * @p item); throws naming @p where and the item otherwise.
     */
    unsigned int
    parse_face(const std::string &text,
               const unsigned int n_faces,
               const std::string &where,
               const std::string &item);

    /**
     * @brief Reads a tensor of dimension @p dim; extra trailing components
     * (a 3D default read in 2D) are ignored when they are zero.
     */
    template <int dim>
    Tensor<1, dim>
    parse_tensor(const std::string &text, const std::string &where);

    /// As parse_tensor(), as a point.
    template <int dim>
    Point<dim>
    parse_point(const std::string &text, const std::string &where);

    /**
     * @brief The message of a deal.II exception without the banner (file,
     * line, function), on one line.
     */
    std::string
    exception_message(const ExceptionBase &e);

    /**
     * @brief Called before MPI is initialised: a process started without an
     * MPI launcher asks Open MPI for a light singleton.
     *
     * By default an Open MPI singleton starts a helper daemon and probes the
     * UCX network layer: 0.4 s of a 0.45 s process start-up on the
     * reference machine, for a process that only talks to itself (MUMPS and
     * Trilinos run on MPI_COMM_SELF). This sets
     * OMPI_MCA_ess_singleton_isolated = 1 and OMPI_MCA_pml = ob1 unless the
     * user has set them. Under a launcher (mpirun, srun) nothing changes;
     * other MPI implementations ignore the variables.
     */
    void
    prefer_light_mpi_singleton();
  } // namespace base
} // namespace igabde

#endif
