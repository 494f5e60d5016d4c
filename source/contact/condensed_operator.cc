#include <igabde/base/utilities.h>
#include <igabde/linear_algebra/dense_lu.h>

#include <igabde/contact/contact_operator.h>
#include <igabde/contact/flexibility_structure.h>

#include <deal.II/base/exceptions.h>

#include <deal.II/lac/lapack_templates.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace igabde
{
  namespace contact
  {
    namespace
    {
      using Vec            = Eigen::VectorXd;
      using Mat            = Eigen::MatrixXd;
      using SparseMatrix   = Eigen::SparseMatrix<double>;
      using RowMajorSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
      using Branch         = PairPiece;

      using dealii::types::blas_int;

      using System = internal::FlexibilityStructure;

      // The LDL^T of the last Levenberg-Marquardt matrix K^T K + lambda I
      // and that matrix's pattern: while the pattern repeats (a third of
      // a capsule heap's iterations, where few pairs change state) the
      // ordering and the symbolic analysis are kept and only the
      // numerical factorisation is redone.
      struct NormalEquationsCache
      {
        std::vector<int>                    outer, inner;
        Eigen::SimplicialLDLT<SparseMatrix> ldlt;
      };



      class NewtonMatrix
      {
      public:
        NewtonMatrix(const System              &sys,
                     const std::vector<Branch> &branches,
                     const bool                 use_symmetry,
                     NormalEquationsCache      &cache)
          : sys(sys)
          , branches(branches)
          , cache(cache)
          , d(sys.d)
          , m(sys.m)
          , na(sys.na)
          , position(m + na, -1)
        {
          symmetric = use_symmetry && sys.symmetric && na == 0;
          for (unsigned int c = 0; c < sys.problem.n_contacts; ++c)
            for (unsigned int k = 0; k < d; ++k)
              {
                const Branch &br      = branches[c];
                bool          trivial = br.B(k, k) == 1.;
                for (unsigned int l = 0; l < d && trivial; ++l)
                  trivial = br.A(k, l) == 0. && (l == k || br.B(k, l) == 0.);
                if (trivial)
                  {
                    this->trivial.push_back(c * d + k);
                    continue;
                  }
                bool diagonal = br.A(k, k) > 0.;
                for (unsigned int l = 0; l < d && diagonal; ++l)
                  diagonal = br.B(k, l) == 0. && (l == k || br.A(k, l) == 0.);
                symmetric           = symmetric && diagonal;
                position[c * d + k] = others.size();
                others.push_back(c * d + k);
              }
          for (unsigned int a = 0; a < na; ++a)
            {
              position[m + a] = others.size();
              others.push_back(m + a);
            }
        }

        unsigned int
        n_reduced() const
        {
          return others.size();
        }

        // J v
        Vec
        apply(const Vec &v) const
        {
          Vec w = sys.W_times(v.head(m));
          if (na > 0)
            w += sys.problem.G * v.tail(na);
          Vec out(m + na);
          for (unsigned int c = 0; c < sys.problem.n_contacts; ++c)
            {
              const unsigned int o  = c * d;
              const Branch      &br = branches[c];
              for (unsigned int k = 0; k < d; ++k)
                {
                  double s = 0.;
                  for (unsigned int l = 0; l < d; ++l)
                    s += br.A(k, l) * w[o + l] + br.B(k, l) * v[o + l];
                  out[o + k] = s;
                }
            }
          if (na > 0)
            out.tail(na) = sys.problem.G.transpose() * v.head(m);
          return out;
        }

        // The Newton direction for the residual H; appends "lm " to
        // @p note if the reduced matrix was (nearly) singular and a
        // Levenberg-Marquardt step was taken instead, regularised by
        // lm_relative times the largest diagonal entry of J^T J. Without
        // @p try_lu the step is Levenberg-Marquardt's unless the Cholesky
        // path applies (the LU is known to fail: a singular matrix the
        // iterations before).
        Vec
        direction(const Vec   &H,
                  std::string &note,
                  const double lm_relative,
                  const bool   try_lu = true) const
        {
          const unsigned int n = m + na;
          Vec                dx(n);
          for (const int i : trivial)
            dx[i] = -H[i];
          const unsigned int nN = others.size();
          if (nN == 0)
            return dx;
          // Matrices of a few hundred rows factorise faster on one thread.
          const base::SerialDenseAlgebra serial(nN);
          Vec                            rhs(nN);
          {
            Vec dt = Vec::Zero(n);
            for (const int i : trivial)
              dt[i] = dx[i];
            const Vec Jdt = trivial.empty() ? Vec::Zero(n) : apply(dt);
            for (unsigned int a = 0; a < nN; ++a)
              rhs[a] = -H[others[a]] - Jdt[others[a]];
          }
          Vec dN;
          if (symmetric &&
              (sys.sparse ? sparse_cholesky(rhs, dN) : dense_cholesky(rhs, dN)))
            ;
          else if (sys.sparse)
            {
              const RowMajorSparse K_rows = sparse_rows();
              const SparseMatrix   K      = K_rows;
              if (!try_lu || !sparse_lu(K, rhs, dN))
                {
                  dN = sparse_lm(K, K_rows, rhs, lm_relative);
                  note += "lm ";
                }
            }
          else if (!try_lu || !dense_lu(rhs, dN))
            {
              dN = dense_lm(rhs, lm_relative);
              note += "lm ";
            }
          for (unsigned int a = 0; a < nN; ++a)
            dx[others[a]] = dN[a];
          return dx;
        }

      private:
        // Smallest accepted reciprocal condition number of J_NN.
        static constexpr double min_rcond = 1e-14;

        // The non-zero A entries of the reduced contact rows: row r of
        // J_NN holds sum_t a_t W(source_t, N) for the terms t of r.
        struct Term
        {
          unsigned int row, source;
          double       a;
        };

        std::vector<Term>
        terms() const
        {
          std::vector<Term> t;
          for (unsigned int r = 0; r < others.size(); ++r)
            if (static_cast<unsigned int>(others[r]) < m)
              {
                const unsigned int i = others[r], c = i / d, k = i % d;
                for (unsigned int l = 0; l < d; ++l)
                  if (branches[c].A(k, l) != 0.)
                    t.push_back({r, c * d + l, branches[c].A(k, l)});
              }
          return t;
        }

        // sqrt(a_i) of the diagonal rows (symmetric case).
        Vec
        row_scaling() const
        {
          Vec s(others.size());
          for (unsigned int r = 0; r < others.size(); ++r)
            {
              const unsigned int i = others[r];
              s[r]                 = std::sqrt(branches[i / d].A(i % d, i % d));
            }
          return s;
        }

        Mat
        dense_matrix() const
        {
          const unsigned int      nN = others.size();
          const std::vector<Term> t  = terms();
          Mat                     K  = Mat::Zero(nN, nN);
          for (unsigned int b = 0; b < nN; ++b)
            {
              const unsigned int j = others[b];
              if (j < m)
                {
                  const double *col = sys.problem.W.data() + std::size_t(j) * m;
                  for (const Term &e : t)
                    K(e.row, b) += e.a * col[e.source];
                }
              else
                for (const Term &e : t)
                  K(e.row, b) += e.a * sys.problem.G(e.source, j - m);
            }
          if (sys.shift != 0.)
            for (const Term &e : t)
              if (position[e.source] >= 0)
                K(e.row, position[e.source]) += e.a * sys.shift;
          for (unsigned int r = 0; r < nN; ++r)
            {
              const unsigned int i = others[r];
              if (i < m)
                {
                  const unsigned int c = i / d, k = i % d, o = c * d;
                  for (unsigned int l = 0; l < d; ++l)
                    if (branches[c].B(k, l) != 0. && position[o + l] >= 0)
                      K(r, position[o + l]) += branches[c].B(k, l);
                }
              else
                for (unsigned int b = 0; b < nN; ++b)
                  if (static_cast<unsigned int>(others[b]) < m)
                    K(r, b) = sys.problem.G(others[b], i - m);
            }
          return K;
        }

        bool
        dense_cholesky(const Vec &rhs, Vec &dN) const
        {
          const blas_int nN = others.size();
          const Vec      s  = row_scaling();
          Mat            S(nN, nN);
          for (int b = 0; b < nN; ++b)
            {
              const double *col =
                sys.problem.W.data() + std::size_t(others[b]) * m;
              for (int r = b; r < nN; ++r)
                S(r, b) = s[r] * col[others[r]] * s[b];
              S(b, b) += s[b] * s[b] * sys.shift;
            }
          if (nN <= linear_algebra::DenseLU::small_size)
            {
              // Eigen in place: on tiny matrices OpenBLAS' per-call cost
              // (buffer lock, LAPACK's condition estimate) exceeds the
              // arithmetic (one-contact FCLIB problems).
              const Eigen::LLT<Eigen::Ref<Mat>, Eigen::Lower> llt(S);
              if (llt.info() != Eigen::Success || !(llt.rcond() > min_rcond))
                return false;
              dN = rhs.cwiseQuotient(s);
              llt.solveInPlace(dN);
              dN = dN.cwiseProduct(s);
              return dN.allFinite();
            }
          double anorm = 0.; // 1-norm from the lower triangle
          for (int b = 0; b < nN; ++b)
            {
              double sum = 0.;
              for (int r = 0; r < b; ++r)
                sum += std::abs(S(b, r));
              for (int r = b; r < nN; ++r)
                sum += std::abs(S(r, b));
              anorm = std::max(anorm, sum);
            }
          blas_int info = 0;
          dealii::potrf("L", &nN, S.data(), &nN, &info);
          if (info != 0)
            return false;
          double                rcond = 0.;
          std::vector<double>   work(3 * nN);
          std::vector<blas_int> iwork(nN);
          dealii::pocon("L",
                        &nN,
                        S.data(),
                        &nN,
                        &anorm,
                        &rcond,
                        work.data(),
                        iwork.data(),
                        &info);
          if (info != 0 || !(rcond > min_rcond))
            return false;
          dN                  = rhs.cwiseQuotient(s);
          const blas_int nrhs = 1;
          dealii::potrs("L", &nN, &nrhs, S.data(), &nN, dN.data(), &nN, &info);
          dN = dN.cwiseProduct(s);
          return info == 0 && dN.allFinite();
        }

        bool
        dense_lu(const Vec &rhs, Vec &dN) const
        {
          const linear_algebra::DenseLU lu(dense_matrix());
          if (!(lu.rcond() > min_rcond))
            return false;
          dN = rhs;
          return lu.solve_in_place(dN);
        }

        // Levenberg-Marquardt: (K^T K + lambda I) d = K^T rhs, through
        // BLAS-3 (syrk forms the lower triangle of K^T K at half a
        // product's flops) and a Cholesky factorisation; a pivoted LDL^T
        // where rounding leaves K^T K + lambda I not numerically positive.
        Vec
        dense_lm(const Vec &rhs, const double lm_relative) const
        {
          const Mat      K = dense_matrix();
          const blas_int n = K.rows();
          Mat            KtK(n, n);
          {
            const double one = 1., zero = 0.;
            dealii::syrk("L",
                         "T",
                         &n,
                         &n,
                         &one,
                         K.data(),
                         &n,
                         &zero,
                         KtK.data(),
                         &n);
          }
          const double lm =
            lm_relative * std::max(KtK.diagonal().maxCoeff(), 1e-300);
          KtK.diagonal().array() += lm;
          Vec      d    = K.transpose() * rhs;
          blas_int info = 0;
          Mat      L    = KtK;
          dealii::potrf("L", &n, L.data(), &n, &info);
          if (info == 0)
            {
              const blas_int nrhs = 1;
              dealii::potrs("L", &n, &nrhs, L.data(), &n, d.data(), &n, &info);
              if (info == 0 && d.allFinite())
                return d;
              d = K.transpose() * rhs;
            }
          return KtK.selfadjointView<Eigen::Lower>().ldlt().solve(d);
        }

        // The reduced Newton matrix by rows: row r is sum_t a_t Ws(source_t,
        // N) (with the shift and G) plus B's entries, accumulated in that
        // order (the order in which triplets once added them, so the
        // entries are the same to the bit), each row's columns sorted and
        // appended: no triplet list to sort. By rows it is also K^T by
        // columns, which the normal equations read.
        RowMajorSparse
        sparse_rows() const
        {
          const unsigned int      nN = others.size();
          const std::vector<Term> t  = terms();
          std::vector<double>     value(nN, 0.);
          std::vector<int>        mark(nN, -1), columns;
          std::size_t             nnz = 0;
          for (const Term &e : t)
            nnz += sys.Ws.outerIndexPtr()[e.source + 1] -
                   sys.Ws.outerIndexPtr()[e.source] + 1;
          RowMajorSparse K(nN, nN);
          K.reserve(nnz + std::size_t(d) * nN);
          std::size_t e = 0; // the terms are in the order of their rows
          for (unsigned int r = 0; r < nN; ++r)
            {
              columns.clear();
              const auto add = [&](const int column, const double v) {
                if (mark[column] != int(r))
                  {
                    mark[column]  = r;
                    value[column] = v;
                    columns.push_back(column);
                  }
                else
                  value[column] += v;
              };
              for (; e < t.size() && t[e].row == r; ++e)
                {
                  const Term &term = t[e];
                  for (RowMajorSparse::InnerIterator it(sys.Ws, term.source);
                       it;
                       ++it)
                    if (position[it.col()] >= 0)
                      add(position[it.col()], term.a * it.value());
                  if (sys.shift != 0. && position[term.source] >= 0)
                    add(position[term.source], term.a * sys.shift);
                  for (unsigned int a = 0; a < na; ++a)
                    if (sys.problem.G(term.source, a) != 0.)
                      add(position[m + a],
                          term.a * sys.problem.G(term.source, a));
                }
              const unsigned int i = others[r];
              if (i < m)
                {
                  const unsigned int c = i / d, k = i % d, o = c * d;
                  for (unsigned int l = 0; l < d; ++l)
                    if (branches[c].B(k, l) != 0. && position[o + l] >= 0)
                      add(position[o + l], branches[c].B(k, l));
                }
              else
                for (unsigned int b = 0; b < nN; ++b)
                  if (static_cast<unsigned int>(others[b]) < m &&
                      sys.problem.G(others[b], i - m) != 0.)
                    add(b, sys.problem.G(others[b], i - m));
              std::sort(columns.begin(), columns.end());
              K.startVec(r);
              for (const int column : columns)
                K.insertBack(r, column) = value[column];
            }
          K.finalize();
          return K;
        }

        // LDL^T of D^1/2 W_NN D^1/2; near-singular (pivot ratio below
        // min_rcond) or indefinite matrices are left to the LU.
        bool
        sparse_cholesky(const Vec &rhs, Vec &dN) const
        {
          const unsigned int                  nN = others.size();
          const Vec                           s  = row_scaling();
          std::vector<Eigen::Triplet<double>> entries;
          for (unsigned int r = 0; r < nN; ++r)
            for (RowMajorSparse::InnerIterator it(sys.Ws, others[r]); it; ++it)
              if (position[it.col()] >= 0)
                entries.emplace_back(r,
                                     position[it.col()],
                                     s[r] * it.value() * s[position[it.col()]]);
          if (sys.shift != 0.)
            for (unsigned int r = 0; r < nN; ++r)
              entries.emplace_back(r, r, s[r] * s[r] * sys.shift);
          SparseMatrix S(nN, nN);
          S.setFromTriplets(entries.begin(), entries.end());
          Eigen::SimplicialLDLT<SparseMatrix> ldlt(S);
          if (ldlt.info() != Eigen::Success)
            return false;
          const Vec &D = ldlt.vectorD();
          if (!(D.minCoeff() > min_rcond * D.maxCoeff()))
            return false;
          dN = ldlt.solve(rhs.cwiseQuotient(s)).cwiseProduct(s);
          return dN.allFinite();
        }

        // Sparse LU. Eigen gives no condition estimate: a pivot ratio
        // below min_rcond, or a solution with |K|_1 |d|_1 > |rhs|_1 /
        // min_rcond (both prove rcond < min_rcond), counts as singular.
        bool
        sparse_lu(const SparseMatrix &K, const Vec &rhs, Vec &dN) const
        {
          Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
          lu.analyzePattern(K);
          lu.factorize(K);
          if (lu.info() != Eigen::Success)
            return false;
          // The diagonal of U sits in the supernodes of L (as in Eigen's
          // SparseLU::absDeterminant()): a pivot ratio below min_rcond
          // proves near-singularity.
          double min_pivot = std::numeric_limits<double>::max(), max_pivot = 0.;
          const auto &L = lu.matrixL().m_mapL;
          for (Eigen::Index j = 0; j < K.cols(); ++j)
            for (typename std::decay_t<decltype(L)>::InnerIterator it(L, j); it;
                 ++it)
              if (it.index() == j)
                {
                  min_pivot = std::min(min_pivot, std::abs(it.value()));
                  max_pivot = std::max(max_pivot, std::abs(it.value()));
                  break;
                }
          if (!(min_pivot > min_rcond * max_pivot))
            return false;
          dN = lu.solve(rhs);
          if (!dN.allFinite())
            return false;
          double anorm = 0.;
          for (int b = 0; b < K.outerSize(); ++b)
            {
              double sum = 0.;
              for (SparseMatrix::InnerIterator it(K, b); it; ++it)
                sum += std::abs(it.value());
              anorm = std::max(anorm, sum);
            }
          return anorm * dN.lpNorm<1>() * min_rcond <= rhs.lpNorm<1>();
        }

        // (K^T K + lambda I) d = K^T rhs. (CHOLMOD's supernodal LL^T was
        // slower here than the simplicial LDL^T, on KaplasTower over the
        // 17 iterations.)
        Vec
        sparse_lm(const SparseMatrix   &K,
                  const RowMajorSparse &K_rows,
                  const Vec            &rhs,
                  const double          lm_relative) const
        {
          // The lower triangle of K^T K, column by column (Gustavson:
          // column j sums K's rows r scaled by K(r, j), in the order of
          // Eigen's sparse product, so the entries are the same to the
          // bit), with lambda on the diagonal, written straight into
          // compressed columns: half the product's flops and none of the
          // two sorting copies Eigen's general product makes (the product
          // and the analysis were most of the iterations' time on
          // Capsules-i100-1090; doc/contact-solver.md, doc/architecture.md).
          const Eigen::Index        n = K.cols();
          std::vector<double>       value(n, 0.);
          std::vector<Eigen::Index> mark(n, -1);
          std::vector<Eigen::Index> column;
          SparseMatrix              KtK(n, n);
          KtK.reserve(2 * K.nonZeros());
          double max_diagonal = 1e-300;
          for (Eigen::Index j = 0; j < n; ++j)
            {
              column.clear();
              mark[j]  = j; // the diagonal is always stored (lambda)
              value[j] = 0.;
              column.push_back(j);
              bool diagonal_touched = false;
              for (SparseMatrix::InnerIterator kr(K, j); kr; ++kr)
                for (RowMajorSparse::InnerIterator it(K_rows, kr.index()); it;
                     ++it)
                  if (const Eigen::Index i = it.index(); i >= j)
                    {
                      const double x = it.value() * kr.value();
                      if (i == j && !diagonal_touched)
                        {
                          diagonal_touched = true;
                          value[j]         = x;
                        }
                      else if (i != j && mark[i] != j)
                        {
                          mark[i]  = j;
                          value[i] = x;
                          column.push_back(i);
                        }
                      else
                        value[i] += x;
                    }
              max_diagonal = std::max(max_diagonal, value[j]);
              std::sort(column.begin() + 1, column.end());
              KtK.startVec(j);
              for (const Eigen::Index i : column)
                KtK.insertBack(i, j) = value[i];
            }
          KtK.finalize();
          const double lm = lm_relative * max_diagonal;
          for (Eigen::Index j = 0; j < n; ++j)
            KtK.valuePtr()[KtK.outerIndexPtr()[j]] += lm; // diagonal first
          const int *const outer = KtK.outerIndexPtr();
          const int *const inner = KtK.innerIndexPtr();
          if (!std::equal(outer,
                          outer + n + 1,
                          cache.outer.begin(),
                          cache.outer.end()) ||
              !std::equal(inner,
                          inner + KtK.nonZeros(),
                          cache.inner.begin(),
                          cache.inner.end()))
            {
              cache.ldlt.analyzePattern(KtK);
              cache.outer.assign(outer, outer + n + 1);
              cache.inner.assign(inner, inner + KtK.nonZeros());
            }
          cache.ldlt.factorize(KtK);
          return cache.ldlt.solve(K_rows.transpose() * rhs);
        }

        const System              &sys;
        const std::vector<Branch> &branches;
        NormalEquationsCache      &cache;
        const unsigned int         d, m, na;
        std::vector<int>           trivial, others, position;
        bool                       symmetric;
      };



    } // namespace



    /// W, the proximal shift and W's structure.
    class CondensedOperator::Storage
    {
    public:
      Storage(const Mat          &W,
              const LinearAlgebra linear_algebra,
              const double        sparse_fill,
              const bool          use_symmetry)
        : W(W)
        , linear_algebra(linear_algebra)
        , sparse_fill(sparse_fill)
        , use_symmetry(use_symmetry)
      {}

      // The structure of W for @p d components and G's columns (built on
      // first use), with the current shift.
      const System &
      system(const unsigned int d, const Mat &G)
      {
        if (!sys || sys->d != d || &sys->problem.G != &G)
          sys = std::make_unique<System>(W, G, d, linear_algebra, sparse_fill);
        sys->shift = eps;
        return *sys;
      }

      const Mat &W;
      /// W's largest diagonal entry (pair_row_is_held(); < 0: not yet).
      double                  max_diagonal = -1.;
      double                  eps          = 0.;
      const LinearAlgebra     linear_algebra;
      const double            sparse_fill;
      const bool              use_symmetry;
      std::unique_ptr<System> sys;
      NormalEquationsCache    normal_equations;
    };



    CondensedOperator::CondensedOperator(const Mat          &W,
                                         const LinearAlgebra linear_algebra,
                                         const double        sparse_fill,
                                         const bool          use_symmetry)
      : storage(std::make_unique<Storage>(W,
                                          linear_algebra,
                                          sparse_fill,
                                          use_symmetry))
    {
      AssertThrow(W.rows() == W.cols(),
                  dealii::ExcMessage("CondensedOperator: W must be square"));
    }



    CondensedOperator::~CondensedOperator() = default;



    bool
    CondensedOperator::pair_row_is_held(const unsigned int row) const
    {
      // A direction held by supports on both sides moves nothing: its row
      // and column of W vanish (W is positive semi-definite, so a zero
      // diagonal entry means a zero row). Weighted-gap pairs leave round-off
      // and mortar tails there (V7: 1e-12 to 1e-10 of the largest diagonal
      // entry), hence 1e-8: such a direction moves by less than 1e-8 of
      // what the same force moves elsewhere. condense() leaves out whole
      // pairs at 1e-12.
      const Mat &W = storage->W;
      AssertIndexRange(row, W.rows());
      if (storage->max_diagonal < 0.)
        storage->max_diagonal =
          W.rows() > 0 ? W.diagonal().cwiseAbs().maxCoeff() : 0.;
      return std::abs(W(row, row)) <= 1e-8 * storage->max_diagonal;
    }



    std::string
    CondensedOperator::path_name() const
    {
      return "condensed";
    }



    unsigned int
    CondensedOperator::n_rows() const
    {
      return storage->W.rows();
    }



    Vec
    CondensedOperator::displacement(const Vec &p, const Vec &) const
    {
      if (storage->sys)
        return storage->sys->W_times(p);
      return storage->W * p + storage->eps * p;
    }



    void
    CondensedOperator::displacement_adjoint(const Vec &y,
                                            Vec       &y_p,
                                            Vec       &y_w) const
    {
      y_p = storage->sys ? storage->sys->WT_times(y) :
                           Vec(storage->W.transpose() * y + storage->eps * y);
      y_w.resize(0);
    }



    PairWeights
    CondensedOperator::weights(const ContactData &data,
                               const double       factor) const
    {
      return pair_weights(storage->W, data.n_components, factor, storage->eps);
    }



    Vec
    CondensedOperator::pair_stiffness() const
    {
      const Mat         &W = storage->W;
      const unsigned int m = W.rows();
      Vec                k(m);
      for (unsigned int i = 0; i < m; ++i)
        {
          const double wii = W(i, i) + storage->eps;
          k[i]             = wii > 0. ? 1. / wii : 0.;
        }
      return k;
    }



    double
    CondensedOperator::flexibility_scale() const
    {
      return storage->W.rows() > 0 ?
               std::max(storage->W.diagonal().maxCoeff(), 0.) :
               0.;
    }



    const Eigen::MatrixXd *
    CondensedOperator::dense_flexibility() const
    {
      return &storage->W;
    }



    const Eigen::SparseMatrix<double, Eigen::RowMajor> *
    CondensedOperator::sparse_flexibility(const ContactData &data) const
    {
      const System &sys = storage->system(data.n_components, data.G);
      return sys.sparse ? &sys.Ws : nullptr;
    }



    void
    CondensedOperator::set_proximal_shift(const double eps)
    {
      storage->eps = eps;
      if (storage->sys)
        storage->sys->shift = eps;
    }



    bool
    CondensedOperator::proximal_for_singular_start() const
    {
      return storage->sys && storage->sys->sparse && storage->sys->symmetric;
    }



    bool
    CondensedOperator::newton_step(const ContactData    &data,
                                   const NewtonBlocks   &blocks,
                                   const ContactIterate &F,
                                   ContactIterate       &dx,
                                   StepReport           &report,
                                   const double          lm_relative,
                                   const bool            try_lu,
                                   const double)
    {
      const System      &sys = storage->system(data.n_components, data.G);
      const unsigned int m = sys.m, na = sys.na;
      const NewtonMatrix J(sys,
                           blocks,
                           storage->use_symmetry,
                           storage->normal_equations);
      report.n_reduced = J.n_reduced();
      Vec H(m + na);
      H.head(m) = F.p;
      if (na > 0)
        H.tail(na) = F.alpha;
      const Vec d = J.direction(H, report.note, lm_relative, try_lu);
      dx.p        = d.head(m);
      dx.alpha    = d.tail(na);
      dx.w.resize(0);
      return true;
    }



    bool
    CondensedOperator::bilateral_start(const ContactData       &problem,
                                       const std::vector<bool> &closed,
                                       ContactIterate          &x)
    {
      // A bilateral solve, W_cc p_c + G_c alpha = -q_c and G_c^T p_c = b,
      // over the pairs @p closed. Directions held by supports on both
      // sides (zero flexibility, no rigid motion) carry no force and are
      // left out.
      const Mat                &W = storage->W;
      const unsigned int        m = problem.n_components;
      std::vector<unsigned int> rows;
      const double              max_diag = W.diagonal().cwiseAbs().maxCoeff();
      const double              max_g =
        (problem.G.size() > 0 ? problem.G.cwiseAbs().maxCoeff() : 0.);
      for (unsigned int i = 0; i < problem.n_contacts; ++i)
        if (closed[i])
          for (unsigned int s = 0; s < m; ++s)
            {
              const unsigned int r = m * i + s;
              const double       g =
                (problem.G.cols() > 0 ? problem.G.row(r).cwiseAbs().maxCoeff() :
                                        0.);
              if (W(r, r) > 1e-12 * max_diag || g > 1e-12 * max_g)
                rows.push_back(r);
            }
      if (rows.empty())
        return false;
      const unsigned int nr = rows.size(), na = problem.n_alpha();
      Mat                A = Mat::Zero(nr + na, nr + na);
      Vec                rhs(nr + na);
      for (unsigned int i = 0; i < nr; ++i)
        {
          for (unsigned int j = 0; j < nr; ++j)
            A(i, j) = W(rows[i], rows[j]);
          for (unsigned int k = 0; k < na; ++k)
            {
              A(i, nr + k) = problem.G(rows[i], k);
              A(nr + k, i) = problem.G(rows[i], k);
            }
          rhs(i) = -problem.q(rows[i]);
        }
      for (unsigned int k = 0; k < na; ++k)
        rhs(nr + k) = problem.b(k);
      // Forces that load held unknowns only, on both sides, move nothing:
      // they make A singular, and their share of p is not determined (point
      // pairs show them as zero rows, left out above; weighted-gap pairs,
      // whose operators spread over a face's mass-matrix row, mix them into
      // several pairs). The minimum-norm solution leaves them out, so that
      // no force goes into the supports without need. A regular A (the
      // reciprocal condition number of its LU above 1e-12, the rank
      // threshold of the minimum-norm solve) is solved by LAPACK's blocked
      // LU: thousands of closed pairs (B2 one refinement past the seed's
      // mesh: 3 492 rows) in a fraction of a second.
      Vec solution = rhs;
      {
        const linear_algebra::DenseLU lu(A);
        if (!(lu.rcond() > 1e-12) || !lu.solve_in_place(solution))
          {
            Eigen::CompleteOrthogonalDecomposition<Mat> cod(A);
            cod.setThreshold(1e-12);
            solution = cod.solve(rhs);
          }
      }
      if (!solution.allFinite())
        return false;
      x.p = Vec::Zero(problem.n_rows());
      for (unsigned int i = 0; i < nr; ++i)
        x.p(rows[i]) = solution(i);
      x.alpha = solution.tail(na);
      x.w.resize(0);
      return true;
    }
  } // namespace contact
} // namespace igabde
