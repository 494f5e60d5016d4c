#ifndef igabde_contact_flexibility_structure_h
#define igabde_contact_flexibility_structure_h

#include <igabde/contact/contact_operator.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <cstddef>

namespace igabde
{
  namespace contact
  {
    namespace internal
    {
      /**
       * @brief The structure of the flexibility W that CondensedOperator's
       * Newton matrices read: whether W is symmetric (to rounding: a
       * problem read from a text file keeps about 1e-13 of asymmetry; a
       * Newton matrix that treats it as symmetric is off by that much), and
       * a sparse copy when W is sparse. The proximal phase's W + shift I is
       * W with the shift added where it is read: neither W nor the
       * structure is copied.
       */
      struct FlexibilityStructure
      {
        using Mat            = Eigen::MatrixXd;
        using Vec            = Eigen::VectorXd;
        using RowMajorSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

        /// What the Newton matrix reads of the problem: W and G.
        struct ProblemView
        {
          const Mat   &W;
          const Mat   &G;
          unsigned int n_contacts;
        };

        /**
         * @brief Reads the structure of @p W for @p d components per pair
         * and the rigid-mode columns @p G: the sparse copy where
         * @p linear_algebra asks for it, or (automatic) from
         * CondensedOperator::min_sparse_rows rows on when at most @p
         * sparse_fill of W's entries are non-zero.
         */
        FlexibilityStructure(const Mat                       &W,
                             const Mat                       &G,
                             unsigned int                     d,
                             CondensedOperator::LinearAlgebra linear_algebra,
                             double                           sparse_fill);

        /**
         * @brief Makes the compressed copy Ws of W in one pass in W's
         * column order and reads W's symmetry from it; gives up (false) as
         * soon as the copy holds more than @p limit non-zeros.
         */
        bool
        sparse_copy(const Mat &W, std::size_t limit);

        /** @brief W's symmetry from a pass over the dense W. */
        bool
        dense_symmetric(const Mat &W) const;

        /** @brief (W + shift I) v, from the sparse copy when there is one. */
        Vec
        W_times(const Vec &v) const;

        /** @brief (W + shift I)^T v. */
        Vec
        WT_times(const Vec &v) const;

        /**
         * @brief A v for a dense A, reading only the columns of the
         * non-zero entries of v on large A, by plain sums on a tiny one (at
         * most tiny_rows rows).
         */
        static Vec
        dense_times(const Mat &A, const Vec &v);

        /// Up to this many rows (four contacts in 3D) dense_times() sums
        /// each row itself: Eigen's product of a 3 x 3 W costs many times
        /// its 15 flops in instructions, a noticeable part of the solve of
        /// a one-contact problem.
        static constexpr Eigen::Index tiny_rows = 12;

        ProblemView        problem;
        const unsigned int d, m, na;
        /// W is symmetric (to 1e-12 of its largest entry).
        bool symmetric = false;
        /// W is kept and factorised as a sparse matrix (Ws).
        bool           sparse = false;
        RowMajorSparse Ws;
        /// The proximal shift: the Newton matrix is built of W + shift I.
        double shift = 0.;
      };
    } // namespace internal
  }   // namespace contact
} // namespace igabde

#endif
