#include <igabde/base/utilities.h>
#include <igabde/linear_algebra/dense_lu.h>

#include <deal.II/lac/lapack_templates.h>

#include <algorithm>
#include <cmath>

namespace igabde
{
  namespace linear_algebra
  {
    using dealii::types::blas_int;

    DenseLU::DenseLU(Eigen::MatrixXd A)
      : LU(std::move(A))
      , pivots(LU.rows())
    {
      const blas_int n = LU.rows();
      for (blas_int j = 0; j < n; ++j)
        anorm = std::max(anorm, LU.col(j).cwiseAbs().sum());
      if (n == 0)
        return;
      if (n > small_size)
        {
          const base::SerialDenseAlgebra serial(n);
          dealii::getrf(&n, &n, LU.data(), &n, pivots.data(), &info);
          return;
        }
      const Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXd>> lu(LU);
      const auto &indices = lu.permutationP().indices();
      for (blas_int i = 0; i < n; ++i)
        pivots[indices[i]] = i;
      // dgetrf's info: the first exactly zero pivot (Eigen leaves its
      // column unscaled and goes on).
      for (blas_int i = 0; i < n && info == 0; ++i)
        if (LU(i, i) == 0.)
          info = i + 1;
    }



    double
    DenseLU::rcond() const
    {
      using Vec            = Eigen::VectorXd;
      const Eigen::Index n = LU.rows();
      if (n == 0 || anorm == 0. || info != 0)
        return 0.;
      // The row permutation leaves the 1-norm alone: the estimate works
      // with L U alone.
      const auto solve = [&](Vec &x) {
        LU.triangularView<Eigen::UnitLower>().solveInPlace(x);
        LU.triangularView<Eigen::Upper>().solveInPlace(x);
      };
      const auto solve_transposed = [&](Vec &x) {
        LU.transpose().triangularView<Eigen::Lower>().solveInPlace(x);
        LU.transpose().triangularView<Eigen::UnitUpper>().solveInPlace(x);
      };
      const auto sign = [](const double v) {
        return v >= 0. ? 1. : -1.;
      };
      Vec x = Vec::Constant(n, 1. / n);
      solve(x);
      double est = x.lpNorm<1>();
      if (n > 1)
        {
          Vec isgn = x.unaryExpr(sign);
          x        = isgn;
          solve_transposed(x);
          Eigen::Index j;
          x.cwiseAbs().maxCoeff(&j);
          for (unsigned int iter = 2;; ++iter)
            {
              x.setZero();
              x[j] = 1.;
              solve(x);
              const double old = est;
              est              = x.lpNorm<1>();
              const Vec s      = x.unaryExpr(sign);
              if (s == isgn || est <= old)
                break;
              isgn = s;
              x    = s;
              solve_transposed(x);
              const Eigen::Index last = j;
              x.cwiseAbs().maxCoeff(&j);
              if (x[last] == std::abs(x[j]) || iter >= 5)
                break;
            }
          for (Eigen::Index i = 0; i < n; ++i)
            x[i] = (i % 2 == 0 ? 1. : -1.) * (1. + double(i) / (n - 1));
          solve(x);
          est = std::max(est, 2. * x.lpNorm<1>() / (3. * n));
        }
      return est > 0. && std::isfinite(est) ? (1. / est) / anorm : 0.;
    }



    bool
    DenseLU::solve_in_place(Eigen::VectorXd &b) const
    {
      const blas_int n = LU.rows();
      if (info != 0 || b.size() != n)
        return false;
      if (n == 0)
        return true;
      if (n <= small_size)
        {
          Eigen::VectorXd x(n);
          for (blas_int i = 0; i < n; ++i)
            x[i] = b[pivots[i]];
          LU.triangularView<Eigen::UnitLower>().solveInPlace(x);
          LU.triangularView<Eigen::Upper>().solveInPlace(x);
          b = std::move(x);
          return b.allFinite();
        }
      const blas_int nrhs   = 1;
      blas_int       status = 0;
      dealii::getrs("N",
                    &n,
                    &nrhs,
                    LU.data(),
                    &n,
                    pivots.data(),
                    b.data(),
                    &n,
                    &status);
      return status == 0 && b.allFinite();
    }
  } // namespace linear_algebra
} // namespace igabde
