// What siconos_comparison hands to siconos_solver and gets back: a
// friction-contact problem (W as its nonzero entries, q, mu) and a solve's
// report, in a binary file each. The two programs are separate processes
// because Siconos links the sequential MUMPS and igabde the MPI one: in one
// process a single dmumps_c serves both, and Siconos' sparse solvers then
// reach the MPI build (doc/contact-solver.md). This header depends on
// neither side.

#ifndef igabde_contrib_siconos_protocol_h
#define igabde_contrib_siconos_protocol_h

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace siconos_protocol
{
  /// W (n x n, n = dimension * contacts) by its nonzero entries.
  struct Problem
  {
    std::int32_t              dimension = 0, contacts = 0;
    std::vector<std::int32_t> rows, columns;
    std::vector<double>       values, q, mu;

    std::int32_t
    n() const
    {
      return dimension * contacts;
    }
  };

  /// One solver's answer: Siconos' info, its iterations, the fastest of
  /// the timed runs (ms) and the forces r.
  struct Report
  {
    std::int32_t        info = -1, iterations = 0;
    double              ms = 0.;
    std::vector<double> r;
  };

  template <typename T>
  void
  put(std::ofstream &out, const std::vector<T> &v)
  {
    const std::uint64_t size = v.size();
    out.write(reinterpret_cast<const char *>(&size), sizeof(size));
    out.write(reinterpret_cast<const char *>(v.data()),
              static_cast<std::streamsize>(size * sizeof(T)));
  }

  template <typename T>
  void
  get(std::ifstream &in, std::vector<T> &v)
  {
    std::uint64_t size = 0;
    in.read(reinterpret_cast<char *>(&size), sizeof(size));
    if (!in || size > (std::uint64_t(1) << 34))
      throw std::runtime_error("truncated or corrupt file");
    v.resize(size);
    in.read(reinterpret_cast<char *>(v.data()),
            static_cast<std::streamsize>(size * sizeof(T)));
  }

  inline void
  write(const std::string &path, const Problem &p)
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char *>(&p.dimension),
              sizeof(p.dimension));
    out.write(reinterpret_cast<const char *>(&p.contacts), sizeof(p.contacts));
    put(out, p.rows);
    put(out, p.columns);
    put(out, p.values);
    put(out, p.q);
    put(out, p.mu);
    if (!out)
      throw std::runtime_error("cannot write " + path);
  }

  inline Problem
  read_problem(const std::string &path)
  {
    std::ifstream in(path, std::ios::binary);
    Problem       p;
    in.read(reinterpret_cast<char *>(&p.dimension), sizeof(p.dimension));
    in.read(reinterpret_cast<char *>(&p.contacts), sizeof(p.contacts));
    get(in, p.rows);
    get(in, p.columns);
    get(in, p.values);
    get(in, p.q);
    get(in, p.mu);
    if (!in || p.rows.size() != p.values.size() ||
        p.columns.size() != p.values.size() ||
        p.q.size() != static_cast<std::size_t>(p.n()) ||
        p.mu.size() != static_cast<std::size_t>(p.contacts))
      throw std::runtime_error(path + ": not a problem file");
    return p;
  }

  inline void
  write(const std::string &path, const Report &r)
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char *>(&r.info), sizeof(r.info));
    out.write(reinterpret_cast<const char *>(&r.iterations),
              sizeof(r.iterations));
    out.write(reinterpret_cast<const char *>(&r.ms), sizeof(r.ms));
    put(out, r.r);
  }

  inline Report
  read_report(const std::string &path)
  {
    std::ifstream in(path, std::ios::binary);
    Report        r;
    in.read(reinterpret_cast<char *>(&r.info), sizeof(r.info));
    in.read(reinterpret_cast<char *>(&r.iterations), sizeof(r.iterations));
    in.read(reinterpret_cast<char *>(&r.ms), sizeof(r.ms));
    get(in, r.r);
    return r;
  }

  /// Whether a solve runs again after @p runs_done runs that took @p spent
  /// ms together, the fastest @p fastest ms; the fastest run counts. A solve
  /// under a second runs at least twice, and again while its runs have
  /// taken under 20 ms together (at most 100 runs), so that a solve of
  /// microseconds is timed warm (first calls pay OpenBLAS' thread start and
  /// first-touch page faults). Siconos and igabde are timed alike.
  inline bool
  run_again(const unsigned int runs_done,
            const double       fastest,
            const double       spent)
  {
    if (runs_done == 0)
      return true;
    if (runs_done == 1)
      return fastest < 1000.;
    return spent < 20. && runs_done < 100;
  }
} // namespace siconos_protocol

#endif
