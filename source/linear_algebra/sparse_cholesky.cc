#include <igabde/base/memory_record.h>
#include <igabde/linear_algebra/sparse_cholesky.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <deal.II/lac/lapack_templates.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <dmumps_c.h>
#include <iomanip>
#include <metis.h>
#include <mpi.h>
#include <mutex>
#include <numeric>
#include <ostream>
#include <sstream>
#include <string>
#include <thread>
#include <type_traits>

namespace igabde
{
  namespace linear_algebra
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

    std::vector<int>
    nested_dissection_order(const unsigned int               n,
                            const std::vector<std::size_t>  &row_start,
                            const std::vector<unsigned int> &columns,
                            const std::vector<int>          &schur_list)
    {
      std::vector<bool> in_schur(n, false);
      for (const int v : schur_list)
        in_schur[v - 1] = true;
      const auto same_row = [&](const unsigned int a, const unsigned int b) {
        return row_start[a + 1] - row_start[a] ==
                 row_start[b + 1] - row_start[b] &&
               std::equal(columns.begin() + row_start[a],
                          columns.begin() + row_start[a + 1],
                          columns.begin() + row_start[b]);
      };

      // Supervariables, numbered in increasing order of their unknowns.
      std::vector<int>          super(n, -1);
      std::vector<unsigned int> representative;
      std::vector<idx_t>        weight;
      for (unsigned int v = 0; v < n; ++v)
        if (!in_schur[v])
          {
            if (v > 0 && super[v - 1] >= 0 && same_row(v - 1, v))
              {
                super[v] = super[v - 1];
                ++weight.back();
              }
            else
              {
                super[v] = representative.size();
                representative.push_back(v);
                weight.push_back(1);
              }
          }
      const unsigned int n_super = representative.size();
      if (n_super == 0)
        return {};

      // Their graph: a row's columns are sorted and the supervariable
      // numbers grow with the unknowns, so repeats are adjacent.
      std::vector<idx_t> xadj(n_super + 1, 0), adjncy;
      adjncy.reserve(columns.size() / std::max<idx_t>(1, weight[0]) + 1);
      for (unsigned int s = 0; s < n_super; ++s)
        {
          const unsigned int v = representative[s];
          for (std::size_t k = row_start[v]; k < row_start[v + 1]; ++k)
            {
              const int t = super[columns[k]];
              if (t >= 0 && t != static_cast<int>(s) &&
                  (adjncy.size() == static_cast<std::size_t>(xadj[s]) ||
                   adjncy.back() != t))
                adjncy.push_back(t);
            }
          xadj[s + 1] = adjncy.size();
        }

      idx_t              n_vertices = n_super;
      std::vector<idx_t> perm(n_super), iperm(n_super);
      idx_t              options[METIS_NOPTIONS];
      METIS_SetDefaultOptions(options);
      options[METIS_OPTION_NUMBERING] = 0;
      if (METIS_NodeND(&n_vertices,
                       xadj.data(),
                       adjncy.data(),
                       weight.data(),
                       options,
                       perm.data(),
                       iperm.data()) != METIS_OK)
        return {};

      // Supervariables in METIS' order, each as a consecutive run.
      std::vector<int> first(n_super + 1, 0);
      for (unsigned int k = 0; k < n_super; ++k)
        first[k + 1] = first[k] + weight[perm[k]];
      std::vector<int> order(n, 0);
      for (unsigned int v = 0; v < n; ++v)
        if (super[v] >= 0)
          order[v] = ++first[iperm[super[v]]];
      int next = n - schur_list.size();
      for (const int v : schur_list)
        order[v - 1] = ++next;
      return order;
    }



    namespace
    {
      /**
       * Progress of one numerical factorisation, which MUMPS does in one
       * call: every 5 s a line on @p stream with the seconds so far and an
       * estimate of those left, from MUMPS' flop estimate of the analysis
       * (RINFOG(1)) and the rate of the longest factorisation this process
       * has finished; before the first, a default rate of numerical
       * factorisations that take seconds (doc/performance.md gives the
       * measurement it comes from). A factorisation under 5 s prints
       * nothing.
       */
      class FactorisationTicker
      {
      public:
        FactorisationTicker(std::ostream      *stream,
                            const std::string &label,
                            const double       estimated_flops)
          : start(std::chrono::steady_clock::now())
        {
          if (stream == nullptr || !(estimated_flops > 0.))
            return;
          const double rate = measured_rate.load();
          thread = std::thread([this, stream, label, estimated_flops, rate] {
            std::unique_lock<std::mutex> lock(mutex);
            const double                 estimate = estimated_flops / rate;
            while (!done.wait_for(lock, std::chrono::seconds(5), [this] {
              return finished;
            }))
              {
                const double       elapsed = seconds();
                std::ostringstream line;
                line << std::setprecision(3) << "  [progress] " << label
                     << ": factorising, " << elapsed << " s";
                if (elapsed < estimate)
                  line << ", about " << estimate - elapsed << " s left";
                else
                  line << ", past the estimate of " << estimate << " s";
                line << " (" << estimated_flops << " flops estimated, at "
                     << rate / 1e9 << " GFlop/s)";
                *stream << line.str() << std::endl;
              }
          });
        }

        /// Ends the progress lines; @p flops done teach the next estimate.
        void
        finish(const double flops)
        {
          const double elapsed = seconds();
          stop();
          // The longest factorisation so far sets the rate: short ones run
          // below the rate of large dense fronts.
          if (flops > 0. && elapsed > longest.load())
            {
              longest.store(elapsed);
              measured_rate.store(flops / elapsed);
            }
        }

        ~FactorisationTicker()
        {
          stop();
        }

      private:
        double
        seconds() const
        {
          return std::chrono::duration<double>(
                   std::chrono::steady_clock::now() - start)
            .count();
        }

        void
        stop()
        {
          if (!thread.joinable())
            return;
          {
            std::lock_guard<std::mutex> lock(mutex);
            finished = true;
          }
          done.notify_all();
          thread.join();
        }

        static std::atomic<double>                  measured_rate;
        static std::atomic<double>                  longest;
        const std::chrono::steady_clock::time_point start;
        std::mutex                                  mutex;
        std::condition_variable                     done;
        bool                                        finished = false;
        std::thread                                 thread;
      };

      std::atomic<double> FactorisationTicker::measured_rate{4e10};
      std::atomic<double> FactorisationTicker::longest{0.};
    } // namespace



    struct SparseCholesky::Data
    {
      DMUMPS_STRUC_C id{};
      bool           mumps_alive = false;
      /// The ranks that factorise together; the host is its rank 0.
      MPI_Comm communicator = MPI_COMM_SELF;
      /// Whether this rank is the host (holds matrix, vectors and S).
      bool host = true;
      /// Whether this rank took part in the factorisation (false after
      /// share() on a rank outside its communicator).
      bool member = true;
      /// Entries of the factor (MUMPS' count, or of S when dense only).
      double entries = 0.;
      /// MUMPS' flop count, kept by release().
      double flops = 0.;
      /// release() was called: no solves.
      bool released = false;
      /// Where the factorisation's progress lines go (the host's), and the
      /// name they give.
      std::ostream *progress = nullptr;
      std::string   label;

      /// Global index of each free unknown (MUMPS' numbering minus one).
      std::vector<types::global_dof_index> free_dofs;
      /// MUMPS' 1-based index of each global unknown, 0 when eliminated.
      std::vector<MUMPS_INT> reduced_index;
      /// Interface unknowns (global), in the order of S.
      std::vector<types::global_dof_index> interface;
      /// Lower triangle of the free block, 1-based coordinates.
      std::vector<MUMPS_INT> rows, cols;
      std::vector<double>    values;

      FullMatrix<double> schur;
      /// Cholesky factor L of S = L L^T (LAPACK, column-major, lower).
      std::vector<double> schur_factor;

      /// Overwrites the n_s x @p m column-major @p b with S^{-1} b.
      void
      solve_schur(double *b, const int m) const
      {
        const int n_s  = interface.size();
        int       info = 0;
        potrs("L", &n_s, &m, schur_factor.data(), &n_s, b, &n_s, &info);
        AssertThrow(info == 0, ExcMessage("LAPACK potrs failed."));
      }
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
      const std::vector<types::global_dof_index> &interface,
      const PivotOrder                            pivot_order,
      const MPI_Comm                              communicator,
      const bool                                  distributed_values,
      const std::function<void()>                &matrix_read)
    {
      Data &d = *data;
      d.release();
      d.communicator = communicator;
      d.host         = (Utilities::MPI::this_mpi_process(communicator) == 0);
      d.member       = true;
      d.released     = false;
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
          if (distributed_values)
            Utilities::MPI::sum(d.schur, communicator, d.schur);
          if (matrix_read)
            matrix_read();
        }
      else
        {
          // The free block in one pass over K's rows (deal.II stores a
          // row's diagonal first, the other columns ascending): its lower
          // triangle for MUMPS (1-based, nonzero values), and its pattern
          // (both triangles, sorted, 0-based) for the pivot order. Only
          // the host reads K (MUMPS' centralised input), unless every rank
          // holds a share of its values (MUMPS' distributed input: each
          // rank passes its entries, the host orders from the pattern).
          const SparsityPattern &pattern = matrix.get_sparsity_pattern();
          const unsigned int     n_free  = d.free_dofs.size();
          const bool             ordering =
            (pivot_order != PivotOrder::minimum_degree && n_s < n_free);
          const unsigned int n_read =
            (d.host || distributed_values ? n_free : 0);
          const bool  order_here = ordering && d.host;
          std::size_t n_entries  = 0;
          for (unsigned int r = 0; r < n_read; ++r)
            n_entries += pattern.row_length(d.free_dofs[r]);
          d.rows.clear();
          d.cols.clear();
          d.values.clear();
          // With distributed values a rank's entries are its share only.
          const std::size_t n_triplets =
            (n_entries / 2 + n_free) /
            (distributed_values ?
               Utilities::MPI::n_mpi_processes(communicator) :
               1u);
          d.rows.reserve(n_triplets);
          d.cols.reserve(n_triplets);
          d.values.reserve(n_triplets);
          std::vector<std::size_t>  row_start(order_here ? n_read + 1 : 0, 0);
          std::vector<unsigned int> columns;
          if (order_here)
            columns.reserve(n_entries);
          for (unsigned int r = 0; r < n_read; ++r)
            {
              const types::global_dof_index row       = d.free_dofs[r];
              const std::size_t             row_begin = columns.size();
              for (auto entry = matrix.begin(row); entry != matrix.end(row);
                   ++entry)
                {
                  const auto      column  = entry->column();
                  const MUMPS_INT reduced = d.reduced_index[column];
                  if (reduced == 0)
                    continue;
                  if (order_here)
                    columns.push_back(reduced - 1);
                  const double value = entry->value();
                  if (column <= row && value != 0.)
                    {
                      d.rows.push_back(r + 1);
                      d.cols.push_back(reduced);
                      d.values.push_back(value);
                    }
                }
              if (order_here)
                {
                  // The diagonal (first) to its place among the others.
                  const auto begin = columns.begin() + row_begin;
                  if (begin != columns.end() && *begin == r)
                    std::rotate(begin,
                                begin + 1,
                                std::upper_bound(begin + 1, columns.end(), r));
                  row_start[r + 1] = columns.size();
                }
            }

          int initialized = 0;
          MPI_Initialized(&initialized);
          AssertThrow(initialized,
                      ExcMessage("SparseCholesky needs MPI to be initialised "
                                 "(MUMPS runs on an MPI communicator)."));
          d.id     = DMUMPS_STRUC_C{};
          d.id.par = 1; // the host works too
          d.id.sym = 1; // symmetric positive definite: LDL^T
          d.id.comm_fortran =
            static_cast<MUMPS_INT>(MPI_Comm_c2f(communicator));
          d.call(-1);
          d.mumps_alive = true;
          // Silent; automatic ordering.
          d.id.icntl[icntl(1)] = -1;
          d.id.icntl[icntl(2)] = -1;
          d.id.icntl[icntl(3)] = -1;
          d.id.icntl[icntl(4)] = 0;

          d.id.n = d.free_dofs.size();
          if (distributed_values)
            {
              d.id.icntl[icntl(18)] = 3; // distributed assembled input
              d.id.nnz_loc          = d.values.size();
              d.id.irn_loc          = d.rows.data();
              d.id.jcn_loc          = d.cols.data();
              d.id.a_loc            = d.values.data();
            }
          else
            {
              d.id.nnz = d.values.size();
              d.id.irn = d.rows.data();
              d.id.jcn = d.cols.data();
              d.id.a   = d.values.data();
            }

          if (matrix_read)
            matrix_read();

          std::vector<MUMPS_INT> schur_list(n_s);
          if (n_s > 0)
            {
              for (unsigned int a = 0; a < n_s; ++a)
                schur_list[a] = d.reduced_index[interface[a]];
              d.id.icntl[icntl(19)] = 1; // centralised on the host
              d.id.size_schur       = n_s;
              d.id.listvar_schur    = schur_list.data();
              d.id.schur_lld        = n_s;
            }
          std::vector<double> schur_values(d.host ? std::size_t(n_s) * n_s : 0,
                                           0.);
          d.id.schur = (n_s > 0 && d.host ? schur_values.data() : nullptr);

          // Pivot order (PivotOrder): MUMPS' own (approximate minimum
          // degree when a Schur complement is asked for), nested
          // dissection with the Schur unknowns last, or whichever of the
          // two MUMPS' analysis estimates to need fewer flops.
          // The host orders; every rank learns whether it did (METIS may
          // fail), so that all take the same branch.
          const bool both = (pivot_order == PivotOrder::cheaper_of_both);
          if (pivot_order != PivotOrder::nested_dissection)
            d.call(1);
          static_assert(std::is_same_v<MUMPS_INT, int>,
                        "PERM_IN is handed over as int");
          const std::vector<MUMPS_INT> order =
            (ordering && d.host ?
               nested_dissection_order(n_free, row_start, columns, schur_list) :
               std::vector<MUMPS_INT>());
          // K's pattern served the pivot order only: gone before the
          // numerical factorisation, where the run's memory peaks
          // (doc/performance.md).
          std::vector<unsigned int>().swap(columns);
          std::vector<std::size_t>().swap(row_start);
          if (Utilities::MPI::max(order.empty() ? 0u : 1u, communicator) > 0)
            {
              const double minimum_degree_flops = d.id.rinfog[0];
              const int    automatic            = d.id.icntl[icntl(7)];
              d.id.perm_in         = const_cast<MUMPS_INT *>(order.data());
              d.id.icntl[icntl(7)] = 1;
              d.call(1);
              if (both && d.id.rinfog[0] > minimum_degree_flops)
                {
                  d.id.perm_in         = nullptr;
                  d.id.icntl[icntl(7)] = automatic;
                  d.call(1);
                }
            }
          else if (pivot_order == PivotOrder::nested_dissection)
            d.call(1); // METIS failed: MUMPS orders.

          // Factorisation; more workspace if MUMPS asks. A long one says
          // how far it is every few seconds (FactorisationTicker).
          d.id.job = 2;
          FactorisationTicker ticker(d.host ? d.progress : nullptr,
                                     d.label,
                                     d.id.rinfog[0]);
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
          ticker.finish(d.id.rinfog[2]);
          d.check(2);
          // MUMPS reads the matrix again only for iterative refinement or
          // error analysis (ICNTL(10), ICNTL(11); neither is asked): the
          // copy handed to it goes (doc/performance.md).
          d.id.irn = d.id.jcn = d.id.irn_loc = d.id.jcn_loc = nullptr;
          d.id.a = d.id.a_loc = nullptr;
          std::vector<MUMPS_INT>().swap(d.rows);
          std::vector<MUMPS_INT>().swap(d.cols);
          std::vector<double>().swap(d.values);
          d.id.listvar_schur = nullptr;
          d.id.schur         = nullptr;
          d.id.perm_in       = nullptr;

          // ICNTL(19) = 1 with a symmetric matrix: the lower triangle,
          // stored by rows (row a, column b <= a at a * n_s + b), on the
          // host; what the upper part holds is not specified. Read as
          // LAPACK's column-major storage that is the upper triangle; it is
          // mirrored into the lower one in place, which the factorisation
          // below reads: no second n_s x n_s copy beside MUMPS' factor at
          // the run's peak (doc/performance.md).
          for (unsigned int a = 0; a < (d.host ? n_s : 0); ++a)
            for (unsigned int b = 0; b < a; ++b)
              schur_values[std::size_t(b) * n_s + a] =
                schur_values[std::size_t(a) * n_s + b];
          d.schur_factor = std::move(schur_values);
        }

      d.entries =
        (d.mumps_alive ? (d.id.infog[28] >= 0 ? double(d.id.infog[28]) :
                                                -1e6 * double(d.id.infog[28])) :
                         0.5 * n_s * (n_s + 1.));
      if (n_s > 0 && (d.host || d.dense_only))
        {
          const int ld = n_s;
          if (d.dense_only)
            {
              d.schur_factor.resize(std::size_t(n_s) * n_s);
              for (unsigned int b = 0; b < n_s; ++b)
                for (unsigned int a = 0; a < n_s; ++a)
                  d.schur_factor[std::size_t(b) * n_s + a] = d.schur(a, b);
            }
          int info = 0;
          potrf("L", &ld, d.schur_factor.data(), &ld, &info);
          AssertThrow(info == 0,
                      ExcMessage("The Schur complement on the contact face is "
                                 "not positive definite: a body is not held "
                                 "against a rigid motion."));
        }
      // Only S's factor serves from here on.
      d.schur = FullMatrix<double>();
    }



    void
    SparseCholesky::share(const MPI_Comm world, const unsigned int root)
    {
      if (Utilities::MPI::n_mpi_processes(world) == 1)
        return;
      Data      &d       = *data;
      const bool is_root = (Utilities::MPI::this_mpi_process(world) == root);
      unsigned long long n_s = d.interface.size();
      Utilities::MPI::broadcast(&n_s, 1, root, world);
      d.interface.resize(n_s);
      Utilities::MPI::broadcast(d.interface.data(), n_s, root, world);
      Utilities::MPI::broadcast(&d.entries, 1, root, world);
      // A rank that never called initialize() holds no MUMPS instance and
      // no factor of S: the interface and the sizes only.
      if (!d.mumps_alive && !d.dense_only && !is_root)
        d.member = false;
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



    FullMatrix<double>
    SparseCholesky::interface_flexibility(FullMatrix<double> c) const
    {
      const int n_s = n_interface();
      const int m   = c.n();
      AssertThrow(
        !data->released,
        ExcMessage("SparseCholesky::interface_flexibility() after release()."));
      AssertThrow(data->schur_factor.size() == std::size_t(n_s) * n_s,
                  ExcMessage("SparseCholesky::interface_flexibility() on a "
                             "rank that does not hold the factor of S (only "
                             "the host does)."));
      AssertDimension(c.m(), static_cast<unsigned int>(n_s));
      FullMatrix<double> result(m, m);
      if (m == 0 || n_s == 0)
        return result;

      // C's columns, compressed: point operators touch a few dozen of the
      // face's unknowns each.
      std::vector<std::size_t> start(m + 1, 0);
      std::vector<int>         rows;
      std::vector<double>      values;
      for (int j = 0; j < m; ++j)
        {
          for (int a = 0; a < n_s; ++a)
            if (c(a, j) != 0.)
              {
                rows.push_back(a);
                values.push_back(c(a, j));
              }
          start[j + 1] = rows.size();
        }
      if (10 * rows.size() <= std::size_t(n_s) * m)
        {
          // A sparse C (at most a tenth non-zero): S^{-1} from the factor
          // (dpotri, 2 n_s^3 / 3 flops), then C^T (S^{-1} C) from the
          // compressed columns (2 nnz(C) (n_s + m) flops). The dense
          // route below costs n_s^2 m + n_s m^2, three times more at
          // n_s ~ m (B2 at 16x64x16: 3 510 face unknowns, 3 564 pair
          // directions, 27 non-zeros per column).
          c = FullMatrix<double>();
          std::vector<double> s_inverse(data->schur_factor);
          int                 info = 0;
          potri("L", &n_s, s_inverse.data(), &n_s, &info);
          AssertThrow(info == 0, ExcMessage("LAPACK potri failed."));
          for (int b = 0; b < n_s; ++b)
            for (int a = b + 1; a < n_s; ++a)
              s_inverse[std::size_t(a) * n_s + b] =
                s_inverse[std::size_t(b) * n_s + a];
          // Column j of S^{-1} C, then row j of the lower triangle of
          // C^T S^{-1} C, columns of result in parallel.
          parallel::apply_to_subranges(
            0,
            m,
            [&](const int first, const int last) {
              std::vector<double> t(n_s);
              for (int j = first; j < last; ++j)
                {
                  std::fill(t.begin(), t.end(), 0.);
                  for (std::size_t k = start[j]; k < start[j + 1]; ++k)
                    {
                      const double *column =
                        s_inverse.data() + std::size_t(rows[k]) * n_s;
                      const double v = values[k];
                      for (int a = 0; a < n_s; ++a)
                        t[a] += v * column[a];
                    }
                  for (int i = j; i < m; ++i)
                    {
                      double w = 0.;
                      for (std::size_t k = start[i]; k < start[i + 1]; ++k)
                        w += values[k] * t[rows[k]];
                      result(i, j) = w;
                    }
                }
            },
            16);
          for (int i = 0; i < m; ++i)
            for (int j = i + 1; j < m; ++j)
              result(i, j) = result(j, i);
          return result;
        }

      std::vector<double> y(std::size_t(n_s) * m);
      for (int j = 0; j < m; ++j)
        for (int a = 0; a < n_s; ++a)
          y[std::size_t(j) * n_s + a] = c(a, j);
      c = FullMatrix<double>();
      // C^T S^{-1} C = Y^T Y with Y = L^{-1} C (S = L L^T): one triangular
      // block solve (dtrsm inside dtrtrs) and one symmetric rank-k product,
      // both multithreaded BLAS-3.
      int info = 0;
      trtrs("L",
            "N",
            "N",
            &n_s,
            &m,
            data->schur_factor.data(),
            &n_s,
            y.data(),
            &n_s,
            &info);
      AssertThrow(info == 0, ExcMessage("LAPACK trtrs failed."));
      // Into result's own storage: its rows read as LAPACK's columns, the
      // lower triangle there is result's upper one, mirrored below.
      const double one = 1., zero = 0.;
      syrk("L", "T", &m, &n_s, &one, y.data(), &n_s, &zero, &result(0, 0), &m);
      for (int i = 1; i < m; ++i)
        for (int j = 0; j < i; ++j)
          result(i, j) = result(j, i);
      return result;
    }



    void
    SparseCholesky::solve(std::vector<Vector<double>> &rhs_and_solutions) const
    {
      Data              &d    = *data;
      const unsigned int nrhs = rhs_and_solutions.size();
      if (nrhs == 0)
        return;
      AssertThrow(d.member && !d.released,
                  ExcMessage(d.released ?
                               "SparseCholesky::solve() after release()." :
                               "SparseCholesky::solve() on a rank that holds "
                               "no part of the factorisation."));
      const unsigned int n_free = d.free_dofs.size();
      const unsigned int n_s    = d.interface.size();

      if (d.dense_only)
        {
          std::vector<double> x(std::size_t(n_s) * nrhs);
          for (unsigned int k = 0; k < nrhs; ++k)
            for (unsigned int a = 0; a < n_s; ++a)
              x[std::size_t(k) * n_s + a] =
                rhs_and_solutions[k][d.interface[a]];
          d.solve_schur(x.data(), nrhs);
          for (unsigned int k = 0; k < nrhs; ++k)
            {
              rhs_and_solutions[k] = 0.;
              for (unsigned int a = 0; a < n_s; ++a)
                rhs_and_solutions[k][d.interface[a]] =
                  x[std::size_t(k) * n_s + a];
            }
          return;
        }

      // The host's vectors in and out; the other ranks take part.
      const unsigned int  n_held = (d.host ? nrhs : 0);
      std::vector<double> rhs(std::size_t(n_free) * n_held);
      for (unsigned int k = 0; k < n_held; ++k)
        {
          AssertDimension(rhs_and_solutions[k].size(), d.reduced_index.size());
          for (unsigned int i = 0; i < n_free; ++i)
            rhs[std::size_t(k) * n_free + i] =
              rhs_and_solutions[k][d.free_dofs[i]];
        }
      d.id.rhs  = (d.host ? rhs.data() : nullptr);
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
          std::vector<double> reduced(std::size_t(n_s) * n_held);
          d.id.redrhs           = (d.host ? reduced.data() : nullptr);
          d.id.lredrhs          = n_s;
          d.id.icntl[icntl(26)] = 1;
          d.call(3);
          if (d.host)
            d.solve_schur(reduced.data(), nrhs);
          d.id.icntl[icntl(26)] = 2;
          d.call(3);
          d.id.icntl[icntl(26)] = 0;
          d.id.redrhs           = nullptr;
        }
      d.id.rhs = nullptr;
      for (unsigned int k = 0; k < n_held; ++k)
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
      return data->entries;
    }



    double
    SparseCholesky::factor_flops() const
    {
      return (data->mumps_alive ? data->id.rinfog[2] : data->flops);
    }



    double
    SparseCholesky::local_bytes() const
    {
      const Data &d = *data;
      // INFO(9), INFO(10): the reals and integers of the factor on this
      // rank (negative: millions). What MUMPS allocates beyond them is
      // workspace of the factorisation, which the peak shows.
      const auto count = [](const MUMPS_INT n) {
        return n >= 0 ? double(n) : -1e6 * double(n);
      };
      double bytes =
        (d.mumps_alive ? count(d.id.info[8]) * sizeof(double) +
                           count(d.id.info[9]) * sizeof(MUMPS_INT) :
                         0.);
      bytes += base::vector_bytes(d.free_dofs) +
               base::vector_bytes(d.reduced_index) +
               base::vector_bytes(d.interface) + base::vector_bytes(d.rows) +
               base::vector_bytes(d.cols) + base::vector_bytes(d.values) +
               base::vector_bytes(d.schur_factor) +
               double(d.schur.m()) * d.schur.n() * sizeof(double);
      return bytes;
    }



    void
    SparseCholesky::set_progress(std::ostream *stream, const std::string &label)
    {
      data->progress = stream;
      data->label    = label;
    }



    void
    SparseCholesky::release()
    {
      Data &d = *data;
      if (d.mumps_alive)
        d.flops = d.id.rinfog[2];
      d.release();
      d.released = true;
      // Swapped with empty ones: clear() would keep the memory.
      std::vector<types::global_dof_index>().swap(d.free_dofs);
      std::vector<MUMPS_INT>().swap(d.reduced_index);
      std::vector<MUMPS_INT>().swap(d.rows);
      std::vector<MUMPS_INT>().swap(d.cols);
      std::vector<double>().swap(d.values);
      std::vector<double>().swap(d.schur_factor);
      d.schur = FullMatrix<double>();
    }
  } // namespace linear_algebra
} // namespace igabde
