#ifndef igabde_contact_fclib_reader_h
#define igabde_contact_fclib_reader_h

#include <igabde/contact/contact_problem.h>

#include <Eigen/Dense>

#include <string>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief Kinds of files in an FCLIB/Siconos problem collection.
     */
    enum class FclibFileKind
    {
      /** HDF5 with /fclib_local (W, q, mu). */
      hdf5_local,
      /** HDF5 with /fclib_global (M, H, f, w, mu); condensed on reading. */
      hdf5_global,
      /** HDF5 global problem with rolling friction (not supported). */
      hdf5_global_rolling,
      /** Siconos numerics .dat local friction-contact problem. */
      siconos_local_dat,
      /** Siconos .dat global problem (GFC3D_*, gfc2d_*); condensed on
       * reading. */
      siconos_global_dat,
      /** Anything else. */
      unknown
    };

    /**
     * @brief Classify @p filename by its extension, name and (for HDF5) its
     * top-level groups, without reading the data.
     */
    FclibFileKind
    classify_fclib_file(const std::string &filename);

    /**
     * @brief Read an FCLIB HDF5 local problem: /fclib_local/W (sparse),
     * /fclib_local/vectors/{q,mu}, /fclib_local/spacedim.
     *
     * FCLIB sparse matrices are groups {nzmax, m, n, nz, p, i, x} in the
     * CSparse convention: nz >= 0 is a triplet matrix with i the row and p
     * the column of each entry; nz = -1 compressed columns (p: n+1 column
     * pointers, i: row indices); nz = -2 compressed rows (p: m+1 row
     * pointers, i: column indices). W is stored densely in the result.
     * Throws (AssertThrow) naming the file and the offending dataset if the
     * file cannot be read or is inconsistent.
     */
    ContactProblem
    read_fclib_local(const std::string &filename);

    /**
     * @brief Read an FCLIB HDF5 global problem and condense it:
     * M v = H r + f, u = H^T v + w give W = H^T M^{-1} H and
     * q = H^T M^{-1} f + w (sparse LDL^T of M). Files with bilateral
     * constraints (/fclib_global/G) are rejected.
     */
    ContactProblem
    read_fclib_global(const std::string &filename);

    /**
     * @brief Read a Siconos numerics .dat local friction-contact problem:
     * dimension, number of contacts, the matrix (storage 0: dense, column
     * major; 1: sparse block; 2: CSparse text print), q, mu.
     */
    ContactProblem
    read_siconos_dat(const std::string &filename);

    /**
     * @brief Read a Siconos numerics .dat global friction-contact problem
     * (as globalFrictionContact_printInFile writes it: dimension, number
     * of contacts, M, H as NumericsMatrix prints, q, b, mu, where
     * M v = H r + q and u = H^T v + b) and condense it as
     * read_fclib_global() does: W = H^T M^{-1} H, q = H^T M^{-1} q + b.
     * A file named like a global problem that holds a local one (no H
     * after the first matrix: GFC3D_TwoRods1-condensed.dat) is read as
     * the local problem it is.
     */
    ContactProblem
    read_siconos_global_dat(const std::string &filename);

    /**
     * @brief Read any supported problem file (dispatch on
     * classify_fclib_file()); throws for unsupported kinds.
     */
    ContactProblem
    read_fclib_problem(const std::string &filename);

    /**
     * @brief Reference solution stored in an FCLIB HDF5 file.
     */
    struct FclibSolution
    {
      /** @brief True if the group 'solution' holds datasets r and u. */
      bool available = false;
      /** @brief Reaction (contact force) r. */
      Eigen::VectorXd r;
      /** @brief Local velocity (relative displacement) u. */
      Eigen::VectorXd u;
    };

    /**
     * @brief Reads the reference solution (datasets r and u of the group
     * 'solution') from an FCLIB HDF5 file, if present.
     */
    FclibSolution
    read_fclib_solution(const std::string &filename);

  } // namespace contact
} // namespace igabde

#endif
