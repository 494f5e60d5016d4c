#include <igabde/contact/fclib_reader.h>

#include <deal.II/base/exceptions.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include <cmath>
#include <fstream>
#include <hdf5.h>
#include <sstream>
#include <type_traits>
#include <vector>

namespace igabde
{
  namespace contact
  {
    namespace
    {
      using SparseMatrix = Eigen::SparseMatrix<double>;

      std::string
      base_name(const std::string &filename)
      {
        const auto pos = filename.find_last_of('/');
        return pos == std::string::npos ? filename : filename.substr(pos + 1);
      }



      bool
      ends_with(const std::string &s, const std::string &suffix)
      {
        return s.size() >= suffix.size() &&
               s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
      }



      // RAII HDF5 file, with HDF5's own error printing switched off while
      // it is open (we report errors ourselves).
      class Hdf5File
      {
      public:
        explicit Hdf5File(const std::string &filename)
          : filename(filename)
        {
          H5Eget_auto2(H5E_DEFAULT, &old_func, &old_data);
          H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
          id = H5Fopen(filename.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
          if (id < 0)
            {
              H5Eset_auto2(H5E_DEFAULT, old_func, old_data);
              AssertThrow(false,
                          dealii::ExcMessage("FCLIB reader: cannot open '" +
                                             filename + "' as an HDF5 file"));
            }
        }

        ~Hdf5File()
        {
          if (id >= 0)
            H5Fclose(id);
          H5Eset_auto2(H5E_DEFAULT, old_func, old_data);
        }

        Hdf5File(const Hdf5File &) = delete;
        Hdf5File &
        operator=(const Hdf5File &) = delete;

        // True if every component of the path exists (names are relative to
        // the file's root group, with or without a leading '/').
        bool
        exists(const std::string &path) const
        {
          std::string partial;
          std::size_t start = (!path.empty() && path[0] == '/' ? 1 : 0);
          while (start <= path.size())
            {
              std::size_t end = path.find('/', start);
              if (end == std::string::npos)
                end = path.size();
              partial = path.substr(0, end);
              if (H5Lexists(id, partial.c_str(), H5P_DEFAULT) <= 0)
                return false;
              start = end + 1;
            }
          return true;
        }

        template <typename T>
        std::vector<T>
        read_vector(const std::string &path) const
        {
          AssertThrow(exists(path),
                      dealii::ExcMessage("FCLIB reader: '" + filename +
                                         "' has no dataset " + path));
          const hid_t ds = H5Dopen2(id, path.c_str(), H5P_DEFAULT);
          AssertThrow(ds >= 0,
                      dealii::ExcMessage("FCLIB reader: cannot open dataset " +
                                         path + " in '" + filename + "'"));
          const hid_t space   = H5Dget_space(ds);
          const int   ndims   = H5Sget_simple_extent_ndims(space);
          hsize_t     dims[4] = {1, 1, 1, 1};
          if (ndims > 0 && ndims <= 4)
            H5Sget_simple_extent_dims(space, dims, nullptr);
          H5Sclose(space);
          std::size_t n = 1;
          for (int k = 0; k < std::max(ndims, 0) && k < 4; ++k)
            n *= dims[k];
          std::vector<T> data(n);
          const hid_t    type =
            std::is_same<T, double>::value ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT;
          const herr_t status =
            n > 0 ?
              H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) :
              0;
          H5Dclose(ds);
          AssertThrow(ndims >= 0 && ndims <= 4 && status >= 0,
                      dealii::ExcMessage("FCLIB reader: cannot read dataset " +
                                         path + " of '" + filename + "'"));
          return data;
        }

        int
        read_int(const std::string &path) const
        {
          const std::vector<int> v = read_vector<int>(path);
          AssertThrow(v.size() >= 1,
                      dealii::ExcMessage("FCLIB reader: empty dataset " + path +
                                         " in '" + filename + "'"));
          return v[0];
        }

        Eigen::VectorXd
        read_eigen_vector(const std::string &path) const
        {
          const std::vector<double> v = read_vector<double>(path);
          Eigen::VectorXd           out(v.size());
          for (std::size_t k = 0; k < v.size(); ++k)
            out[k] = v[k];
          return out;
        }

        // An FCLIB sparse matrix group (see the header for the layout).
        SparseMatrix
        read_sparse(const std::string &group) const
        {
          const int                 m  = read_int(group + "/m");
          const int                 n  = read_int(group + "/n");
          const int                 nz = read_int(group + "/nz");
          const std::vector<int>    p  = read_vector<int>(group + "/p");
          const std::vector<int>    i  = read_vector<int>(group + "/i");
          const std::vector<double> x  = read_vector<double>(group + "/x");
          const std::string         where =
            "FCLIB reader: matrix " + group + " of '" + filename + "': ";
          AssertThrow(m >= 0 && n >= 0,
                      dealii::ExcMessage(where + "negative size"));
          std::vector<Eigen::Triplet<double>> entries;
          auto add = [&](const long row, const long col, const double v) {
            AssertThrow(row >= 0 && row < m && col >= 0 && col < n,
                        dealii::ExcMessage(
                          where + "entry (" + std::to_string(row) + ", " +
                          std::to_string(col) + ") outside " +
                          std::to_string(m) + " x " + std::to_string(n)));
            AssertThrow(std::isfinite(v),
                        dealii::ExcMessage(where + "non-finite entry"));
            entries.emplace_back(row, col, v);
          };
          if (nz >= 0)
            {
              AssertThrow(p.size() >= std::size_t(nz) &&
                            i.size() >= std::size_t(nz) &&
                            x.size() >= std::size_t(nz),
                          dealii::ExcMessage(where + "triplet arrays shorter "
                                                     "than nz"));
              for (int k = 0; k < nz; ++k)
                add(i[k], p[k], x[k]); // CSparse: i = row, p = column
            }
          else if (nz == -1 || nz == -2)
            {
              const int outer = nz == -1 ? n : m;
              AssertThrow(p.size() >= std::size_t(outer + 1),
                          dealii::ExcMessage(where + "pointer array too "
                                                     "short"));
              const int nnz = p[outer];
              AssertThrow(nnz >= 0 && i.size() >= std::size_t(nnz) &&
                            x.size() >= std::size_t(nnz),
                          dealii::ExcMessage(where + "index arrays shorter "
                                                     "than the pointers say"));
              for (int o = 0; o < outer; ++o)
                {
                  AssertThrow(p[o] <= p[o + 1] && p[o] >= 0,
                              dealii::ExcMessage(where + "pointers not "
                                                         "monotone"));
                  for (int k = p[o]; k < p[o + 1]; ++k)
                    {
                      if (nz == -1)
                        add(i[k], o, x[k]);
                      else
                        add(o, i[k], x[k]);
                    }
                }
            }
          else
            AssertThrow(false,
                        dealii::ExcMessage(where + "unknown storage nz = " +
                                           std::to_string(nz)));
          SparseMatrix A(m, n);
          A.setFromTriplets(entries.begin(), entries.end());
          return A;
        }

        const std::string filename;
        hid_t             id = -1;

      private:
        H5E_auto2_t old_func = nullptr;
        void       *old_data = nullptr;
      };



      void
      set_mu(ContactProblem        &problem,
             const Eigen::VectorXd &mu,
             const std::string     &filename)
      {
        AssertThrow(mu.size() == problem.n_contacts ||
                      (mu.size() == 1 && problem.n_contacts >= 1),
                    dealii::ExcMessage("FCLIB reader: '" + filename + "' has " +
                                       std::to_string(mu.size()) +
                                       " friction coefficients for " +
                                       std::to_string(problem.n_contacts) +
                                       " contacts"));
        problem.mu.resize(problem.n_contacts);
        for (unsigned int c = 0; c < problem.n_contacts; ++c)
          problem.mu[c] = mu.size() == 1 ? mu[0] : mu[c];
      }



      void
      finish(ContactProblem &problem, const std::string &filename)
      {
        problem.name = base_name(filename);
        try
          {
            problem.check_consistency();
          }
        catch (const std::exception &e)
          {
            AssertThrow(false,
                        dealii::ExcMessage("FCLIB reader: '" + filename +
                                           "' gives an inconsistent "
                                           "problem: " +
                                           e.what()));
          }
      }



      // Whitespace-separated tokens of a Siconos .dat file, with line
      // access for the CSparse text print.
      class DatStream
      {
      public:
        explicit DatStream(const std::string &filename)
          : filename(filename)
          , in(filename)
        {
          AssertThrow(in.good(),
                      dealii::ExcMessage("Siconos reader: cannot open '" +
                                         filename + "'"));
        }

        double
        number(const std::string &what)
        {
          double v;
          in >> v;
          AssertThrow(!in.fail(),
                      dealii::ExcMessage("Siconos reader: '" + filename +
                                         "': cannot read " + what));
          return v;
        }

        long
        integer(const std::string &what)
        {
          const double v = number(what);
          AssertThrow(v == std::floor(v) && std::abs(v) < 1e9,
                      dealii::ExcMessage("Siconos reader: '" + filename +
                                         "': " + what + " is not an integer"));
          return static_cast<long>(v);
        }

        /// Whether the next token is written as an integer (a matrix
        /// header), not as a floating-point value; nothing is consumed.
        bool
        next_is_integer()
        {
          const auto  position = in.tellg();
          std::string token;
          in >> token;
          in.clear();
          in.seekg(position);
          return !token.empty() &&
                 token.find_first_not_of("+-0123456789") == std::string::npos;
        }

        bool
        line(std::string &l)
        {
          return static_cast<bool>(std::getline(in, l));
        }

        const std::string filename;
        std::ifstream     in;
      };



      // The CSparse text print (cs_print) of a storage-2 matrix.
      SparseMatrix
      read_csparse_print(DatStream &s, const long rows, const long cols)
      {
        s.integer("sparse matrix origin");
        std::string                         l;
        long                                nnz = -1, col = -1;
        std::vector<Eigen::Triplet<double>> entries;
        while ((nnz < 0 || long(entries.size()) < nnz) && s.line(l))
          {
            if (l.find("-by-") != std::string::npos)
              {
                const auto pos = l.find("nnz:");
                AssertThrow(pos != std::string::npos,
                            dealii::ExcMessage("Siconos reader: '" +
                                               s.filename +
                                               "': no nnz in the CSparse "
                                               "header"));
                nnz = std::stol(l.substr(pos + 4));
                continue;
              }
            if (l.find("col") != std::string::npos &&
                l.find("locations") != std::string::npos)
              {
                std::istringstream ls(l.substr(l.find("col") + 3));
                ls >> col;
                continue;
              }
            const auto colon = l.find(':');
            if (colon == std::string::npos || nnz < 0)
              continue;
            std::istringstream left(l.substr(0, colon));
            std::istringstream right(l.substr(colon + 1));
            long               a, b;
            double             v;
            left >> a;
            const bool triplet = static_cast<bool>(left >> b);
            right >> v;
            AssertThrow(!right.fail(),
                        dealii::ExcMessage("Siconos reader: '" + s.filename +
                                           "': bad sparse entry line '" + l +
                                           "'"));
            const long row = a, c = triplet ? b : col;
            AssertThrow(row >= 0 && row < rows && c >= 0 && c < cols,
                        dealii::ExcMessage("Siconos reader: '" + s.filename +
                                           "': sparse entry out of range"));
            entries.emplace_back(row, c, v);
          }
        AssertThrow(nnz >= 0 && long(entries.size()) == nnz,
                    dealii::ExcMessage("Siconos reader: '" + s.filename +
                                       "': truncated sparse matrix"));
        SparseMatrix A(rows, cols);
        A.setFromTriplets(entries.begin(), entries.end());
        return A;
      }


      /**
       * A NumericsMatrix as Siconos prints it (NM_write_in_file): the
       * storage type, the two sizes, then the dense matrix column by column
       * (0, after the sizes again), the sparse-block matrix (1) or the
       * CSparse text print (2). @p what names it in messages.
       */
      SparseMatrix
      read_numerics_matrix(DatStream &s, const std::string &what)
      {
        const std::string where   = "Siconos reader: '" + s.filename + "': ";
        const long        storage = s.integer("the storage type of " + what);
        const long        rows    = s.integer("the size of " + what);
        const long        cols    = s.integer("the size of " + what);
        AssertThrow(rows >= 0 && cols >= 0 && rows < 100000000 &&
                      cols < 100000000,
                    dealii::ExcMessage(where + "bad sizes of " + what));
        std::vector<Eigen::Triplet<double>> entries;
        const auto add = [&](const long i, const long j, const double v) {
          if (v != 0.)
            entries.emplace_back(i, j, v);
        };
        if (storage == 0)
          {
            const long r = s.integer("the dense size of " + what),
                       c = s.integer("the dense size of " + what);
            AssertThrow(r == rows && c == cols,
                        dealii::ExcMessage(where + "dense sizes of " + what +
                                           " disagree"));
            for (long j = 0; j < cols; ++j) // column major
              for (long i = 0; i < rows; ++i)
                add(i, j, s.number("an entry of " + what));
          }
        else if (storage == 1)
          {
            const long nbblocks = s.integer("the number of blocks");
            if (nbblocks > 0)
              {
                const long bn0 = s.integer("blocknumber0");
                const long bn1 = s.integer("blocknumber1");
                AssertThrow(bn0 > 0 && bn1 > 0 && bn0 <= rows && bn1 <= cols,
                            dealii::ExcMessage(where + "bad block counts of " +
                                               what));
                std::vector<long> bs0(bn0), bs1(bn1);
                for (auto &v : bs0)
                  v = s.integer("blocksize0");
                for (auto &v : bs1)
                  v = s.integer("blocksize1");
                AssertThrow(bs0.back() == rows && bs1.back() == cols,
                            dealii::ExcMessage(where + "the block sizes of " +
                                               what +
                                               " do not add up to its "
                                               "size"));
                const long filled1 = s.integer("filled1");
                const long filled2 = s.integer("filled2");
                AssertThrow(filled1 == bn0 + 1 && filled2 == nbblocks,
                            dealii::ExcMessage(where +
                                               "bad sparse-block index sizes "
                                               "of " +
                                               what));
                std::vector<long> index1(filled1), index2(filled2);
                for (auto &v : index1)
                  v = s.integer("index1_data");
                for (auto &v : index2)
                  v = s.integer("index2_data");
                for (long row = 0; row + 1 < filled1; ++row)
                  for (long blk = index1[row]; blk < index1[row + 1]; ++blk)
                    {
                      AssertThrow(blk >= 0 && blk < filled2,
                                  dealii::ExcMessage(where +
                                                     "bad block index"));
                      const long col = index2[blk];
                      AssertThrow(col >= 0 && col < bn1,
                                  dealii::ExcMessage(where +
                                                     "bad block column"));
                      const long r0 = row == 0 ? 0 : bs0[row - 1];
                      const long c0 = col == 0 ? 0 : bs1[col - 1];
                      const long nr = bs0[row] - r0, ncol = bs1[col] - c0;
                      const long number = s.integer("the block number");
                      AssertThrow(number == blk,
                                  dealii::ExcMessage(where +
                                                     "block numbering"));
                      for (long j = 0; j < ncol; ++j) // column major
                        for (long i = 0; i < nr; ++i)
                          add(r0 + i, c0 + j, s.number("a block entry"));
                    }
              }
          }
        else if (storage == 2)
          return read_csparse_print(s, rows, cols);
        else
          AssertThrow(false,
                      dealii::ExcMessage(where + "unknown storage " +
                                         std::to_string(storage) + " of " +
                                         what));
        SparseMatrix A(rows, cols);
        A.setFromTriplets(entries.begin(), entries.end());
        return A;
      }



      /**
       * The local problem of the global one M v = H r + f, u = H^T v + w:
       * W = H^T M^-1 H, q = H^T M^-1 f + w (sparse LDL^T of M, LU if that
       * fails), with d components per contact.
       */
      ContactProblem
      condense_global(SparseMatrix           M,
                      const SparseMatrix    &H,
                      const Eigen::VectorXd &fv,
                      const Eigen::VectorXd &w,
                      const int              d,
                      const std::string     &where)
      {
        AssertThrow(M.rows() == M.cols() && H.rows() == M.rows() &&
                      fv.size() == M.rows() && w.size() == H.cols() &&
                      H.cols() % d == 0,
                    dealii::ExcMessage(where + "inconsistent sizes of M (" +
                                       std::to_string(M.rows()) + "x" +
                                       std::to_string(M.cols()) + "), H (" +
                                       std::to_string(H.rows()) + "x" +
                                       std::to_string(H.cols()) + "), f, w"));
        // M may be stored as one triangle only: symmetrise.
        {
          const SparseMatrix L = M.triangularView<Eigen::StrictlyLower>();
          const SparseMatrix U = M.triangularView<Eigen::StrictlyUpper>();
          if (L.nonZeros() == 0 && U.nonZeros() > 0)
            M = M + SparseMatrix(U.transpose());
          else if (U.nonZeros() == 0 && L.nonZeros() > 0)
            M = M + SparseMatrix(L.transpose());
        }
        M.makeCompressed();
        SparseMatrix Hc = H;
        Hc.makeCompressed();

        Eigen::MatrixXd                     MinvH;
        Eigen::VectorXd                     Minvf;
        Eigen::SimplicialLDLT<SparseMatrix> ldlt(M);
        if (ldlt.info() == Eigen::Success)
          {
            const SparseMatrix X = ldlt.solve(Hc);
            Minvf                = ldlt.solve(fv);
            MinvH                = Eigen::MatrixXd(X);
          }
        if (ldlt.info() != Eigen::Success || !MinvH.allFinite() ||
            !Minvf.allFinite())
          {
            Eigen::SparseLU<SparseMatrix> lu(M);
            AssertThrow(lu.info() == Eigen::Success,
                        dealii::ExcMessage(where + "M is singular"));
            MinvH = lu.solve(Eigen::MatrixXd(Hc));
            Minvf = lu.solve(fv);
          }
        ContactProblem problem;
        problem.n_components = d;
        problem.n_contacts   = H.cols() / d;
        problem.W            = Hc.transpose() * MinvH;
        problem.W            = 0.5 * (problem.W + problem.W.transpose()).eval();
        problem.q            = Hc.transpose() * Minvf + w;
        return problem;
      }


      /**
       * The rest of a local .dat problem once its matrix @p W is read:
       * q, then mu (dimension 1: frictionless, mu ignored).
       */
      ContactProblem
      read_local_tail(DatStream          &s,
                      const SparseMatrix &W,
                      const long          d,
                      const long          nc)
      {
        const long n = d * nc;
        AssertThrow(W.rows() == n && W.cols() == n,
                    dealii::ExcMessage(
                      "Siconos reader: '" + s.filename + "': matrix is " +
                      std::to_string(W.rows()) + " x " +
                      std::to_string(W.cols()) + ", expected " +
                      std::to_string(n) + " x " + std::to_string(n) +
                      " (dimension x contacts)"));
        ContactProblem problem;
        problem.n_components = d;
        problem.n_contacts   = nc;
        problem.W            = Eigen::MatrixXd(W);
        problem.q.resize(n);
        for (long i = 0; i < n; ++i)
          problem.q[i] = s.number("q");
        Eigen::VectorXd mu(nc);
        for (long c = 0; c < nc; ++c)
          mu[c] = s.number("mu");
        if (d > 1)
          set_mu(problem, mu, s.filename);
        finish(problem, s.filename);
        return problem;
      }
    } // namespace



    FclibFileKind
    classify_fclib_file(const std::string &filename)
    {
      const std::string name = base_name(filename);
      if (ends_with(name, ".hdf5") || ends_with(name, ".h5"))
        {
          try
            {
              Hdf5File f(filename);
              if (f.exists("/fclib_local"))
                return FclibFileKind::hdf5_local;
              if (f.exists("/fclib_global"))
                return FclibFileKind::hdf5_global;
              if (f.exists("/fclib_global_rolling"))
                return FclibFileKind::hdf5_global_rolling;
            }
          catch (...)
            {}
          return FclibFileKind::unknown;
        }
      if (ends_with(name, ".dat"))
        {
          if (name.rfind("GFC", 0) == 0 || name.rfind("gfc", 0) == 0)
            return FclibFileKind::siconos_global_dat;
          return FclibFileKind::siconos_local_dat;
        }
      return FclibFileKind::unknown;
    }



    ContactProblem
    read_fclib_local(const std::string &filename)
    {
      Hdf5File f(filename);
      AssertThrow(f.exists("/fclib_local"),
                  dealii::ExcMessage("FCLIB reader: '" + filename +
                                     "' has no /fclib_local group"));
      const int d = f.read_int("/fclib_local/spacedim");
      AssertThrow(d == 2 || d == 3,
                  dealii::ExcMessage("FCLIB reader: '" + filename +
                                     "': spacedim must be 2 or 3, is " +
                                     std::to_string(d)));
      const SparseMatrix W = f.read_sparse("/fclib_local/W");
      ContactProblem     problem;
      problem.n_components = d;
      AssertThrow(W.rows() == W.cols() && W.rows() % d == 0,
                  dealii::ExcMessage("FCLIB reader: '" + filename +
                                     "': W is not square with a multiple "
                                     "of spacedim rows"));
      problem.n_contacts = W.rows() / d;
      problem.W          = Eigen::MatrixXd(W);
      problem.q          = f.read_eigen_vector("/fclib_local/vectors/q");
      set_mu(problem, f.read_eigen_vector("/fclib_local/vectors/mu"), filename);
      AssertThrow(!f.exists("/fclib_local/R"),
                  dealii::ExcMessage("FCLIB reader: '" + filename +
                                     "': local problems with R (bilateral "
                                     "constraints) are not supported"));
      finish(problem, filename);
      return problem;
    }



    ContactProblem
    read_fclib_global(const std::string &filename)
    {
      Hdf5File f(filename);
      AssertThrow(f.exists("/fclib_global"),
                  dealii::ExcMessage("FCLIB reader: '" + filename +
                                     "' has no /fclib_global group"));
      AssertThrow(!f.exists("/fclib_global/G"),
                  dealii::ExcMessage("FCLIB reader: '" + filename +
                                     "': global problems with G (bilateral "
                                     "constraints) are not supported"));
      const int d = f.read_int("/fclib_global/spacedim");
      AssertThrow(d == 2 || d == 3,
                  dealii::ExcMessage("FCLIB reader: '" + filename +
                                     "': spacedim must be 2 or 3, is " +
                                     std::to_string(d)));
      const SparseMatrix    M  = f.read_sparse("/fclib_global/M");
      const SparseMatrix    H  = f.read_sparse("/fclib_global/H");
      const Eigen::VectorXd fv = f.read_eigen_vector("/fclib_global/vectors/f");
      const Eigen::VectorXd w  = f.read_eigen_vector("/fclib_global/vectors/w");
      ContactProblem        problem =
        condense_global(M, H, fv, w, d, "FCLIB reader: '" + filename + "': ");
      set_mu(problem,
             f.read_eigen_vector("/fclib_global/vectors/mu"),
             filename);
      finish(problem, filename);
      return problem;
    }



    ContactProblem
    read_siconos_dat(const std::string &filename)
    {
      DatStream  s(filename);
      const long d  = s.integer("the dimension");
      const long nc = s.integer("the number of contacts");
      AssertThrow(d >= 1 && d <= 3,
                  dealii::ExcMessage("Siconos reader: '" + filename +
                                     "': dimension must be 1, 2 or 3, is " +
                                     std::to_string(d)));
      AssertThrow(nc >= 0 && nc < 10000000,
                  dealii::ExcMessage("Siconos reader: '" + filename +
                                     "': bad number of contacts " +
                                     std::to_string(nc)));
      return read_local_tail(s, read_numerics_matrix(s, "the matrix W"), d, nc);
    }



    ContactProblem
    read_siconos_global_dat(const std::string &filename)
    {
      DatStream         s(filename);
      const std::string where = "Siconos reader: '" + filename + "': ";
      const long        d     = s.integer("the dimension");
      const long        nc    = s.integer("the number of contacts");
      AssertThrow(d == 2 || d == 3,
                  dealii::ExcMessage(where + "dimension must be 2 or 3, is " +
                                     std::to_string(d)));
      AssertThrow(nc >= 0 && nc < 10000000,
                  dealii::ExcMessage(where + "bad number of contacts " +
                                     std::to_string(nc)));
      const SparseMatrix M = read_numerics_matrix(s, "the mass matrix M");
      if (!s.next_is_integer())
        {
          // No H: a local problem under a global problem's name (e.g.
          // GFC3D_TwoRods1-condensed.dat); the matrix is W.
          return read_local_tail(s, M, d, nc);
        }
      const SparseMatrix H = read_numerics_matrix(s, "the matrix H");
      AssertThrow(H.cols() == d * nc,
                  dealii::ExcMessage(
                    where + "H has " + std::to_string(H.cols()) +
                    " columns for " + std::to_string(nc) +
                    " contacts of dimension " + std::to_string(d)));
      Eigen::VectorXd fv(M.rows()), w(H.cols()), mu(nc);
      for (long i = 0; i < fv.size(); ++i)
        fv[i] = s.number("q (the load f)");
      for (long i = 0; i < w.size(); ++i)
        w[i] = s.number("b (the offset w)");
      for (long c = 0; c < nc; ++c)
        mu[c] = s.number("mu");
      ContactProblem problem = condense_global(M, H, fv, w, d, where);
      set_mu(problem, mu, filename);
      finish(problem, filename);
      return problem;
    }



    ContactProblem
    read_fclib_problem(const std::string &filename)
    {
      switch (classify_fclib_file(filename))
        {
          case FclibFileKind::hdf5_local:
            return read_fclib_local(filename);
          case FclibFileKind::hdf5_global:
            return read_fclib_global(filename);
          case FclibFileKind::siconos_local_dat:
            return read_siconos_dat(filename);
          case FclibFileKind::hdf5_global_rolling:
            AssertThrow(false,
                        dealii::ExcMessage("FCLIB reader: '" + filename +
                                           "' is a rolling-friction problem "
                                           "(not supported)"));
            break;
          case FclibFileKind::siconos_global_dat:
            return read_siconos_global_dat(filename);
          case FclibFileKind::unknown:
            AssertThrow(false,
                        dealii::ExcMessage("FCLIB reader: '" + filename +
                                           "' is not a recognised problem "
                                           "file"));
            break;
        }
      return ContactProblem();
    }



    FclibSolution
    read_fclib_solution(const std::string &filename)
    {
      FclibSolution sol;
      Hdf5File      f(filename);
      // The reference solution: datasets r and u of the group 'solution'.
      if (f.exists("solution/r") && f.exists("solution/u"))
        {
          sol.r         = f.read_eigen_vector("solution/r");
          sol.u         = f.read_eigen_vector("solution/u");
          sol.available = true;
        }
      return sol;
    }

  } // namespace contact
} // namespace igabde
