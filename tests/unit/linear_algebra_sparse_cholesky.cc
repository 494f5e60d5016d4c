// SparseCholesky (MUMPS LDL^T with the Schur complement) against dense
// linear algebra on a small SPD matrix: a 1D Laplacian chain with a
// coupling to its second neighbour, some unknowns eliminated.

#include <igabde/linear_algebra/sparse_cholesky.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

namespace
{
  using namespace dealii;

  constexpr unsigned int n = 40;

  struct Chain
  {
    SparsityPattern      sparsity;
    SparseMatrix<double> matrix;
    Eigen::MatrixXd      dense;

    Chain()
      : dense(Eigen::MatrixXd::Zero(n, n))
    {
      DynamicSparsityPattern dsp(n, n);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = (i >= 2 ? i - 2 : 0); j < std::min(n, i + 3); ++j)
          dsp.add(i, j);
      sparsity.copy_from(dsp);
      matrix.reinit(sparsity);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = (i >= 2 ? i - 2 : 0); j < std::min(n, i + 3); ++j)
          {
            const double v =
              (i == j ? 6. + 0.1 * i :
                        (std::abs(int(i) - int(j)) == 1 ? -2. : -0.5));
            matrix.set(i, j, v);
            dense(i, j) = v;
          }
    }
  };
} // namespace



TEST(SparseCholesky, SchurComplementAndSolveMatchDenseAlgebra)
{
  const Chain       chain;
  std::vector<bool> eliminated(n, false);
  eliminated[0] = eliminated[17] = eliminated[n - 1] = true;
  std::vector<unsigned int> free;
  for (unsigned int i = 0; i < n; ++i)
    if (!eliminated[i])
      free.push_back(i);
  const std::vector<types::global_dof_index> interface = {30, 3, 31, 12, 38};

  igabde::linear_algebra::SparseCholesky cholesky;
  cholesky.initialize(chain.matrix, eliminated, interface);
  ASSERT_EQ(cholesky.n_interface(), interface.size());

  // Dense reference on the free block: S^{-1} = (K_ff^{-1})_II.
  Eigen::MatrixXd Kf(free.size(), free.size());
  for (unsigned int a = 0; a < free.size(); ++a)
    for (unsigned int b = 0; b < free.size(); ++b)
      Kf(a, b) = chain.dense(free[a], free[b]);
  const Eigen::MatrixXd Kf_inv   = Kf.inverse();
  auto                  position = [&](const unsigned int i) {
    return std::find(free.begin(), free.end(), i) - free.begin();
  };
  Eigen::MatrixXd inv_II(interface.size(), interface.size());
  for (unsigned int a = 0; a < interface.size(); ++a)
    for (unsigned int b = 0; b < interface.size(); ++b)
      inv_II(a, b) = Kf_inv(position(interface[a]), position(interface[b]));
  // S^{-1} = (K_ff^{-1})_II: C^T S^{-1} C with C = I, from the factor of S
  // that the solves use.
  FullMatrix<double> identity(interface.size(), interface.size());
  for (unsigned int a = 0; a < interface.size(); ++a)
    identity(a, a) = 1.;
  const auto check_inverse = [&](const auto &factorization) {
    const FullMatrix<double> S_inv =
      factorization.interface_flexibility(identity);
    for (unsigned int a = 0; a < interface.size(); ++a)
      for (unsigned int b = 0; b < interface.size(); ++b)
        EXPECT_NEAR(S_inv(a, b), inv_II(a, b), 1e-12 * inv_II.norm());
  };
  check_inverse(cholesky);
  // The same complement whatever the pivot order.
  using Order = igabde::linear_algebra::SparseCholesky::PivotOrder;
  for (const Order order : {Order::minimum_degree, Order::nested_dissection})
    {
      igabde::linear_algebra::SparseCholesky ordered;
      ordered.initialize(chain.matrix, eliminated, interface, order);
      check_inverse(ordered);
    }

  // C^T S^{-1} C for two columns.
  FullMatrix<double> C(interface.size(), 2);
  Eigen::MatrixXd    Ce(interface.size(), 2);
  for (unsigned int a = 0; a < interface.size(); ++a)
    {
      C(a, 0) = Ce(a, 0) = 1. + a;
      C(a, 1) = Ce(a, 1) = (a % 2 ? -1. : 0.5);
    }
  const FullMatrix<double> F       = cholesky.interface_flexibility(C);
  const Eigen::MatrixXd    F_dense = Ce.transpose() * inv_II * Ce;
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = 0; j < 2; ++j)
      EXPECT_NEAR(F(i, j), F_dense(i, j), 1e-12 * F_dense.norm());

  // Full solves (reduction, dense Schur solve, expansion) for two
  // right-hand sides; eliminated entries are zero.
  std::vector<Vector<double>> rhs(2, Vector<double>(n));
  for (unsigned int i = 0; i < n; ++i)
    {
      rhs[0][i] = std::sin(0.3 * i);
      rhs[1][i] = (i == 30 ? 1. : 0.);
    }
  const std::vector<Vector<double>> original = rhs;
  cholesky.solve(rhs);
  for (unsigned int k = 0; k < 2; ++k)
    {
      Eigen::VectorXd f(free.size());
      for (unsigned int a = 0; a < free.size(); ++a)
        f(a) = original[k][free[a]];
      const Eigen::VectorXd u = Kf_inv * f;
      for (unsigned int a = 0; a < free.size(); ++a)
        EXPECT_NEAR(rhs[k][free[a]], u(a), 1e-12 * u.norm());
      EXPECT_EQ(rhs[k][0], 0.);
      EXPECT_EQ(rhs[k][17], 0.);
      EXPECT_EQ(rhs[k][n - 1], 0.);
    }

  // Without interface: a plain factorisation gives the same solves.
  igabde::linear_algebra::SparseCholesky plain;
  plain.initialize(chain.matrix, eliminated, {});
  std::vector<Vector<double>> rhs2 = original;
  plain.solve(rhs2);
  for (unsigned int k = 0; k < 2; ++k)
    for (unsigned int i = 0; i < n; ++i)
      EXPECT_NEAR(rhs2[k][i], rhs[k][i], 1e-12);
}



// Point operators touch a few of the face's unknowns each: for a C with at
// most a tenth of its entries non-zero, C^T S^{-1} C is formed from S^{-1}
// and C's compressed columns instead of L^{-1} C. Against the dense
// reference (K_ff^{-1})_II, on an interface of 19 unknowns with 30
// columns of one or two entries (45 of C's 570 entries).
TEST(SparseCholesky, SparseLoadPatternsMatchDenseAlgebra)
{
  const Chain       chain;
  std::vector<bool> eliminated(n, false);
  eliminated[0] = eliminated[n - 1] = true;
  std::vector<unsigned int> free;
  for (unsigned int i = 0; i < n; ++i)
    if (!eliminated[i])
      free.push_back(i);
  std::vector<types::global_dof_index> interface;
  for (unsigned int i = 1; i < n - 1; i += 2)
    interface.push_back(i);
  const unsigned int n_s = interface.size(), m = 30;
  ASSERT_EQ(n_s, 19u);

  igabde::linear_algebra::SparseCholesky cholesky;
  cholesky.initialize(chain.matrix, eliminated, interface);

  Eigen::MatrixXd Kf(free.size(), free.size());
  for (unsigned int a = 0; a < free.size(); ++a)
    for (unsigned int b = 0; b < free.size(); ++b)
      Kf(a, b) = chain.dense(free[a], free[b]);
  const Eigen::MatrixXd Kf_inv   = Kf.inverse();
  const auto            position = [&](const unsigned int i) {
    return std::find(free.begin(), free.end(), i) - free.begin();
  };
  Eigen::MatrixXd inv_II(n_s, n_s);
  for (unsigned int a = 0; a < n_s; ++a)
    for (unsigned int b = 0; b < n_s; ++b)
      inv_II(a, b) = Kf_inv(position(interface[a]), position(interface[b]));

  FullMatrix<double> C(n_s, m);
  Eigen::MatrixXd    Ce       = Eigen::MatrixXd::Zero(n_s, m);
  unsigned int       nonzeros = 0;
  for (unsigned int j = 0; j < m; ++j)
    for (unsigned int k = 0; k <= j % 2; ++k)
      {
        const unsigned int a = (7 * j + 5 * k) % n_s;
        const double       v = (k == 1 ? -0.7 : 1.) * (1. + 0.1 * j);
        nonzeros += (C(a, j) == 0.);
        C(a, j) += v;
        Ce(a, j) += v;
      }
  ASSERT_LE(10 * nonzeros, n_s * m);
  const FullMatrix<double> F       = cholesky.interface_flexibility(C);
  const Eigen::MatrixXd    F_dense = Ce.transpose() * inv_II * Ce;
  for (unsigned int i = 0; i < m; ++i)
    for (unsigned int j = 0; j < m; ++j)
      {
        EXPECT_NEAR(F(i, j), F_dense(i, j), 1e-12 * F_dense.norm());
        EXPECT_EQ(F(i, j), F(j, i));
      }
}


TEST(SparseCholesky, ReleaseKeepsTheReportsAndRefusesSolves)
{
  // The full contact path frees the bodies' factors once their load cases
  // are solved: the factor's size and flops stay for summary.json, a solve
  // is refused with a message instead of reading freed memory, and the
  // object factorises again afterwards.
  const Chain       chain;
  std::vector<bool> eliminated(n, false);
  eliminated[0]                                        = true;
  const std::vector<types::global_dof_index> interface = {10, 20};

  igabde::linear_algebra::SparseCholesky cholesky;
  cholesky.initialize(chain.matrix, eliminated, interface);
  const double entries = cholesky.factor_entries();
  const double flops   = cholesky.factor_flops();
  ASSERT_GT(entries, 0.);
  ASSERT_GT(flops, 0.);
  std::vector<Vector<double>> before(1, Vector<double>(n));
  for (unsigned int i = 0; i < n; ++i)
    before[0][i] = std::cos(0.2 * i);
  const std::vector<Vector<double>> rhs = before;
  cholesky.solve(before);

  cholesky.release();
  EXPECT_EQ(cholesky.factor_entries(), entries);
  EXPECT_EQ(cholesky.factor_flops(), flops);
  EXPECT_EQ(cholesky.n_interface(), interface.size());
  std::vector<Vector<double>> after = rhs;
  EXPECT_THROW(cholesky.solve(after), ExceptionBase);
  FullMatrix<double> C(interface.size(), 1);
  C(0, 0) = 1.;
  EXPECT_THROW(cholesky.interface_flexibility(C), ExceptionBase);

  cholesky.initialize(chain.matrix, eliminated, interface);
  cholesky.solve(after);
  for (unsigned int i = 0; i < n; ++i)
    EXPECT_EQ(after[0][i], before[0][i]);
}
