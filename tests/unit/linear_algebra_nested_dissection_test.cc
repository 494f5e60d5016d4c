// linear_algebra::nested_dissection_order, the pivot order the bodies' and
// the coupled system's MUMPS factorisations take, on the graph of a 3D grid
// of nodes: a permutation that keeps a node's unknowns together and puts
// the Schur unknowns last, and the fill theory predicts (George: nested
// dissection O(n^{4/3}) factor entries on a k x k x k grid against the
// banded order's O(n^{5/3}), a factor of about k / 4 at these sizes).

#include <igabde/linear_algebra/sparse_cholesky.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace
{
  // The 7-point graph of a k x k x k grid of nodes with c unknowns each
  // (numbered node by node), as sorted rows holding their diagonal.
  struct Grid
  {
    std::vector<std::size_t>  row_start{0};
    std::vector<unsigned int> columns;
    unsigned int              n;

    Grid(const unsigned int k, const unsigned int c)
      : n(k * k * k * c)
    {
      const auto node = [k](const int x, const int y, const int z) {
        return static_cast<unsigned int>((z * k + y) * k + x);
      };
      for (unsigned int v = 0; v < n; ++v)
        {
          const int x = (v / c) % k, y = (v / c / k) % k, z = v / c / k / k;
          std::vector<unsigned int> row;
          const int                 offsets[7][3] = {{0, 0, 0},
                                                     {-1, 0, 0},
                                                     {1, 0, 0},
                                                     {0, -1, 0},
                                                     {0, 1, 0},
                                                     {0, 0, -1},
                                                     {0, 0, 1}};
          for (const auto &o : offsets)
            {
              const int a = x + o[0], b = y + o[1], d = z + o[2];
              if (a < 0 || b < 0 || d < 0 || a >= int(k) || b >= int(k) ||
                  d >= int(k))
                continue;
              for (unsigned int s = 0; s < c; ++s)
                row.push_back(node(a, b, d) * c + s);
            }
          std::sort(row.begin(), row.end());
          columns.insert(columns.end(), row.begin(), row.end());
          row_start.push_back(columns.size());
        }
    }

    // Entries of the Cholesky factor of a matrix with this pattern (an
    // SPD Laplacian) eliminated in the order @p position (0-based
    // positions; empty: the natural order).
    long
    factor_entries(const std::vector<int> &position) const
    {
      std::vector<Eigen::Triplet<double>> entries;
      for (unsigned int i = 0; i < n; ++i)
        for (std::size_t k = row_start[i]; k < row_start[i + 1]; ++k)
          {
            const int pi = position.empty() ? int(i) : position[i];
            const int pj =
              position.empty() ? int(columns[k]) : position[columns[k]];
            entries.emplace_back(pi, pj, columns[k] == i ? 8. : -1.);
          }
      Eigen::SparseMatrix<double> A(n, n);
      A.setFromTriplets(entries.begin(), entries.end());
      Eigen::SimplicialLLT<Eigen::SparseMatrix<double>,
                           Eigen::Lower,
                           Eigen::NaturalOrdering<int>>
        cholesky(A);
      EXPECT_EQ(cholesky.info(), Eigen::Success);
      return Eigen::SparseMatrix<double>(cholesky.matrixL()).nonZeros();
    }
  };
} // namespace



TEST(NestedDissection, PermutationWithNodesTogetherAndSchurUnknownsLast)
{
  const Grid             grid(6, 3);
  const std::vector<int> schur = {5, 2, 11}; // 1-based, in this order
  const std::vector<int> order =
    igabde::linear_algebra::nested_dissection_order(grid.n,
                                                    grid.row_start,
                                                    grid.columns,
                                                    schur);
  ASSERT_EQ(order.size(), grid.n);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (unsigned int i = 0; i < grid.n; ++i)
    ASSERT_EQ(sorted[i], int(i) + 1);
  // The Schur unknowns last, in their given order.
  for (unsigned int s = 0; s < schur.size(); ++s)
    EXPECT_EQ(order[schur[s] - 1], int(grid.n - schur.size() + s + 1));
  // Every other node's three unknowns at consecutive positions (their
  // supervariable), in their own order.
  for (unsigned int v = 12; v < grid.n; v += 3)
    {
      EXPECT_EQ(order[v + 1], order[v] + 1);
      EXPECT_EQ(order[v + 2], order[v] + 2);
    }
}



TEST(NestedDissection, FactorOfA3DGridFarBelowTheBandedOrder)
{
  const Grid             grid(16, 1);
  const std::vector<int> order =
    igabde::linear_algebra::nested_dissection_order(grid.n,
                                                    grid.row_start,
                                                    grid.columns,
                                                    {});
  ASSERT_EQ(order.size(), grid.n);
  std::vector<int> position(grid.n);
  for (unsigned int i = 0; i < grid.n; ++i)
    position[i] = order[i] - 1;
  const long natural = grid.factor_entries({});
  const long nested  = grid.factor_entries(position);
  // k / 4 = 4 by the asymptotic orders; half is asked.
  EXPECT_LT(2 * nested, natural) << nested << " against " << natural;
}
