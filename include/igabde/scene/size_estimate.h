#ifndef igabde_scene_size_estimate_h
#define igabde_scene_size_estimate_h

#include <igabde/scene/parameters.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief What a scene will need, estimated from its coarse geometry
     * before anything is assembled: unknowns, matrix entries, sparse factor
     * entries, the dense contact blocks and the output fields, and the bytes
     * they take together.
     *
     * The counts of elements, unknowns, face unknowns and matrix entries
     * follow from the knot vectors (exact for a single patch). The factor
     * entries follow the growth of a nested-dissection factorisation (2D:
     * n log n; 3D: the smaller of n^{4/3} and a recursive-bisection count
     * that sees plates; times the square of the unknowns per separator
     * node), with constants measured on MUMPS' own counts (doc/robustness.md
     * states how close the estimate comes). The contact blocks are those of
     * the path the run takes (dense on the condensed path, the coupled
     * system's LU or AMG on the full one). All sizes are
     * doubles: a scene far beyond any machine must not overflow the count.
     */
    struct SizeEstimate
    {
      struct BodySize
      {
        std::string name;
        double      n_elements     = 0.;
        double      n_unknowns     = 0.;
        double      matrix_entries = 0.;
        double      factor_entries = 0.;
        double      face_unknowns  = 0.;
      };

      std::vector<BodySize> bodies;
      /// Contact unknowns (pairs times 1 frictionless, times dim with
      /// friction).
      double contact_unknowns = 0.;
      /// Sparse matrices, their solver copies and the vectors.
      double bytes_matrix = 0.;
      /// Sparse factors (direct solvers) or the multigrid hierarchy.
      double bytes_factor = 0.;
      /// Dense contact blocks of the condensed path: Schur complements,
      /// flexibility, Newton matrix.
      double bytes_dense = 0.;
      /// The full path's coupled system: its matrix and its sparse LU
      /// (direct) or its multigrid hierarchy (gmres-amg).
      double bytes_coupled = 0.;
      /// The contact path whose blocks the total counts (condensed when
      /// there is no contact): the scene's Contact/Path, the full path for
      /// penalty and augmented Lagrange, and for Contact/Path = auto the
      /// condensed one unless choose_path_for_memory() chose full.
      contact::Path path = contact::Path::condensed;
      /// VTU output fields (when written).
      double bytes_output = 0.;
      /// The process before any of the above: code and data of the
      /// libraries (deal.II, Trilinos, MPI, MUMPS): a fixed allowance, the
      /// resident set of a small scene (its value: doc/robustness.md).
      double bytes_process = 0.;

      double
      total_bytes() const;

      /// total_bytes() if the contact blocks were those of @p p (on the
      /// full path the larger of the bodies' factors and the coupled
      /// system: the bodies free their factors before it is set up).
      double
      total_bytes(const contact::Path p) const;

      /**
       * @brief Contact/Path = auto and the condensed path's dense blocks
       * do not fit in @p available bytes while the full path does: counts
       * the full path from now on and returns why (the contact stage then
       * takes the full path whatever its cost model says); else "".
       */
      std::string
      choose_path_for_memory(const double available);

      /// Whether the scene's Contact/Path is auto (set by estimate_size()).
      bool automatic_path = false;

      double
      total_unknowns() const;

      /// One line: unknowns, factor entries and memory, in GiB.
      std::string
      describe() const;

      nlohmann::json
      to_json() const;
    };

    /**
     * @brief The size of the scene @p parameters at @p refinements uniform
     * refinements (the scene's own by default).
     */
    SizeEstimate
    estimate_size(const AllParameters &parameters,
                  const std::string   &scene_file,
                  const int            refinements = -1);

    /**
     * @brief Memory this process can use without swapping: MemAvailable of
     * /proc/meminfo, else the physical memory; at most IGABDE_MEMORY_LIMIT
     * GiB when that environment variable is set (a share of a machine).
     */
    double
    available_memory_bytes();

    /**
     * @brief Stops with a one-line error (base::ExcInput) when the scene's
     * estimate exceeds @p available bytes, naming the estimate and the
     * largest Discretization/Refinements that fits; returns the estimate
     * otherwise.
     */
    SizeEstimate
    check_size(const AllParameters &parameters,
               const std::string   &scene_file,
               const double         available);
  } // namespace scene
} // namespace igabde

#endif
