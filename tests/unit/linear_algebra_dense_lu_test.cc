#include <igabde/linear_algebra/dense_lu.h>

#include <gtest/gtest.h>

#include <cmath>

using igabde::linear_algebra::DenseLU;

namespace
{
  // The exact 1-norm condition number, |A|_1 |A^-1|_1, from the explicit
  // inverse (Eigen's full-pivoting LU): the independent reference.
  double
  exact_rcond(const Eigen::MatrixXd &A)
  {
    const Eigen::MatrixXd inverse  = A.fullPivLu().inverse();
    const auto            one_norm = [](const Eigen::MatrixXd &M) {
      return M.cwiseAbs().colwise().sum().maxCoeff();
    };
    return 1. / (one_norm(A) * one_norm(inverse));
  }
} // namespace

// diag(1, 1e-8) has |A|_1 = 1 and |A^-1|_1 = 1e8: rcond = 1e-8 exactly,
// and the estimator finds the largest column of the inverse exactly.
TEST(DenseLU, DiagonalMatrixHasItsExactConditionNumber)
{
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2, 2);
  A(0, 0)           = 1.;
  A(1, 1)           = 1e-8;
  const DenseLU lu(A);
  EXPECT_NEAR(lu.rcond(), 1e-8, 1e-20);
}

// Higham's estimator is a lower bound of |A^-1|_1, hence rcond() an upper
// bound of the true rcond; on Hilbert matrices it is exact or within the
// factor 3 that LAPACK's documentation states as typical.
TEST(DenseLU, HilbertConditionNumberWithinTheEstimatorsBound)
{
  for (const int n : {4, 6, 8})
    {
      Eigen::MatrixXd H(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          H(i, j) = 1. / (i + j + 1);
      const double  exact = exact_rcond(H);
      const DenseLU lu(H);
      EXPECT_GE(lu.rcond(), exact * (1. - 1e-3)) << "n = " << n;
      EXPECT_LE(lu.rcond(), 3. * exact) << "n = " << n;
    }
}

// Random non-symmetric systems solved against the product they came from,
// at sizes on both sides of small_size (Eigen below, LAPACK above). The
// rows of a diagonally dominant matrix are reversed, so that no
// factorisation without row interchanges would be accurate: the pivots
// must be found and applied.
TEST(DenseLU, SolvesRandomSystemsThatNeedPivoting)
{
  for (const int n : {3, 17, DenseLU::small_size, DenseLU::small_size + 1, 200})
    {
      const Eigen::MatrixXd dominant =
        Eigen::MatrixXd::Random(n, n) + n * Eigen::MatrixXd::Identity(n, n);
      const Eigen::MatrixXd A = dominant.colwise().reverse();
      const Eigen::VectorXd x = Eigen::VectorXd::Random(n);
      Eigen::VectorXd       b = A * x;
      const DenseLU         lu(A);
      ASSERT_TRUE(lu.factorized()) << "n = " << n;
      ASSERT_TRUE(lu.solve_in_place(b)) << "n = " << n;
      EXPECT_LT((b - x).norm(), 1e-12 * x.norm()) << "n = " << n;
    }
}

// An exactly singular matrix: dgetrf reports the zero pivot, rcond() is
// zero and no solution is returned.
TEST(DenseLU, SingularMatrixIsReported)
{
  Eigen::MatrixXd A(3, 3);
  A << 1., 2., 3., 2., 4., 6., 1., 0., 1.;
  const DenseLU lu(A);
  EXPECT_FALSE(lu.factorized());
  EXPECT_EQ(lu.rcond(), 0.);
  Eigen::VectorXd b = Eigen::VectorXd::Ones(3);
  EXPECT_FALSE(lu.solve_in_place(b));
}
