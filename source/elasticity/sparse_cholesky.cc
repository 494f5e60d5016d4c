#include <igabde/elasticity/sparse_cholesky.h>

#include <deal.II/base/exceptions.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <dmumps_c.h>
#include <mpi.h>
#include <string>

namespace igabde
{
  namespace elasticity
  {
    namespace
    {
      // MUMPS' control arrays are documented 1-based.
      constexpr int
      icntl(const int i)
      {
        return i - 1;
      }
    } // namespace

    struct SparseCholesky::Data
    {
      DMUMPS_STRUC_C id{};
      bool           mumps_alive = false;

      /// Global index of each free unknown (MUMPS' numbering minus one).
      std::vector<types::global_dof_index> free_dofs;
      /// MUMPS' 1-based index of each global unknown, 0 when eliminated.
      std::vector<MUMPS_INT> reduced_index;
      /// Interface unknowns (global), in the order of S.
      std::vector<types::global_dof_index> interface;
      /// Lower triangle of the free block, 1-based coordinates.
      std::vector<MUMPS_INT> rows, cols;
      std::vector<double>    values;

      FullMatrix<double>          schur;
      Eigen::LLT<Eigen::MatrixXd> schur_cholesky;
      /// Every free unknown is an interface unknown: S is the free block and
      /// MUMPS is not used.
      bool dense_only = false;

      /// Throws with MUMPS' error codes when the last call failed.
      void
      check(const int job) const
      {
        AssertThrow(id.infog[0] >= 0,
                    ExcMessage("MUMPS (job " + std::to_string(job) +
                               ") failed with INFOG(1) = " +
                               std::to_string(id.infog[0]) +
                               ", INFOG(2) = " + std::to_string(id.infog[1]) +
                               (id.infog[0] == -10 ?
                                  ": the stiffness is singular (a body is "
                                  "not held against a rigid motion)" :
                                  "")));
      }

      void
      call(const int job)
      {
        id.job = job;
        dmumps_c(&id);
        check(job);
      }

      void
      release()
      {
        if (mumps_alive)
          {
            id.job = -2;
            dmumps_c(&id);
            mumps_alive = false;
          }
      }
    };



    SparseCholesky::SparseCholesky()
      : data(std::make_unique<Data>())
    {}



    SparseCholesky::~SparseCholesky()
    {
      data->release();
    }



    void
    SparseCholesky::initialize(
      const SparseMatrix<double>                 &matrix,
      const std::vector<bool>                    &eliminated,
      const std::vector<types::global_dof_index> &interface)
    {
      Data &d = *data;
      d.release();
      const types::global_dof_index n = matrix.m();
      AssertDimension(eliminated.size(), n);

      d.free_dofs.clear();
      d.reduced_index.assign(n, 0);
      for (types::global_dof_index i = 0; i < n; ++i)
        if (!eliminated[i])
          {
            d.free_dofs.push_back(i);
            d.reduced_index[i] = d.free_dofs.size();
          }
      d.interface = interface;
      for (const auto i : interface)
        AssertThrow(i < n && !eliminated[i],
                    ExcMessage("SparseCholesky: interface unknown " +
                               std::to_string(i) +
                               " is out of range or eliminated."));
      const unsigned int n_s = interface.size();

      d.dense_only = (n_s > 0 && n_s == d.free_dofs.size());
      if (d.dense_only)
        {
          // Nothing to eliminate: S is the free block itself.
          d.schur.reinit(n_s, n_s);
          for (unsigned int a = 0; a < n_s; ++a)
            for (unsigned int b = 0; b < n_s; ++b)
              d.schur(a, b) = matrix.el(interface[a], interface[b]);
        }
      else
        {
          d.rows.clear();
          d.cols.clear();
          d.values.clear();
          for (types::global_dof_index row = 0; row < n; ++row)
            if (d.reduced_index[row] > 0)
              for (auto entry = matrix.begin(row); entry != matrix.end(row);
                   ++entry)
                if (entry->column() <= row &&
                    d.reduced_index[entry->column()] > 0 &&
                    entry->value() != 0.)
                  {
                    d.rows.push_back(d.reduced_index[row]);
                    d.cols.push_back(d.reduced_index[entry->column()]);
                    d.values.push_back(entry->value());
                  }

          int initialized = 0;
          MPI_Initialized(&initialized);
          AssertThrow(initialized,
                      ExcMessage("SparseCholesky needs MPI to be initialised "
                                 "(MUMPS runs on MPI_COMM_SELF)."));
          d.id     = DMUMPS_STRUC_C{};
          d.id.par = 1;
          d.id.sym = 1; // symmetric positive definite: LDL^T
          d.id.comm_fortran =
            static_cast<MUMPS_INT>(MPI_Comm_c2f(MPI_COMM_SELF));
          d.call(-1);
          d.mumps_alive = true;
          // Silent; automatic ordering.
          d.id.icntl[icntl(1)] = -1;
          d.id.icntl[icntl(2)] = -1;
          d.id.icntl[icntl(3)] = -1;
          d.id.icntl[icntl(4)] = 0;

          d.id.n   = d.free_dofs.size();
          d.id.nnz = d.values.size();
          d.id.irn = d.rows.data();
          d.id.jcn = d.cols.data();
          d.id.a   = d.values.data();

          std::vector<MUMPS_INT> schur_list(n_s);
          if (n_s > 0)
            {
              for (unsigned int a = 0; a < n_s; ++a)
                schur_list[a] = d.reduced_index[interface[a]];
              d.schur.reinit(n_s, n_s);
              d.id.icntl[icntl(19)] = 1; // centralised on the host
              d.id.size_schur       = n_s;
              d.id.listvar_schur    = schur_list.data();
              d.id.schur_lld        = n_s;
            }
          std::vector<double> schur_values(std::size_t(n_s) * n_s, 0.);
          d.id.schur = (n_s > 0 ? schur_values.data() : nullptr);

          // Analysis and factorisation; more workspace if MUMPS asks.
          d.id.job = 4;
          for (unsigned int attempt = 0;; ++attempt)
            {
              dmumps_c(&d.id);
              if ((d.id.infog[0] == -8 || d.id.infog[0] == -9) && attempt < 4)
                {
                  d.id.icntl[icntl(14)] =
                    std::max(2 * d.id.icntl[icntl(14)], 40);
                  continue;
                }
              break;
            }
          d.check(4);
          d.id.listvar_schur = nullptr;
          d.id.schur         = nullptr;

          // ICNTL(19) = 1 with a symmetric matrix: the lower triangle,
          // stored by rows (row a, column b <= a at a * n_s + b); what the
          // upper part holds is not specified.
          for (unsigned int a = 0; a < n_s; ++a)
            for (unsigned int b = 0; b <= a; ++b)
              {
                const double v = schur_values[std::size_t(a) * n_s + b];
                d.schur(a, b)  = v;
                d.schur(b, a)  = v;
              }
        }

      if (n_s > 0)
        {
          Eigen::MatrixXd s(n_s, n_s);
          for (unsigned int a = 0; a < n_s; ++a)
            for (unsigned int b = 0; b < n_s; ++b)
              s(a, b) = d.schur(a, b);
          d.schur_cholesky.compute(s);
          AssertThrow(d.schur_cholesky.info() == Eigen::Success,
                      ExcMessage("The Schur complement on the contact face is "
                                 "not positive definite: a body is not held "
                                 "against a rigid motion."));
        }
    }



    unsigned int
    SparseCholesky::n_interface() const
    {
      return data->interface.size();
    }



    const std::vector<types::global_dof_index> &
    SparseCholesky::interface_dofs() const
    {
      return data->interface;
    }



    const FullMatrix<double> &
    SparseCholesky::schur_complement() const
    {
      return data->schur;
    }



    FullMatrix<double>
    SparseCholesky::interface_flexibility(const FullMatrix<double> &c) const
    {
      const unsigned int n_s = n_interface();
      AssertDimension(c.m(), n_s);
      Eigen::MatrixXd C(n_s, c.n());
      for (unsigned int a = 0; a < n_s; ++a)
        for (unsigned int j = 0; j < c.n(); ++j)
          C(a, j) = c(a, j);
      // C^T S^{-1} C = Y^T Y with Y = L^{-1} C (S = L L^T): one triangular
      // block solve and one symmetric rank-k product.
      const Eigen::MatrixXd Y = data->schur_cholesky.matrixL().solve(C);
      Eigen::MatrixXd       F(c.n(), c.n());
      F.setZero();
      F.selfadjointView<Eigen::Lower>().rankUpdate(Y.transpose());
      FullMatrix<double> result(c.n(), c.n());
      for (unsigned int i = 0; i < c.n(); ++i)
        for (unsigned int j = 0; j <= i; ++j)
          result(i, j) = result(j, i) = F(i, j);
      return result;
    }



    void
    SparseCholesky::solve(std::vector<Vector<double>> &rhs_and_solutions) const
    {
      Data              &d    = *data;
      const unsigned int nrhs = rhs_and_solutions.size();
      if (nrhs == 0)
        return;
      const unsigned int n_free = d.free_dofs.size();
      const unsigned int n_s    = d.interface.size();

      if (d.dense_only)
        {
          Eigen::MatrixXd b(n_s, nrhs);
          for (unsigned int k = 0; k < nrhs; ++k)
            for (unsigned int a = 0; a < n_s; ++a)
              b(a, k) = rhs_and_solutions[k][d.interface[a]];
          const Eigen::MatrixXd x = d.schur_cholesky.solve(b);
          for (unsigned int k = 0; k < nrhs; ++k)
            {
              rhs_and_solutions[k] = 0.;
              for (unsigned int a = 0; a < n_s; ++a)
                rhs_and_solutions[k][d.interface[a]] = x(a, k);
            }
          return;
        }

      std::vector<double> rhs(std::size_t(n_free) * nrhs);
      for (unsigned int k = 0; k < nrhs; ++k)
        {
          AssertDimension(rhs_and_solutions[k].size(), d.reduced_index.size());
          for (unsigned int i = 0; i < n_free; ++i)
            rhs[std::size_t(k) * n_free + i] =
              rhs_and_solutions[k][d.free_dofs[i]];
        }
      d.id.rhs  = rhs.data();
      d.id.nrhs = nrhs;
      d.id.lrhs = n_free;
      if (n_s == 0)
        {
          d.id.icntl[icntl(26)] = 0;
          d.call(3);
        }
      else
        {
          // Reduction onto the interface, dense solve with S, expansion.
          std::vector<double> reduced(std::size_t(n_s) * nrhs);
          d.id.redrhs           = reduced.data();
          d.id.lredrhs          = n_s;
          d.id.icntl[icntl(26)] = 1;
          d.call(3);
          Eigen::Map<Eigen::MatrixXd> y(reduced.data(), n_s, nrhs);
          y                     = d.schur_cholesky.solve(Eigen::MatrixXd(y));
          d.id.icntl[icntl(26)] = 2;
          d.call(3);
          d.id.icntl[icntl(26)] = 0;
          d.id.redrhs           = nullptr;
        }
      d.id.rhs = nullptr;
      for (unsigned int k = 0; k < nrhs; ++k)
        {
          rhs_and_solutions[k] = 0.;
          for (unsigned int i = 0; i < n_free; ++i)
            rhs_and_solutions[k][d.free_dofs[i]] =
              rhs[std::size_t(k) * n_free + i];
        }
    }



    double
    SparseCholesky::factor_entries() const
    {
      if (!data->mumps_alive)
        return 0.5 * n_interface() * (n_interface() + 1.);
      const MUMPS_INT e = data->id.infog[28];
      return (e >= 0 ? double(e) : -1e6 * double(e));
    }



    double
    SparseCholesky::factor_flops() const
    {
      return (data->mumps_alive ? data->id.rinfog[2] : 0.);
    }
  } // namespace elasticity
} // namespace igabde
