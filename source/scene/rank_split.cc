#include <igabde/scene/rank_split.h>
#include <igabde/scene/run_record.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>
#include <cmath>
#include <numeric>

namespace igabde
{
  namespace scene
  {
    Communicators::~Communicators()
    {
      for (auto &c : list)
        if (c != MPI_COMM_NULL)
          Utilities::MPI::free_communicator(c);
    }



    template <int dim>
    std::vector<std::string>
    split_ranks_among_bodies(
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      const std::vector<double> &factor_entries,
      const bool                 direct_solver,
      Communicators             &groups,
      ConditionalOStream        &pcout)
    {
      const unsigned int n_ranks =
        Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
      const unsigned int rank =
        Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
      std::vector<std::string> factorised_here;
      if (n_ranks == 1 || !direct_solver)
        {
          // One process, or a solver that every rank runs for itself.
          for (const auto &body : bodies)
            factorised_here.push_back(body->name());
          return factorised_here;
        }
      const unsigned int n_bodies = bodies.size();
      if (n_bodies > n_ranks)
        {
          // Fewer ranks than bodies: each body on one rank (round robin),
          // factorised there alone; a rank may take several in turn.
          for (unsigned int b = 0; b < n_bodies; ++b)
            {
              const unsigned int             owner = b % n_ranks;
              discretization::ParallelLayout layout;
              layout.world = MPI_COMM_WORLD;
              layout.group = (rank == owner ? MPI_COMM_SELF : MPI_COMM_NULL);
              layout.root  = owner;
              layout.matrix_everywhere = false;
              bodies[b]->set_parallel_layout(layout);
              if (rank == owner)
                factorised_here.push_back(bodies[b]->name());
              pcout << "  " << bodies[b]->name()
                    << " assembled and factorised on rank " << owner << " of "
                    << n_ranks << std::endl;
            }
          return factorised_here;
        }
      // Ranks in proportion to the estimated factor sizes, at least one
      // each, consecutive ranks per body in the bodies' order (two bodies:
      // the rounded share of Body 1; more: one each and the rest by the
      // largest remainders).
      std::vector<unsigned int> count(n_bodies, 1);
      std::vector<double>       weight(n_bodies);
      for (unsigned int b = 0; b < n_bodies; ++b)
        weight[b] = std::max(factor_entries[b], 1.);
      const double total = std::accumulate(weight.begin(), weight.end(), 0.);
      if (n_bodies == 1)
        count[0] = n_ranks;
      else if (n_bodies == 2)
        {
          count[0] =
            std::clamp<unsigned int>(std::lround(n_ranks * weight[0] / total),
                                     1,
                                     n_ranks - 1);
          count[1] = n_ranks - count[0];
        }
      else
        {
          const unsigned int  rest = n_ranks - n_bodies;
          std::vector<double> remainder(n_bodies);
          unsigned int        given = 0;
          for (unsigned int b = 0; b < n_bodies; ++b)
            {
              const double share = rest * weight[b] / total;
              count[b] += static_cast<unsigned int>(std::floor(share));
              given += static_cast<unsigned int>(std::floor(share));
              remainder[b] = share - std::floor(share);
            }
          std::vector<unsigned int> order(n_bodies);
          std::iota(order.begin(), order.end(), 0u);
          std::stable_sort(order.begin(),
                           order.end(),
                           [&](const unsigned int a, const unsigned int b) {
                             return remainder[a] > remainder[b];
                           });
          for (unsigned int k = 0; given < rest; ++k, ++given)
            ++count[order[k % n_bodies]];
        }
      std::vector<unsigned int> first(n_bodies + 1, 0);
      for (unsigned int b = 0; b < n_bodies; ++b)
        first[b + 1] = first[b] + count[b];
      unsigned int color = 0;
      while (rank >= first[color + 1])
        ++color;
      MPI_Comm  group = MPI_COMM_NULL;
      const int ierr  = MPI_Comm_split(MPI_COMM_WORLD, color, rank, &group);
      AssertThrowMPI(ierr);
      groups.list.push_back(group);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          discretization::ParallelLayout layout;
          layout.world             = MPI_COMM_WORLD;
          layout.group             = (b == color ? group : MPI_COMM_NULL);
          layout.root              = first[b];
          layout.matrix_everywhere = false;
          bodies[b]->set_parallel_layout(layout);
          if (b == color)
            factorised_here.push_back(bodies[b]->name());
          pcout << "  " << bodies[b]->name()
                << " assembled and factorised on rank"
                << (first[b + 1] - first[b] > 1 ?
                      "s " + std::to_string(first[b]) + ".." +
                        std::to_string(first[b + 1] - 1) :
                      " " + std::to_string(first[b]))
                << " of " << n_ranks << std::endl;
        }
      return factorised_here;
    }



    std::pair<std::map<std::string, double>, nlohmann::json>
    gather_rank_figures(const TimerOutput                   &timer,
                        const std::vector<std::string>      &factorised_here,
                        const std::vector<base::MemoryItem> &held_here)
    {
      const MPI_Comm world  = MPI_COMM_WORLD;
      auto           timing = timing_seconds(timer);
      // Every rank runs the same phases; their largest seconds are the
      // run's.
      std::vector<double> seconds;
      for (const auto &[phase, s] : timing)
        seconds.push_back(s);
      AssertThrow(Utilities::MPI::min(seconds.size(), world) ==
                    Utilities::MPI::max(seconds.size(), world),
                  ExcInternalError());
      std::vector<double> largest(seconds.size());
      Utilities::MPI::max(seconds, world, largest);
      unsigned int k = 0;
      for (auto &entry : timing)
        entry.second = largest[k++];

      Utilities::System::MemoryStats memory;
      Utilities::System::get_memory_stats(memory);
      const auto peaks =
        Utilities::MPI::gather(world,
                               std::pair(memory.VmHWM / 1024., factorised_here),
                               0);
      std::vector<std::pair<std::string, std::pair<double, bool>>> held;
      for (const base::MemoryItem &item : held_here)
        held.push_back({item.name, {item.bytes, item.divided}});
      const auto       all_held = Utilities::MPI::gather(world, held, 0);
      constexpr double mib      = 1024. * 1024.;
      nlohmann::json   ranks    = nlohmann::json::array();
      for (unsigned int r = 0; r < peaks.size(); ++r)
        {
          nlohmann::json items      = nlohmann::json::array();
          double         replicated = 0., divided = 0.;
          for (const auto &[name, entry] : all_held[r])
            {
              (entry.second ? divided : replicated) += entry.first;
              items.push_back({{"name", name},
                               {"mib", entry.first / mib},
                               {"divided", entry.second}});
            }
          ranks.push_back({{"rank", r},
                           {"peak_memory_mib", peaks[r].first},
                           {"factorises", peaks[r].second},
                           {"held",
                            {{"replicated_mib", replicated / mib},
                             {"divided_mib", divided / mib},
                             {"items", items}}}});
        }
      return {timing, ranks};
    }



    template std::vector<std::string>
    split_ranks_among_bodies<2>(
      const std::vector<std::unique_ptr<discretization::Body<2>>> &,
      const std::vector<double> &,
      bool,
      Communicators &,
      ConditionalOStream &);
    template std::vector<std::string>
    split_ranks_among_bodies<3>(
      const std::vector<std::unique_ptr<discretization::Body<3>>> &,
      const std::vector<double> &,
      bool,
      Communicators &,
      ConditionalOStream &);
  } // namespace scene
} // namespace igabde
