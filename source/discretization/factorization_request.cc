#include <igabde/discretization/factorization_request.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

// The factorisation of a set of bodies as their contact path asks it.

namespace igabde
{
  namespace discretization
  {
    template <int dim>
    FactorizationReport
    factorize_bodies(const std::vector<std::unique_ptr<Body<dim>>> &bodies,
                     const std::vector<FactorizationRequest<dim>>  &requests,
                     TimerOutput                                   &timer,
                     MPI_Comm                                       world)
    {
      AssertDimension(requests.size(), bodies.size());
      bool reads_matrix = false;
      for (const auto &request : requests)
        reads_matrix = reads_matrix || request.matrix_read_afterwards;
      if (reads_matrix)
        {
          TimerOutput::Scope t(timer, "assembly");
          for (unsigned int b = 0; b < bodies.size(); ++b)
            if (requests[b].matrix_read_afterwards)
              bodies[b]->ensure_assembled();
        }

      FactorizationReport report;
      report.seconds.assign(bodies.size(), 0.);
      report.flops.assign(bodies.size(), 0.);
      {
        TimerOutput::Scope t(timer, "factorization");
        for (unsigned int b = 0; b < bodies.size(); ++b)
          // (Collective on the body's group; the other ranks only free
          // what they will not read.)
          if (!bodies[b]->finite_strain())
            {
              Timer clock;
              // A K read no more after its factorisation keeps only the
              // rows of the support reactions, freed as soon as the
              // factorisation has read it.
              bodies[b]->factorize(requests[b].interface,
                                   !requests[b].matrix_read_afterwards);
              report.seconds[b] = clock.wall_time();
              report.flops[b] =
                (bodies[b]->factorizes_here() ? bodies[b]->factor_flops() : 0.);
            }
        for (auto &body : bodies)
          body->share_factorization();
      }
      // A factorisation that serves its load cases only would otherwise
      // stay in memory beside what comes next (the coupled system's).
      for (unsigned int b = 0; b < bodies.size(); ++b)
        if (!requests[b].solves_afterwards)
          bodies[b]->release_factorization();

      std::vector<double> largest(bodies.size());
      Utilities::MPI::max(report.seconds, world, largest);
      report.seconds = largest;
      Utilities::MPI::max(report.flops, world, largest);
      report.flops = largest;
      return report;
    }



    template FactorizationReport
    factorize_bodies(const std::vector<std::unique_ptr<Body<2>>> &,
                     const std::vector<FactorizationRequest<2>> &,
                     TimerOutput &,
                     MPI_Comm);
    template FactorizationReport
    factorize_bodies(const std::vector<std::unique_ptr<Body<3>>> &,
                     const std::vector<FactorizationRequest<3>> &,
                     TimerOutput &,
                     MPI_Comm);
  } // namespace discretization
} // namespace igabde
