#ifndef igabde_scene_rank_split_h
#define igabde_scene_rank_split_h

#include <igabde/base/memory_record.h>

#include <igabde/discretization/body.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {
    using namespace dealii;

    /// MPI communicators a run creates, freed when it is destroyed.
    struct Communicators
    {
      std::vector<MPI_Comm> list;
      ~Communicators();
    };

    /**
     * @brief Under mpirun with the direct solver: splits MPI_COMM_WORLD
     * among the @p bodies (ranks in proportion to @p factor_entries, their
     * estimated factor sizes, at least one each; one body: every rank;
     * more bodies than ranks: each body on one rank, round robin), gives
     * each body its ParallelLayout, keeps the
     * group communicator in @p groups and says the split on @p pcout.
     * Returns the names of the bodies this rank factorises (every body
     * with one process or another solver).
     */
    template <int dim>
    std::vector<std::string>
    split_ranks_among_bodies(
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const std::vector<double> &factor_entries,
      const bool                 direct_solver,
      Communicators             &groups,
      ConditionalOStream        &pcout);

    /**
     * @brief At the end of a run (collective): the seconds of every phase
     * of @p timer, the largest over the ranks, and summary.json's "ranks"
     * (each rank's peak memory, the bodies in @p factorised_here, and
     * @p held_here, what the rank holds: its replicated and divided MiB and
     * the items).
     */
    std::pair<std::map<std::string, double>, nlohmann::json>
    gather_rank_figures(const TimerOutput                   &timer,
                        const std::vector<std::string>      &factorised_here,
                        const std::vector<base::MemoryItem> &held_here = {});
  } // namespace scene
} // namespace igabde

#endif
