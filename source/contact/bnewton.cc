#include <igabde/contact/bnewton.h>

#include <deal.II/base/exceptions.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

// LAPACK (OpenBLAS through Debian's alternatives, linked by deal.II): the
// dense Newton matrices are factorised here rather than by Eigen, whose
// kernels are several times slower at the sizes of interest (2 000 pairs).
extern "C" {
void
dgetrf_(const int *, const int *, double *, const int *, int *, int *);
void
dgetrs_(const char *,
        const int *,
        const int *,
        const double *,
        const int *,
        const int *,
        double *,
        const int *,
        int *);
void
dgecon_(const char *,
        const int *,
        const double *,
        const int *,
        const double *,
        double *,
        double *,
        int *,
        int *);
void
dpotrf_(const char *, const int *, double *, const int *, int *);
void
dpotrs_(const char *,
        const int *,
        const int *,
        const double *,
        const int *,
        double *,
        const int *,
        int *);
void
dpocon_(const char *,
        const int *,
        const double *,
        const int *,
        const double *,
        double *,
        double *,
        int *,
        int *);
}

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

      double
      equilibrium_error(const ContactProblem &problem,
                        const Vec            &p,
                        double               &absolute)
      {
        return relative_equilibrium_error(problem, p, absolute);
      }



      using Weights = PairWeights;
      using Branch  = PairPiece;



      // H(x) and the branches for one problem, one radius, one r.
      class System
      {
      public:
        // With @p scan_W false, only residuals and dense products are
        // available (no look at W's structure).
        System(const ContactProblem          &problem,
               const Weights                 &weights,
               const FrictionRadius           radius,
               const BNewtonSolver::Settings &settings,
               const bool                     scan_W = true)
          : problem(problem)
          , w(weights)
          , radius(radius)
          , d(problem.n_components)
          , m(problem.n_rows())
          , na(problem.n_alpha())
        {
          if (!scan_W)
            return;
          // One pass over W, in tiles for the cache: its fill and whether
          // it is symmetric.
          std::size_t        nnz       = 0;
          double             max_entry = 0., max_asym = 0.;
          const unsigned int tile = 64;
          for (unsigned int jb = 0; jb < m; jb += tile)
            for (unsigned int ib = 0; ib < m; ib += tile)
              for (unsigned int j = jb; j < std::min(m, jb + tile); ++j)
                for (unsigned int i = ib; i < std::min(m, ib + tile); ++i)
                  {
                    const double wij = problem.W(i, j);
                    nnz += wij != 0.;
                    max_entry = std::max(max_entry, std::abs(wij));
                    if (i > j)
                      max_asym =
                        std::max(max_asym, std::abs(wij - problem.W(j, i)));
                  }
          symmetric = max_asym <= 1e-14 * max_entry;
          fill      = m > 0 ? double(nnz) / (double(m) * m) : 1.;
          switch (settings.linear_algebra)
            {
              case NewtonLinearAlgebra::dense:
                sparse = false;
                break;
              case NewtonLinearAlgebra::sparse:
                sparse = true;
                break;
              case NewtonLinearAlgebra::automatic:
                sparse = m >= 300 && fill <= settings.sparse_fill;
                break;
            }
          if (sparse)
            {
              std::vector<Eigen::Triplet<double>> entries;
              entries.reserve(nnz);
              for (unsigned int j = 0; j < m; ++j)
                for (unsigned int i = 0; i < m; ++i)
                  if (problem.W(i, j) != 0.)
                    entries.emplace_back(i, j, problem.W(i, j));
              Ws.resize(m, m);
              Ws.setFromTriplets(entries.begin(), entries.end());
            }
        }

        // W v, from the sparse copy when there is one.
        Vec
        W_times(const Vec &v) const
        {
          return sparse ? Vec(Ws * v) : Vec(problem.W * v);
        }

        // W^T v
        Vec
        WT_times(const Vec &v) const
        {
          return sparse ? Vec(Ws.transpose() * v) :
                          Vec(problem.W.transpose() * v);
        }

        Vec
        displacement(const Vec &x) const
        {
          Vec u = W_times(x.head(m)) + problem.q;
          if (na > 0)
            u += problem.G * x.tail(na);
          return u;
        }

        // Fills H (size m + na); branches if non-null.
        void
        residual(const Vec           &x,
                 const Vec           &u,
                 Vec                 &H,
                 std::vector<Branch> *branches) const
        {
          H.resize(m + na);
          if (branches)
            branches->resize(problem.n_contacts);
          for (unsigned int c = 0; c < problem.n_contacts; ++c)
            {
              const unsigned int o = c * d;
              pair_law(d,
                       d > 1 ? problem.mu[c] : 0.,
                       w.r_n[c],
                       w.r_t[c],
                       radius,
                       x.data() + o,
                       u.data() + o,
                       H.data() + o,
                       branches ? &(*branches)[c] : nullptr);
            }
          if (na > 0)
            H.tail(na) = problem.G.transpose() * x.head(m) - problem.b;
        }

        // Floating-body tie rule: activate the closest contact if none is
        // closed (else the alpha columns of J vanish).
        void
        apply_floating_tie_rule(const Vec           &x,
                                const Vec           &u,
                                std::vector<Branch> &branches) const
        {
          if (na == 0 || problem.n_contacts == 0)
            return;
          for (const Branch &br : branches)
            if (br.closed)
              return;
          unsigned int best = 0;
          double       gap  = std::numeric_limits<double>::infinity();
          for (unsigned int c = 0; c < problem.n_contacts; ++c)
            {
              const double g = w.r_n[c] * u[c * d] - x[c * d];
              if (g < gap)
                {
                  gap  = g;
                  best = c;
                }
            }
          Branch &br = branches[best];
          br.closed  = true;
          br.A(0, 0) = w.r_n[best];
          br.B(0, 0) = 0.;
        }

        const ContactProblem &problem;
        const Weights        &w;
        const FrictionRadius  radius;
        const unsigned int    d, m, na;
        /// W is exactly symmetric (to 1e-14 of its largest entry).
        bool symmetric = false;
        /// Share of non-zero entries of W.
        double fill = 1.;
        /// W is kept and factorised as a sparse matrix (Ws).
        bool           sparse = false;
        RowMajorSparse Ws;
      };



      // The Newton matrix J = [A W + B, A G; G^T, 0] of one iteration,
      // matrix-free for products, and its direction solve. Rows with A = 0
      // and B = identity ("trivial": open normals, free tangents) give
      // d_i = -H_i and drop out; the rest, J_NN d_N = -H_N - J_NT d_T, is
      // factorised: by Cholesky when every remaining row is a positive
      // multiple a_i of a row of a symmetric W (closed normals, stick
      // tangents; then J_NN = D W_NN, and J_NN d = r is S y = D^-1/2 r,
      // d = D^1/2 y with S = D^1/2 W_NN D^1/2 symmetric),
      // by LU otherwise; dense (LAPACK) or sparse (Eigen) as the System
      // stores W.
      class NewtonMatrix
      {
      public:
        NewtonMatrix(const System              &sys,
                     const std::vector<Branch> &branches,
                     const bool                 use_symmetry)
          : sys(sys)
          , branches(branches)
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

        // J^T h
        Vec
        apply_transpose(const Vec &h) const
        {
          Vec y(m), bt(m);
          for (unsigned int c = 0; c < sys.problem.n_contacts; ++c)
            {
              const unsigned int o  = c * d;
              const Branch      &br = branches[c];
              for (unsigned int l = 0; l < d; ++l)
                {
                  double sa = 0., sb = 0.;
                  for (unsigned int k = 0; k < d; ++k)
                    {
                      sa += br.A(k, l) * h[o + k];
                      sb += br.B(k, l) * h[o + k];
                    }
                  y[o + l]  = sa;
                  bt[o + l] = sb;
                }
            }
          Vec out(m + na);
          out.head(m) = sys.WT_times(y) + bt;
          if (na > 0)
            {
              out.head(m) += sys.problem.G * h.tail(na);
              out.tail(na) = sys.problem.G.transpose() * y;
            }
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
          Vec rhs(nN);
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
              const SparseMatrix K = sparse_matrix();
              if (!try_lu || !sparse_lu(K, rhs, dN))
                {
                  dN = sparse_lm(K, rhs, lm_relative);
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
          const int nN = others.size();
          const Vec s  = row_scaling();
          Mat       S(nN, nN);
          for (int b = 0; b < nN; ++b)
            {
              const double *col =
                sys.problem.W.data() + std::size_t(others[b]) * m;
              for (int r = b; r < nN; ++r)
                S(r, b) = s[r] * col[others[r]] * s[b];
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
          int info = 0;
          dpotrf_("L", &nN, S.data(), &nN, &info);
          if (info != 0)
            return false;
          double              rcond = 0.;
          std::vector<double> work(3 * nN);
          std::vector<int>    iwork(nN);
          dpocon_("L",
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
          dN             = rhs.cwiseQuotient(s);
          const int nrhs = 1;
          dpotrs_("L", &nN, &nrhs, S.data(), &nN, dN.data(), &nN, &info);
          dN = dN.cwiseProduct(s);
          return info == 0 && dN.allFinite();
        }

        bool
        dense_lu(const Vec &rhs, Vec &dN) const
        {
          const int nN    = others.size();
          Mat       K     = dense_matrix();
          double    anorm = 0.;
          for (int b = 0; b < nN; ++b)
            anorm = std::max(anorm, K.col(b).cwiseAbs().sum());
          std::vector<int> pivots(nN);
          int              info = 0;
          dgetrf_(&nN, &nN, K.data(), &nN, pivots.data(), &info);
          if (info != 0)
            return false;
          double              rcond = 0.;
          std::vector<double> work(4 * nN);
          std::vector<int>    iwork(nN);
          dgecon_("1",
                  &nN,
                  K.data(),
                  &nN,
                  &anorm,
                  &rcond,
                  work.data(),
                  iwork.data(),
                  &info);
          if (info != 0 || !(rcond > min_rcond))
            return false;
          dN             = rhs;
          const int nrhs = 1;
          dgetrs_("N",
                  &nN,
                  &nrhs,
                  K.data(),
                  &nN,
                  pivots.data(),
                  dN.data(),
                  &nN,
                  &info);
          return info == 0 && dN.allFinite();
        }

        // Levenberg-Marquardt: (K^T K + lambda I) d = K^T rhs.
        Vec
        dense_lm(const Vec &rhs, const double lm_relative) const
        {
          const Mat    K   = dense_matrix();
          const Mat    KtK = K.transpose() * K;
          const double lm =
            lm_relative * std::max(KtK.diagonal().maxCoeff(), 1e-300);
          return (KtK + lm * Mat::Identity(K.rows(), K.rows()))
            .ldlt()
            .solve(K.transpose() * rhs);
        }

        SparseMatrix
        sparse_matrix() const
        {
          const unsigned int                  nN = others.size();
          std::vector<Eigen::Triplet<double>> entries;
          for (const Term &e : terms())
            {
              for (RowMajorSparse::InnerIterator it(sys.Ws, e.source); it; ++it)
                if (position[it.col()] >= 0)
                  entries.emplace_back(e.row,
                                       position[it.col()],
                                       e.a * it.value());
              for (unsigned int a = 0; a < na; ++a)
                if (sys.problem.G(e.source, a) != 0.)
                  entries.emplace_back(e.row,
                                       position[m + a],
                                       e.a * sys.problem.G(e.source, a));
            }
          for (unsigned int r = 0; r < nN; ++r)
            {
              const unsigned int i = others[r];
              if (i < m)
                {
                  const unsigned int c = i / d, k = i % d, o = c * d;
                  for (unsigned int l = 0; l < d; ++l)
                    if (branches[c].B(k, l) != 0. && position[o + l] >= 0)
                      entries.emplace_back(r,
                                           position[o + l],
                                           branches[c].B(k, l));
                }
              else
                for (unsigned int b = 0; b < nN; ++b)
                  if (static_cast<unsigned int>(others[b]) < m &&
                      sys.problem.G(others[b], i - m) != 0.)
                    entries.emplace_back(r, b, sys.problem.G(others[b], i - m));
            }
          SparseMatrix K(nN, nN);
          K.setFromTriplets(entries.begin(), entries.end());
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
        // slower here than the simplicial LDL^T: on KaplasTower 0.66 s
        // against 0.46 s over the 17 iterations.)
        Vec
        sparse_lm(const SparseMatrix &K,
                  const Vec          &rhs,
                  const double        lm_relative) const
        {
          SparseMatrix KtK = K.transpose() * K;
          const double lm =
            lm_relative * std::max(KtK.diagonal().maxCoeff(), 1e-300);
          SparseMatrix I(K.cols(), K.cols());
          I.setIdentity();
          KtK += lm * I;
          return Eigen::SimplicialLDLT<SparseMatrix>(KtK).solve(K.transpose() *
                                                                rhs);
        }

        const System              &sys;
        const std::vector<Branch> &branches;
        const unsigned int         d, m, na;
        std::vector<int>           trivial, others, position;
        bool                       symmetric;
      };



      void
      count_status(const std::vector<Branch> &branches,
                   unsigned int              &n_open,
                   unsigned int              &n_stick,
                   unsigned int              &n_slip)
      {
        n_open = n_stick = n_slip = 0;
        for (const Branch &br : branches)
          switch (br.status)
            {
              case ContactStatus::open:
                ++n_open;
                break;
              case ContactStatus::stick:
                ++n_stick;
                break;
              case ContactStatus::slip:
                ++n_slip;
                break;
            }
      }



      std::string
      phase_name(const std::string &prefix, const FrictionRadius radius)
      {
        return prefix +
               (radius == FrictionRadius::christensen_pang ? "-cp" : "-ac");
      }



      FrictionRadius
      other(const FrictionRadius radius)
      {
        return radius == FrictionRadius::christensen_pang ?
                 FrictionRadius::alart_curnier :
                 FrictionRadius::christensen_pang;
      }



      // The stopping test (see the class documentation).
      bool
      stopping_test(const ContactProblem &problem,
                    const Vec            &x,
                    const Vec            &u,
                    const double          tolerance,
                    double               &err,
                    double               &balanced,
                    double               &eq_err,
                    const bool            at_rounding_floor)
      {
        const unsigned int m = problem.n_rows();
        err      = relative_natural_map_error(problem, x.head(m), u);
        balanced = balanced_natural_map_error(problem, x.head(m), u);
        double abs_eq;
        eq_err = equilibrium_error(problem, x.head(m), abs_eq);
        return balanced <= tolerance &&
               (err <= tolerance ||
                (at_rounding_floor && balanced <= 1e-3 * tolerance)) &&
               eq_err <= tolerance;
      }



      /// "pairs 3, 17, 40" (at most eight named, then "+N more").
      std::string
      pair_list_text(const std::vector<unsigned int> &pairs)
      {
        std::string text = pairs.size() == 1 ? "pair " : "pairs ";
        for (unsigned int k = 0; k < pairs.size() && k < 8; ++k)
          text += (k > 0 ? ", " : "") + std::to_string(pairs[k]);
        if (pairs.size() > 8)
          text += " (+" + std::to_string(pairs.size() - 8) + " more)";
        return text;
      }



      /// The piece of each pair (status and closed normal), for comparing
      /// active sets between iterations.
      std::vector<int>
      active_set(const std::vector<Branch> &branches)
      {
        std::vector<int> set;
        set.reserve(branches.size());
        for (const Branch &br : branches)
          set.push_back(2 * static_cast<int>(br.status) + (br.closed ? 1 : 0));
        return set;
      }



      /**
       * What a failed phase involves, for its diagnosis: pairs with
       * non-finite forces or residuals; else, if the last active sets of
       * the phase repeat (fewer distinct sets than half the window), a cycle
       * and the pairs whose piece changes in it; else the three pairs with
       * the largest residual.
       */
      std::string
      describe_failure(const std::vector<std::vector<int>> &sets,
                       const unsigned int                   window,
                       const Vec                           &x,
                       const Vec                           &H,
                       const unsigned int                   n_contacts,
                       const unsigned int                   d,
                       std::vector<unsigned int>           &involved)
      {
        involved.clear();
        for (unsigned int c = 0; c < n_contacts; ++c)
          if (!x.segment(c * d, d).allFinite() ||
              (H.size() >= (c + 1) * d && !H.segment(c * d, d).allFinite()))
            involved.push_back(c);
        if (!involved.empty())
          return "; non-finite at " + pair_list_text(involved);

        const unsigned int w =
          std::min<unsigned int>(window,
                                 static_cast<unsigned int>(sets.size()));
        if (w >= 4)
          {
            std::vector<std::vector<int>> last(sets.end() - w, sets.end());
            std::vector<std::vector<int>> distinct = last;
            std::sort(distinct.begin(), distinct.end());
            distinct.erase(std::unique(distinct.begin(), distinct.end()),
                           distinct.end());
            if (distinct.size() >= 2 && 2 * distinct.size() <= w)
              {
                for (unsigned int c = 0; c < n_contacts; ++c)
                  for (const auto &set : last)
                    if (c < set.size() && set[c] != last.front()[c])
                      {
                        involved.push_back(c);
                        break;
                      }
                return "; cycling between " + std::to_string(distinct.size()) +
                       " active sets in the last " + std::to_string(w) +
                       " iterations, changing the state of " +
                       pair_list_text(involved);
              }
          }
        if (H.size() < n_contacts * d || n_contacts == 0)
          return "";
        std::vector<unsigned int> order(n_contacts);
        for (unsigned int c = 0; c < n_contacts; ++c)
          order[c] = c;
        const unsigned int k = std::min(3u, n_contacts);
        std::partial_sort(order.begin(),
                          order.begin() + k,
                          order.end(),
                          [&](const unsigned int a, const unsigned int b) {
                            return H.segment(a * d, d).norm() >
                                   H.segment(b * d, d).norm();
                          });
        involved.assign(order.begin(), order.begin() + k);
        return "; largest residual at " + pair_list_text(involved);
      }



      struct PhaseOutcome
      {
        bool        converged = false;
        std::string reason;
      };



      class Driver
      {
      public:
        Driver(const ContactProblem          &original,
               const BNewtonSolver::Settings &settings,
               BNewtonSolver::Result         &result)
          : original(original)
          , settings(settings)
          , result(result)
          , start(std::chrono::steady_clock::now())
          , m(original.n_rows())
          , na(original.n_alpha())
          , r_factor(settings.r_factor)
        {
          out = settings.log_stream ? settings.log_stream : &std::cout;
        }

        bool
        out_of_time() const
        {
          if (settings.max_wall_seconds <= 0.)
            return false;
          const double elapsed = std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - start)
                                   .count();
          return elapsed > settings.max_wall_seconds;
        }

        bool
        out_of_iterations() const
        {
          return result.iterations >= settings.max_iterations;
        }

        // Record x as a candidate for the returned iterate (original
        // problem only).
        void
        offer_best(const Vec &x, const double err, const double eq_err)
        {
          const double score = std::max(err, eq_err);
          if (!std::isfinite(score))
            return;
          if (!have_best || score < best_score)
            {
              have_best  = true;
              best_score = score;
              best_x     = x;
            }
        }

        PhaseOutcome
        newton(const ContactProblem &problem,
               const FrictionRadius  radius,
               Vec                  &x,
               const double          tolerance,
               const std::string    &phase,
               const bool            on_original,
               const unsigned int    budget);

        void
        log_record(const BNewtonSolver::IterationRecord &rec)
        {
          if (!settings.log)
            return;
          rec.print(*out);
        }

        const ContactProblem                 &original;
        const BNewtonSolver::Settings        &settings;
        BNewtonSolver::Result                &result;
        std::chrono::steady_clock::time_point start;
        const unsigned int                    m, na;
        /// The factor c of r in use (Settings::r_factor, then 1 after the
        /// phase that resets it).
        double        r_factor;
        std::ostream *out;
        bool          have_best  = false;
        double        best_score = 0.;
        /// Iterations whose Newton matrix was singular (Levenberg-Marquardt
        /// steps).
        unsigned int singular_iterations = 0;
        Vec          best_x;
        Vec          converged_x;
      };



      PhaseOutcome
      Driver::newton(const ContactProblem &problem,
                     const FrictionRadius  radius,
                     Vec                  &x,
                     const double          tolerance,
                     const std::string    &phase,
                     const bool            on_original,
                     const unsigned int    budget)
      {
        const Weights w = pair_weights(problem, r_factor);
        const System  sys(problem, w, radius, settings);
        const double  sigma = settings.armijo_sigma;
        const double  beta  = settings.armijo_beta;

        std::deque<double>  theta_memory;
        std::vector<Branch> branches;
        Vec                 H, H_trial;
        double              best_theta    = std::numeric_limits<double>::max();
        unsigned int        last_progress = 0;
        unsigned int        local_it      = 0;
        unsigned int        singular_streak = 0;
        double              last_theta      = 0.;

        // The active set of every iteration of this phase, and how a
        // failure is reported: the iteration, and the pairs involved.
        std::vector<std::vector<int>> sets;
        const auto                    fail = [&](const std::string &what) {
          const std::string pairs =
            describe_failure(sets,
                             std::max(4u, settings.stall_iterations),
                             x,
                             H,
                             problem.n_contacts,
                             problem.n_components,
                             result.pairs_involved);
          return PhaseOutcome{false,
                              what + " at iteration " +
                                std::to_string(result.iterations) + pairs};
        };

        Vec u = sys.displacement(x);
        sys.residual(x, u, H, &branches);
        for (;;)
          {
            sets.push_back(active_set(branches));
            if (sets.size() > std::max(4u, settings.stall_iterations))
              sets.erase(sets.begin());
            const double theta = 0.5 * H.squaredNorm();
            if (!std::isfinite(theta) || !x.allFinite())
              return fail("non-finite values (NaN/inf) in H");
            double err, balanced, eq_err;
            // The FCLIB error may be out of reach in floating point when
            // forces and displacements have very different scales: accept
            // the balanced error alone once Newton stops converging
            // quadratically (|H| decreased less than 2x in the last step).
            const bool at_floor = local_it > 0 && theta > 0.25 * last_theta;
            last_theta          = theta;
            const bool done     = stopping_test(problem,
                                            x,
                                            u,
                                            tolerance,
                                            err,
                                            balanced,
                                            eq_err,
                                            at_floor);
            if (on_original)
              offer_best(x, balanced, eq_err);

            BNewtonSolver::IterationRecord rec;
            rec.phase             = phase;
            rec.h_norm            = std::sqrt(2. * theta);
            rec.residual          = err;
            rec.balanced_residual = balanced;
            count_status(branches, rec.n_open, rec.n_stick, rec.n_slip);

            if (done)
              {
                if (on_original)
                  converged_x = x;
                return {true, "converged"};
              }
            if (local_it >= budget || out_of_iterations())
              return fail("iteration limit");
            if (out_of_time())
              return fail("time limit");
            if (theta < best_theta * (1. - 1e-3))
              {
                best_theta    = theta;
                last_progress = local_it;
              }
            else if (local_it - last_progress >= settings.stall_iterations)
              return fail("stall (no decrease of |H| in " +
                          std::to_string(settings.stall_iterations) +
                          " iterations)");

            ++local_it;
            ++result.iterations;
            rec.iteration = result.iterations;

            // --- direction
            sys.apply_floating_tie_rule(x, u, branches);
            const NewtonMatrix J(sys, branches, settings.use_symmetry);
            rec.n_reduced = J.n_reduced();
            // Levenberg-Marquardt parameter relative to max diag J^T J:
            // the square of the relative residual (Yamashita and
            // Fukushima: fast local convergence without a nonsingular
            // Newton matrix, the rigid stacks of FCLIB), between 1e-10
            // far from the solution and 1e-14, below which it would sink
            // under the rounding of J^T J and leave its null space to
            // noise.
            const double lm_relative =
              std::isfinite(err) ? std::clamp(err * err, 1e-14, 1e-10) : 1e-10;
            // After two singular Newton matrices in a row (a hyperstatic
            // stack of rigid bodies: every iteration's, KaplasTower's 19)
            // the LU is tried only every fifth iteration: its failure costs
            // as much as the Levenberg-Marquardt step itself.
            const bool try_lu = singular_streak < 2 || local_it % 5 == 0;
            Vec        dx     = J.direction(H, rec.note, lm_relative, try_lu);
            if (rec.note.find("lm") != std::string::npos)
              {
                ++singular_iterations;
                ++singular_streak;
              }
            else
              singular_streak = 0;

            const Vec grad          = J.apply_transpose(H);
            double    slope         = grad.dot(J.apply(dx));
            bool      gradient_step = false;
            if (!dx.allFinite() || !(slope < -1e-8 * grad.norm() * dx.norm()))
              {
                dx            = -grad;
                slope         = -grad.squaredNorm();
                gradient_step = true;
                rec.note += "gradient ";
              }

            // --- line search (non-monotone Armijo)
            theta_memory.push_back(theta);
            while (theta_memory.size() >
                   std::max(1u, settings.nonmonotone_memory))
              theta_memory.pop_front();
            const double theta_ref =
              *std::max_element(theta_memory.begin(), theta_memory.end());

            bool   accepted = false;
            double step     = 0.;
            for (int attempt = 0; attempt < 2 && !accepted; ++attempt)
              {
                Vec du = sys.W_times(dx.head(m));
                if (na > 0)
                  du += problem.G * dx.tail(na);
                double t = 1., best_t = 0.,
                       best_trial = std::numeric_limits<double>::max();
                while (t >= settings.min_step)
                  {
                    const Vec xt = x + t * dx;
                    const Vec ut = u + t * du;
                    sys.residual(xt, ut, H_trial, nullptr);
                    const double th = 0.5 * H_trial.squaredNorm();
                    if (std::isfinite(th) && th < best_trial)
                      {
                        best_trial = th;
                        best_t     = t;
                      }
                    if (std::isfinite(th) &&
                        th <= theta_ref + sigma * t * slope)
                      {
                        accepted = true;
                        step     = t;
                        break;
                      }
                    t *= beta;
                  }
                if (!accepted && best_t > 0. && best_trial < theta)
                  {
                    accepted = true;
                    step     = best_t;
                    rec.note += "best-trial ";
                  }
                if (!accepted && !gradient_step)
                  {
                    dx            = -grad;
                    slope         = -grad.squaredNorm();
                    gradient_step = true;
                    rec.note += "gradient ";
                  }
                else
                  break;
              }
            rec.step = step;
            result.history.push_back(rec);
            log_record(rec);
            if (!accepted)
              return fail("line-search failure (no decrease along the "
                          "Newton and the steepest-descent directions)");

            x += step * dx;
            u = sys.displacement(x);
            sys.residual(x, u, H, &branches);
          }
      }

    } // namespace



    BNewtonSolver::BNewtonSolver(const Settings &settings)
      : settings(settings)
    {
      AssertThrow(settings.tolerance > 0.,
                  dealii::ExcMessage("BNewtonSolver: tolerance must be > 0"));
      AssertThrow(settings.armijo_sigma > 0. && settings.armijo_sigma < 0.5,
                  dealii::ExcMessage(
                    "BNewtonSolver: armijo_sigma must be in (0, 1/2)"));
      AssertThrow(settings.armijo_beta > 0. && settings.armijo_beta < 1.,
                  dealii::ExcMessage(
                    "BNewtonSolver: armijo_beta must be in (0, 1)"));
      AssertThrow(settings.min_step > 0. && settings.min_step < 1.,
                  dealii::ExcMessage(
                    "BNewtonSolver: min_step must be in (0, 1)"));
      AssertThrow(settings.r_factor > 0.,
                  dealii::ExcMessage("BNewtonSolver: r_factor must be > 0"));
    }



    std::string
    BNewtonSolver::name() const
    {
      return "bde";
    }



    const BNewtonSolver::Settings &
    BNewtonSolver::get_settings() const
    {
      return settings;
    }



    BNewtonSolver::Result
    BNewtonSolver::solve(const ContactProblem &problem) const
    {
      return solve(problem, Eigen::VectorXd(), Eigen::VectorXd());
    }



    BNewtonSolver::Result
    BNewtonSolver::solve(const ContactProblem  &problem,
                         const Eigen::VectorXd &p0,
                         const Eigen::VectorXd &alpha0) const
    {
      problem.check_consistency();
      const unsigned int m = problem.n_rows(), na = problem.n_alpha();
      AssertThrow(p0.size() == 0 || p0.size() == m,
                  dealii::ExcMessage("BNewtonSolver::solve: p0 has size " +
                                     std::to_string(p0.size()) + ", expected " +
                                     std::to_string(m)));
      AssertThrow(alpha0.size() == 0 || alpha0.size() == na,
                  dealii::ExcMessage("BNewtonSolver::solve: alpha0 has size " +
                                     std::to_string(alpha0.size()) +
                                     ", expected " + std::to_string(na)));
      Result result;
      Vec    x(m + na);
      x.head(m) = p0.size() > 0 ? p0 : Vec::Zero(m);
      if (na > 0)
        {
          if (alpha0.size() > 0)
            x.tail(na) = alpha0;
          else
            {
              // No pair closes along -b (e.g. b = 0): start from zero.
              try
                {
                  x.tail(na) = touching_alpha(problem);
                }
              catch (const std::exception &)
                {
                  x.tail(na).setZero();
                }
            }
        }

      Driver driver(problem, settings, result);
      if (settings.log)
        *driver.out
          << "B-Newton on " << (problem.name.empty() ? "problem" : problem.name)
          << ": " << problem.n_contacts << " contacts, " << problem.n_components
          << " components, " << na << " floating modes\n"
          << "   it     phase        |H|    residual    balanced        step"
             "  open stick  slip   red note\n";

      PhaseOutcome outcome;
      std::string  reasons;
      if (m + na == 0)
        outcome.converged = true;
      else
        {
          // Phase 1: Newton with the chosen radius.
          const FrictionRadius radius = settings.radius;
          Vec                  x1     = x;
          outcome                     = driver.newton(problem,
                                  radius,
                                  x1,
                                  settings.tolerance,
                                  phase_name("newton", radius),
                                  true,
                                  settings.max_iterations);
          reasons = phase_name("newton", radius) + ": " + outcome.reason;
          // Phase 2: the other radius, from the best iterate.
          if (!outcome.converged && problem.has_friction() &&
              settings.switch_radius && !driver.out_of_iterations() &&
              !driver.out_of_time())
            {
              Vec x2  = driver.have_best ? driver.best_x : x;
              outcome = driver.newton(problem,
                                      other(radius),
                                      x2,
                                      settings.tolerance,
                                      phase_name("newton", other(radius)),
                                      true,
                                      settings.max_iterations);
              reasons += "; " + phase_name("newton", other(radius)) + ": " +
                         outcome.reason;
            }
          // Phase 2b: r from the flexibility alone (c = 1), when the
          // chosen factor is far from it. The solution does not depend on
          // r, but the merit |H|^2 weighs the displacement rows by r: with
          // c = 1e-4 (B1) the line search hardly sees the penetration and
          // the active sets cycle; c = 1 balances force and displacement.
          if (!outcome.converged && settings.switch_radius &&
              std::abs(std::log10(settings.r_factor)) > 1. &&
              !driver.out_of_iterations() && !driver.out_of_time())
            {
              driver.r_factor = 1.;
              Vec x3          = driver.have_best ? driver.best_x : x;
              outcome         = driver.newton(problem,
                                      radius,
                                      x3,
                                      settings.tolerance,
                                      phase_name("newton-r1", radius),
                                      true,
                                      settings.max_iterations);
              reasons +=
                "; " + phase_name("newton-r1", radius) + ": " + outcome.reason;
            }
          // Phase 3: proximal point.
          if (!outcome.converged && settings.proximal &&
              !driver.out_of_iterations() && !driver.out_of_time())
            {
              Vec          xk = driver.have_best ? driver.best_x : x;
              const double max_diag =
                m > 0 ? std::max(problem.W.diagonal().maxCoeff(), 0.) : 0.;
              const double   eps_ref = max_diag > 0. ? max_diag : 1.;
              double         eps     = eps_ref;
              double         err    = driver.have_best ? driver.best_score : 1.;
              unsigned int   n_fail = 0, n_idle = 0;
              std::string    prox_reason = "iteration limit";
              ContactProblem sub         = problem;
              while (!driver.out_of_iterations() && !driver.out_of_time())
                {
                  sub.W = problem.W;
                  sub.W.diagonal().array() += eps;
                  sub.q                  = problem.q - eps * xk.head(m);
                  const double inner_tol = std::max(0.1 * settings.tolerance,
                                                    std::min(1e-6, 0.1 * err));
                  Vec          xi        = xk;
                  PhaseOutcome in        = driver.newton(sub,
                                                  radius,
                                                  xi,
                                                  inner_tol,
                                                  phase_name("prox", radius),
                                                  false,
                                                  50);
                  if (!in.converged && !driver.out_of_iterations())
                    {
                      xi = xk;
                      in = driver.newton(sub,
                                         other(radius),
                                         xi,
                                         inner_tol,
                                         phase_name("prox", other(radius)),
                                         false,
                                         50);
                    }
                  if (in.converged && xi == xk)
                    {
                      // The subproblem is solved where it starts (its
                      // relative residual is measured against q - eps x_k,
                      // which a large eps makes large): a smaller eps
                      // brings it nearer the original problem; without
                      // that the loop would turn without iterating.
                      eps = std::max(eps * 0.1, 1e-12 * eps_ref);
                      if (++n_idle > 12)
                        {
                          prox_reason = "stall (every proximal subproblem "
                                        "is solved at the current iterate)";
                          break;
                        }
                    }
                  else if (in.converged)
                    {
                      n_idle = 0;
                      xk     = xi;
                      const Vec uk =
                        problem.relative_displacement(xk.head(m), xk.tail(na));
                      double       e_fclib, e_bal, eq;
                      const bool   done = stopping_test(problem,
                                                      xk,
                                                      uk,
                                                      settings.tolerance,
                                                      e_fclib,
                                                      e_bal,
                                                      eq,
                                                      false);
                      const double e    = e_bal;
                      driver.offer_best(xk, e, eq);
                      if (done)
                        {
                          driver.converged_x = xk;
                          outcome.converged  = true;
                          prox_reason        = "converged";
                          break;
                        }
                      if (e < 0.5 * err)
                        eps = std::max(eps * 0.1, 1e-12 * eps_ref);
                      err    = std::min(err, e);
                      n_fail = 0;
                    }
                  else
                    {
                      eps *= 10.;
                      if (++n_fail > 6 || eps > 1e12 * eps_ref)
                        {
                          prox_reason =
                            "stall (inner solves fail: " + in.reason + ")";
                          break;
                        }
                    }
                }
              if (!outcome.converged)
                outcome.reason = prox_reason;
              reasons += "; proximal: " + prox_reason;
            }
        }

      // The returned iterate: the converged one, else the best one seen on
      // the original problem.
      Vec xr   = outcome.converged ? driver.converged_x :
                 driver.have_best  ? driver.best_x :
                                     x;
      result.p = xr.head(m);
      if (na > 0)
        result.alpha = xr.tail(na);
      result.u          = problem.relative_displacement(result.p, result.alpha);
      const bool strict = stopping_test(problem,
                                        xr,
                                        result.u,
                                        settings.tolerance,
                                        result.residual,
                                        result.balanced_residual,
                                        result.equilibrium_residual,
                                        false);
      result.converged  = (strict || outcome.converged) &&
                         result.p.allFinite() &&
                         result.balanced_residual <= settings.tolerance;
      if (result.converged)
        result.diagnosis = "converged (" + reasons + ")";
      else if (!result.p.allFinite() || !std::isfinite(result.residual))
        result.diagnosis = "non-finite result (" + reasons + ")";
      else
        result.diagnosis =
          "not converged: " + outcome.reason + " [" + reasons + "]";
      if (result.converged)
        result.pairs_involved.clear();
      else if (driver.singular_iterations > 0)
        result.diagnosis +=
          "; the Newton matrix was singular in " +
          std::to_string(driver.singular_iterations) + " of " +
          std::to_string(result.iterations) +
          " iterations (Levenberg-Marquardt steps): redundant pairs, or a "
          "body held only through contact";

      // Final per-contact status at (p, u), with the phase-1 radius.
      {
        const Weights       w = pair_weights(problem, settings.r_factor);
        const System        sys(problem, w, settings.radius, settings, false);
        std::vector<Branch> branches;
        Vec                 H;
        if (m + na > 0)
          sys.residual(xr, result.u, H, &branches);
        result.status.clear();
        for (const Branch &br : branches)
          result.status.push_back(br.status);
        count_status(branches, result.n_open, result.n_stick, result.n_slip);
      }
      if (settings.log)
        *driver.out << result.summary() << '\n';
      return result;
    }

  } // namespace contact
} // namespace igabde
