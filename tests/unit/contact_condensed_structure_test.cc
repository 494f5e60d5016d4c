// CondensedOperator reads W's structure once: whether it is kept sparse
// (automatic: from 48 rows at most 10 % non-zeros) and whether it is
// symmetric to 1e-12 of its largest entry. The reference is W itself: the
// sparse copy must hold W's entries exactly, and the symmetry verdict must
// follow the definition max |W_ij - W_ji| <= 1e-12 max |W_ij| for
// matrices built to lie on either side of it, including mirror entries of
// which one is an exact zero.

#include <igabde/contact/contact_operator.h>
#include <igabde/contact/contact_problem.h>

#include <gtest/gtest.h>

#include <random>

using namespace igabde::contact;

namespace condensed_structure_test
{
  using Mat = Eigen::MatrixXd;

  // 30 pairs in 3D; each pair coupled to itself and to the next pair (a
  // chain of rigid bodies): 30 full diagonal 3 x 3 blocks and 29 x 2
  // off-diagonal ones with one zero entry each, 270 + 464 = 734 of W's
  // 8 100 entries (9 %).
  Mat
  chain_flexibility()
  {
    std::mt19937                           rng(11);
    std::uniform_real_distribution<double> uniform(0.5, 1.5);
    const int                              n = 30, d = 3;
    Mat                                    W = Mat::Zero(n * d, n * d);
    for (int a = 0; a < n; ++a)
      for (int b = a; b < std::min(n, a + 2); ++b)
        for (int i = 0; i < d; ++i)
          for (int j = 0; j < d; ++j)
            if ((i + 2 * j) % 4 != 3 || a == b)
              {
                const double v = (a == b && i == j) ? 10. : uniform(rng);
                W(a * d + i, b * d + j) = v;
                W(b * d + j, a * d + i) = v;
              }
    return W;
  }

  ContactData
  data_for(const Mat &W)
  {
    ContactData data;
    data.n_contacts   = W.rows() / 3;
    data.n_components = 3;
    data.q            = Eigen::VectorXd::Zero(W.rows());
    data.mu.assign(data.n_contacts, 0.3);
    return data;
  }

  // The sparse copy, or an empty matrix where W is kept dense.
  Mat
  sparse_copy(const CondensedOperator &op, const ContactData &data)
  {
    const auto *Ws = op.sparse_flexibility(data);
    return Ws == nullptr ? Mat() : Mat(*Ws);
  }

  // The automatic sparse copy of W holds exactly W's non-zero entries
  // (-0 is not one), and no others.
  void
  expect_automatic_copy_is_exact(const Mat &W)
  {
    const int nnz = static_cast<int>((W.array() != 0.).cast<int>().sum());
    const ContactData       data = data_for(W);
    const CondensedOperator automatic(W);
    const Mat               copy = sparse_copy(automatic, data);
    ASSERT_EQ(copy.rows(), W.rows());
    EXPECT_EQ((copy - W).cwiseAbs().maxCoeff(), 0.);
    EXPECT_EQ(automatic.sparse_flexibility(data)->nonZeros(), nnz);
  }
} // namespace condensed_structure_test

using namespace condensed_structure_test;

TEST(ContactCondensedStructure, SparseCopyHoldsWExactly)
{
  const Mat W = chain_flexibility();
  const int m = W.rows();
  ASSERT_EQ(static_cast<int>((W.array() != 0.).cast<int>().sum()), 734);
  expect_automatic_copy_is_exact(W);
  const ContactData data = data_for(W);

  // A full W: kept dense when automatic, copied when sparse is asked for.
  Mat full = W;
  full.array() += 0.01;
  const CondensedOperator dense_auto(full);
  EXPECT_EQ(dense_auto.sparse_flexibility(data), nullptr);
  const CondensedOperator forced(full,
                                 CondensedOperator::LinearAlgebra::sparse);
  const Mat               forced_copy = sparse_copy(forced, data);
  ASSERT_EQ(forced_copy.rows(), m);
  EXPECT_EQ((forced_copy - full).cwiseAbs().maxCoeff(), 0.);
  const CondensedOperator dense(W, CondensedOperator::LinearAlgebra::dense);
  EXPECT_EQ(dense.sparse_flexibility(data), nullptr);
}

// The scan skips runs of zero entries: every stored position of a column
// (each remainder modulo the scan's run length, and the rows past the last
// full run: 99 rows) must still be copied, and -0 entries, equal to 0,
// must not be.
TEST(ContactCondensedStructure, SparseCopyFindsIsolatedEntriesAndDropsMinusZero)
{
  const int m = 99;
  Mat       W = Mat::Zero(m, m);
  for (int j = 0; j < m; ++j)
    {
      W(j, j)               = 5.;
      W((3 * j + 1) % m, j) = 0.25 + 0.01 * j;
      const int minus_zero  = (5 * j + 2) % m;
      if (W(minus_zero, j) == 0.)
        W(minus_zero, j) = -0.;
    }
  ASSERT_GE(static_cast<int>((W.array() != 0.).cast<int>().sum()), m + 90);
  ASSERT_LT(static_cast<int>((W.array() != 0.).cast<int>().sum()), 2 * m);
  expect_automatic_copy_is_exact(W);
}

TEST(ContactCondensedStructure, FillLimitIsTenPercentOfTheEntries)
{
  // Exactly floor(0.1 m^2) non-zeros is sparse, one more is dense.
  const int m = 60, limit = m * m / 10; // 360
  Mat       W      = Mat::Zero(m, m);
  int       placed = 0;
  for (int i = 0; i < m; ++i, ++placed)
    W(i, i) = 2.;
  for (int k = 1; placed < limit; ++k)
    for (int i = 0; i + k < m && placed < limit; ++i, ++placed)
      W(i, i + k) = 0.1;
  ASSERT_EQ((W.array() != 0.).cast<int>().sum(), limit);
  const ContactData data = data_for(W);
  EXPECT_NE(CondensedOperator(W).sparse_flexibility(data), nullptr);
  for (int i = m - 1; i >= 0; --i)
    if (W(i, 0) == 0.)
      {
        W(i, 0) = 0.1;
        break;
      }
  EXPECT_EQ(CondensedOperator(W).sparse_flexibility(data), nullptr);

  // Below 48 rows W stays dense whatever its fill.
  const Mat small = Mat::Identity(45, 45);
  EXPECT_EQ(CondensedOperator(small).sparse_flexibility(data_for(small)),
            nullptr);
}

TEST(ContactCondensedStructure, SymmetryToOneInATrillionOfTheLargestEntry)
{
  // proximal_for_singular_start() is true exactly where W is kept sparse
  // and is symmetric.
  const Mat    W0               = chain_flexibility();
  const double largest          = W0.cwiseAbs().maxCoeff(); // 10
  const auto   symmetric_sparse = [](const Mat &W) {
    const CondensedOperator op(W);
    op.sparse_flexibility(data_for(W)); // builds the structure
    return op.proximal_for_singular_start();
  };
  EXPECT_TRUE(symmetric_sparse(W0));

  // Rounding below the bound (a problem read from a text file).
  Mat W = W0;
  W(3, 5) += 1e-13 * largest;
  EXPECT_TRUE(symmetric_sparse(W));

  // Above it.
  W = W0;
  W(3, 5) += 1e-9 * largest;
  EXPECT_FALSE(symmetric_sparse(W));

  // Mirror entries of which one is an exact zero: different patterns.
  W = W0;
  ASSERT_EQ(W(0, 40), 0.);
  W(0, 40) = 0.5;
  EXPECT_FALSE(symmetric_sparse(W));
  W(0, 40) = 1e-14 * largest;
  EXPECT_TRUE(symmetric_sparse(W));

  // A dense symmetric W is not a sparse one.
  Mat full = W0;
  full.array() += 0.01;
  EXPECT_FALSE(symmetric_sparse(full));
}



// The displacement W p of a few contacts is summed row by row (up to 12
// rows), of more by Eigen's product: both must be W p to rounding, on a
// non-symmetric W (a transposed index would not pass) of 1, 4 and 5
// contacts. Reference: Eigen's product; bound: n eps sum_j |W_ij p_j|.
TEST(ContactCondensedStructure, DisplacementIsWTimesPOnTinyAndLargerW)
{
  std::mt19937                           rng(5);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  for (const int n : {3, 12, 15})
    {
      Mat W(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          W(i, j) = (i == j ? 4. : 0.) + uniform(rng) + (j > i ? 2. : 0.);
      Eigen::VectorXd p(n);
      for (int j = 0; j < n; ++j)
        p[j] = uniform(rng);
      const CondensedOperator op(W);
      op.sparse_flexibility(data_for(W)); // builds the structure
      const Eigen::VectorXd u     = op.displacement(p, Eigen::VectorXd());
      const Eigen::VectorXd exact = W * p;
      const Eigen::VectorXd bound =
        (W.cwiseAbs() * p.cwiseAbs()) * (n * 1.2e-16);
      ASSERT_EQ(u.size(), n);
      for (int i = 0; i < n; ++i)
        EXPECT_LE(std::abs(u[i] - exact[i]), bound[i])
          << "n = " << n << ", row " << i;
    }
}
