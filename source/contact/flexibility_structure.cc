#include <igabde/contact/flexibility_structure.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace igabde
{
  namespace contact
  {
    namespace internal
    {
      FlexibilityStructure::FlexibilityStructure(
        const Mat                             &W,
        const Mat                             &G,
        const unsigned int                     d,
        const CondensedOperator::LinearAlgebra linear_algebra,
        const double                           sparse_fill)
        : problem{W, G, d > 0 ? static_cast<unsigned int>(W.rows()) / d : 0}
        , d(d)
        , m(W.rows())
        , na(G.cols())
      {
        // From a few dozen rows on a sparse W's factorisations beat
        // LAPACK's (on the FCLIB corpus at fill 0.02-0.08: Box_Stacks-i0122,
        // 246 rows; Box_Stacks-i0035, 93 rows; FrictionContactProblem00374,
        // 56 rows; doc/contact-solver.md); at fill 0.2-0.3 (OneObject,
        // 69-75 rows) they lose.
        const bool automatic =
          linear_algebra == CondensedOperator::LinearAlgebra::automatic;
        const std::size_t limit =
          automatic ? static_cast<std::size_t>(sparse_fill * m * m) :
                      std::size_t(m) * m;
        if (linear_algebra == CondensedOperator::LinearAlgebra::sparse ||
            (automatic && m >= CondensedOperator::min_sparse_rows))
          sparse = sparse_copy(W, limit);
        if (!sparse)
          symmetric = dense_symmetric(W);
      }



      // A compressed copy of W, in one pass in W's column order, given
      // up as soon as it holds more than `limit` non-zeros (a dense W:
      // after a tenth of it). W's symmetry then follows from the copy:
      // W is symmetric exactly when its compressed rows (Ws) are its
      // compressed columns. A separate scan of W for its fill and
      // symmetry, and a copy through sorted triplets, took two thirds
      // of a one-sweep solve of Box_Stacks-i0035 (93 rows).
      bool
      FlexibilityStructure::sparse_copy(const Mat &W, const std::size_t limit)
      {
        std::vector<int>    start(m + 1, 0), rows;
        std::vector<double> values;
        double              max_entry = 0.;
        const auto          keep = [&](const unsigned int i, const double wij) {
          if (wij != 0.)
            {
              rows.push_back(i);
              values.push_back(wij);
              max_entry = std::max(max_entry, std::abs(wij));
            }
        };
        for (unsigned int j = 0; j < m; ++j)
          {
            // Eight entries at a time, skipped when all eight are zero:
            // +0 or -0, whose bits other than the sign are all zero. A
            // sparse W is mostly zeros, so the scan is the cost: at one
            // comparison per entry, half of a one-sweep solve of
            // NESpheres_30_1 (132 rows).
            const double *column = W.data() + std::size_t(j) * m;
            unsigned int  i      = 0;
            for (; i + 8 <= m; i += 8)
              {
                std::uint64_t bits[8];
                std::memcpy(bits, column + i, sizeof bits);
                if (((bits[0] | bits[1] | bits[2] | bits[3] | bits[4] |
                      bits[5] | bits[6] | bits[7])
                     << 1) != 0)
                  for (unsigned int k = i; k < i + 8; ++k)
                    keep(k, column[k]);
              }
            for (; i < m; ++i)
              keep(i, column[i]);
            if (rows.size() > limit)
              return false;
            start[j + 1] = rows.size();
          }
        const Eigen::Map<const Eigen::SparseMatrix<double>> by_columns(
          m,
          m,
          rows.size(),
          start.data(),
          rows.data(),
          values.data());
        Ws                    = by_columns;
        const std::size_t nnz = rows.size();
        if (std::equal(start.begin(), start.end(), Ws.outerIndexPtr()) &&
            std::equal(rows.begin(), rows.end(), Ws.innerIndexPtr()))
          {
            double max_asym = 0.;
            for (std::size_t k = 0; k < nnz; ++k)
              max_asym =
                std::max(max_asym, std::abs(values[k] - Ws.valuePtr()[k]));
            symmetric = max_asym <= 1e-12 * max_entry;
          }
        else
          {
            // Different patterns: an entry and its mirror, one of them
            // zero (or rounding below the other's exact zero). Each
            // stored entry against its mirror, found by bisection in the
            // mirror's column; the first pair that differs ends the test
            // (a capsule heap's W: at once, where forming W - W^T took a
            // noticeable part of its solve; doc/architecture.md).
            const double bound = 1e-12 * max_entry;
            symmetric          = true;
            for (unsigned int j = 0; j < m && symmetric; ++j)
              for (int k = start[j]; k < start[j + 1] && symmetric; ++k)
                {
                  const auto   first = rows.begin() + start[rows[k]];
                  const auto   last  = rows.begin() + start[rows[k] + 1];
                  const auto   q     = std::lower_bound(first, last, int(j));
                  const double mirror =
                    (q != last && *q == int(j)) ? values[q - rows.begin()] : 0.;
                  symmetric = std::abs(values[k] - mirror) <= bound;
                }
          }
        return true;
      }



      // W's symmetry from a pass over the dense W, in tiles for the
      // cache.
      bool
      FlexibilityStructure::dense_symmetric(const Mat &W) const
      {
        // The largest entry in one vectorised pass, then the strictly
        // lower triangle against its mirror tile by tile (the mirror's rows
        // stay in cache), ending at the first tile that exceeds the bound.
        if (m == 0)
          return true;
        const double       bound = 1e-12 * W.cwiseAbs().maxCoeff();
        const unsigned int tile  = 64;
        for (unsigned int jb = 0; jb < m; jb += tile)
          for (unsigned int ib = jb; ib < m; ib += tile)
            {
              double max_asym = 0.;
              for (unsigned int j = jb; j < std::min(m, jb + tile); ++j)
                for (unsigned int i = std::max(ib, j + 1);
                     i < std::min(m, ib + tile);
                     ++i)
                  max_asym = std::max(max_asym, std::abs(W(i, j) - W(j, i)));
              if (max_asym > bound)
                return false;
            }
        return true;
      }



      // (W + shift I) v, from the sparse copy when there is one.
      FlexibilityStructure::Vec
      FlexibilityStructure::W_times(const Vec &v) const
      {
        Vec out = sparse ? Vec(Ws * v) : dense_times(problem.W, v);
        if (shift != 0.)
          out += shift * v;
        return out;
      }



      // (W + shift I)^T v
      FlexibilityStructure::Vec
      FlexibilityStructure::WT_times(const Vec &v) const
      {
        Vec out = sparse    ? Vec(Ws.transpose() * v) :
                  symmetric ? dense_times(problem.W, v) :
                              Vec(problem.W.transpose() * v);
        if (shift != 0.)
          out += shift * v;
        return out;
      }



      // A v for a dense A, reading only the columns of the non-zero
      // entries of v: the forces of open pairs are zero, and on large
      // problems (10 000 rows: 800 MB of W) reading W is the cost of a
      // product, not its flops. Below 8 MiB (1 024 rows), where A stays
      // in the caches, Eigen's blocked product is as fast and is kept.
      FlexibilityStructure::Vec
      FlexibilityStructure::dense_times(const Mat &A, const Vec &v)
      {
        if (A.rows() <= tiny_rows)
          {
            Vec out(A.rows());
            for (Eigen::Index i = 0; i < A.rows(); ++i)
              {
                double sum = 0.;
                for (Eigen::Index j = 0; j < A.cols(); ++j)
                  sum += A(i, j) * v[j];
                out[i] = sum;
              }
            return out;
          }
        if (A.size() < (Eigen::Index(1) << 20))
          return A * v;
        Eigen::Index nonzero = 0;
        for (Eigen::Index j = 0; j < v.size(); ++j)
          nonzero += (v[j] != 0.);
        if (4 * nonzero > 3 * v.size())
          return A * v;
        Vec out = Vec::Zero(A.rows());
        for (Eigen::Index j = 0; j < v.size(); ++j)
          if (v[j] != 0.)
            out.noalias() += v[j] * A.col(j);
        return out;
      }
    } // namespace internal
  }   // namespace contact
} // namespace igabde
