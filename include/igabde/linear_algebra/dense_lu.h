#ifndef igabde_linear_algebra_dense_lu_h
#define igabde_linear_algebra_dense_lu_h

#include <deal.II/lac/lapack_support.h>

#include <Eigen/Dense>

#include <vector>

namespace igabde
{
  namespace linear_algebra
  {
    /**
     * @brief LU factorisation with partial pivoting of a dense square
     * matrix by LAPACK (dgetrf through deal.II's lapack_templates.h:
     * blocked, BLAS-3), with the reciprocal condition number of the matrix
     * in the 1-norm estimated from the factors. Matrices of at most
     * small_size rows are factorised by Eigen instead (the same
     * algorithm, partial pivoting): on them OpenBLAS' per-call cost (its
     * buffer lock and thread check) exceeds the arithmetic.
     *
     * deal.II 9.4 wraps no dgecon, so rcond() is LAPACK's estimate done by
     * hand: Higham's estimate of |A^-1|_1 (dlacn2: Hager's method, at most
     * five sweeps, then the alternating-sign test vector), by triangular
     * solves with the factors. A caller decides what a regular matrix is
     * (e.g. rcond() > 1e-12) and uses a rank-revealing solve otherwise.
     */
    class DenseLU
    {
    public:
      /// Largest size factorised by Eigen rather than LAPACK.
      static constexpr int small_size = 32;

      /// @brief Factorises @p A (taken by value: the factors replace it).
      explicit DenseLU(Eigen::MatrixXd A);

      /// @brief False when dgetrf found an exactly zero pivot.
      bool
      factorized() const
      {
        return info == 0;
      }

      /**
       * @brief Estimate of 1 / (|A|_1 |A^-1|_1); 0 when the factorisation
       * failed or the matrix is zero.
       */
      double
      rcond() const;

      /// @brief b := A^-1 b (dgetrs); false if LAPACK reports an error.
      bool
      solve_in_place(Eigen::VectorXd &b) const;

    private:
      Eigen::MatrixXd LU;
      /// LAPACK's row interchanges (1-based), or for a small matrix the
      /// row permutation P of P A = L U (0-based: row i of P A is row
      /// pivots[i] of A).
      std::vector<dealii::types::blas_int> pivots;
      double                               anorm = 0.;
      dealii::types::blas_int              info  = 0;
    };
  } // namespace linear_algebra
} // namespace igabde

#endif
