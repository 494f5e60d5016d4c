#ifndef igabde_linear_algebra_sparse_cholesky_h
#define igabde_linear_algebra_sparse_cholesky_h

#include <deal.II/base/types.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <memory>
#include <mpi.h>
#include <ostream>
#include <string>
#include <vector>

namespace igabde
{
  namespace linear_algebra
  {
    using namespace dealii;

    /**
     * @brief Sparse LDL^T factorisation of a symmetric positive definite
     * stiffness (MUMPS, sequential) that can return the Schur complement
     * onto a set of interface unknowns in the same factorisation.
     *
     * The matrix is the free block of K: the unknowns marked as eliminated
     * (supports, pins) are left out and read as zero in every solution.
     * With interface unknowns I, the interior E is factorised and
     * S = K_II - K_IE K_EE^{-1} K_EI comes out of the factorisation as a
     * dense matrix (BLAS-3 in MUMPS' last front); S is then factorised by
     * dense Cholesky. Then, for load patterns C that act on I only,
     * C^T K^{-1} C = C_I^T S^{-1} C_I without one solve per column, and a
     * full solve is a reduction onto I, a dense solve with S and an
     * expansion (MUMPS' ICNTL(26)).
     *
     * The factorisation runs on an MPI communicator (MPI_COMM_SELF unless
     * told otherwise): its first rank, the host, holds the matrix, the
     * right-hand sides, the solutions and S (MUMPS' centralised input and
     * Schur complement); the other ranks take part in every call and hold
     * their share of the factor. share() hands the interface (not S's
     * factor, n_s^2 values that only the host reads) to ranks outside the
     * communicator, so that they know the Schur interface.
     */
    class SparseCholesky
    {
    public:
      /**
       * @brief The fill-reducing pivot order of the factorisation.
       *
       * MUMPS orders by approximate minimum degree whenever a Schur
       * complement is requested; nested dissection (METIS, the Schur
       * unknowns last) needs about half its flops on 3D stiffness matrices
       * (B2: doc/performance.md) and costs an
       * ordering of its own (supervariable graph and METIS), on 2D meshes
       * of 10^5 unknowns more than the flops it saves (doc/performance.md).
       */
      enum class PivotOrder
      {
        /// MUMPS' own (approximate minimum degree).
        minimum_degree,
        /// METIS nested dissection of the interior, Schur unknowns last.
        nested_dissection,
        /// Both analysed, the one with fewer estimated flops factorised.
        cheaper_of_both
      };

      SparseCholesky();
      ~SparseCholesky();

      SparseCholesky(const SparseCholesky &) = delete;
      SparseCholesky &
      operator=(const SparseCholesky &) = delete;

      /**
       * @brief Factorises the free block of @p matrix.
       * @param matrix symmetric positive definite on the free unknowns
       * (only its lower triangle is read).
       * @param eliminated true for the unknowns that are held at zero.
       * @param interface unknowns onto which the Schur complement is formed
       * (free, distinct); empty: a plain factorisation.
       * @param order the pivot order (PivotOrder).
       * @param communicator the ranks that factorise together (collective
       * on it); only its first rank reads @p matrix, unless
       * @p distributed_values.
       * @param distributed_values each rank's @p matrix holds a share of
       * K's values (same sparsity pattern on every rank); K is their sum
       * (MUMPS' distributed assembled input).
       * @param matrix_read called on every rank once @p matrix has been
       * read, before the numerical factorisation: @p matrix is not read
       * after it, so the caller may free it there (where the memory
       * peaks).
       */
      void
      initialize(const SparseMatrix<double>                 &matrix,
                 const std::vector<bool>                    &eliminated,
                 const std::vector<types::global_dof_index> &interface,
                 PivotOrder     order        = PivotOrder::cheaper_of_both,
                 const MPI_Comm communicator = MPI_COMM_SELF,
                 const bool     distributed_values        = false,
                 const std::function<void()> &matrix_read = {});

      /**
       * @brief Progress lines of the numerical factorisations to come, on
       * @p stream (on the host; nullptr: none), naming @p label: every 5 s
       * the seconds so far and an estimate of those left (MUMPS' flop
       * estimate at the rate the longest finished factorisation reached).
       */
      void
      set_progress(std::ostream *stream, const std::string &label);

      /**
       * @brief Hands the interface and the factor size from the world rank
       * @p root (the host of the communicator the factorisation ran on) to
       * every rank of @p world (collective on @p world). The Cholesky factor
       * of S stays where it was computed (the host, or every rank when S is
       * the whole free block): interface_flexibility() and solve() run
       * there, so that the other ranks do not hold it at the height of
       * their memory use (doc/performance.md).
       */
      void
      share(const MPI_Comm world, const unsigned int root);

      /// Number of interface unknowns (size of the Schur complement).
      unsigned int
      n_interface() const;

      /// The interface unknowns, in the order of the Schur complement.
      const std::vector<types::global_dof_index> &
      interface_dofs() const;

      /**
       * @brief C^T S^{-1} C for the columns @p c given on the interface
       * unknowns (rows in the order of interface_dofs()): the flexibility
       * of the load patterns C, equal to C^T K^{-1} C.
       */
      FullMatrix<double>
      interface_flexibility(FullMatrix<double> c) const;

      /**
       * @brief Solves K u = f for every vector (in place), all at once;
       * eliminated unknowns are zero on return. Collective on the
       * factorisation's communicator: the host's vectors are read and
       * solved, the other ranks' are left as they are.
       */
      void
      solve(std::vector<Vector<double>> &rhs_and_solutions) const;

      /**
       * @brief Frees the factorisation (MUMPS' instance, the copy of the
       * matrix handed to it, S and its factor), keeping the interface and
       * the factor's size and flop count for reports; solve() and
       * interface_flexibility() are then unavailable. Collective on the
       * factorisation's communicator.
       */
      void
      release();

      /// Entries of the sparse factor (MUMPS' estimate after factorisation).
      double
      factor_entries() const;

      /// Floating-point operations of the factorisation (MUMPS' count).
      double
      factor_flops() const;

      /**
       * @brief Bytes this rank holds for the factorisation: the factor's
       * reals and integers on this rank as MUMPS reports them (INFO(9),
       * INFO(10); its workspace is not counted), the copy of the matrix
       * handed to it, the Schur complement and its factor, the index maps.
       */
      double
      local_bytes() const;

    private:
      struct Data;
      std::unique_ptr<Data> data;
    };

    /**
     * A fill-reducing pivot order for MUMPS (its PERM_IN, 1-based
     * positions: entry v is the position of unknown v): METIS nested
     * dissection of the unknowns not in @p schur_list, those last, in
     * their given order.
     *
     * MUMPS falls back to approximate minimum degree whenever a Schur
     * complement is requested, whatever ICNTL(7) says; on 3D stiffness
     * matrices nested dissection needs about half the flops (B2 8x16x8:
     * 3.2 instead of 6.2 GFlop per body). The graph is first compressed
     * into supervariables, runs of consecutive unknowns with the same
     * adjacency (the components of one control point or node, which both
     * discretisations number together), which METIS orders with their
     * length as vertex weight: dim^2 fewer edges. Another numbering only
     * compresses less.
     *
     * @p row_start, @p columns: the pattern (both triangles, each row
     * sorted and holding its diagonal, 0-based); @p schur_list: 1-based.
     * Returns an empty vector when METIS fails (MUMPS then orders).
     */
    std::vector<int>
    nested_dissection_order(const unsigned int               n,
                            const std::vector<std::size_t>  &row_start,
                            const std::vector<unsigned int> &columns,
                            const std::vector<int>          &schur_list);
  } // namespace linear_algebra
} // namespace igabde

#endif
