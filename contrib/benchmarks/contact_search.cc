// contact_search: see `usage` below (also printed by --help).

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <igabde/contact/contact_surface.h>
#include <igabde/contact/pairing.h>

#include <deal.II/base/mpi.h>

#include "option_value.h"
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  const char *const usage =
    R"(What the contact search costs as the pairs grow: the set-up of the
pairs of two 3D plates, the upper [0, 1]^2 x [0, 0.2] on the lower
[0, 1]^2 x [-0.2, 0], with non-matching meshes (the lower one has 0.7
times the upper's spans per direction), from about 10^2 to 10^5 pairs.

The master surface's candidate points go into an R-tree
(base::NearestPoints, Boost.Geometry); each slave point's nearest
candidate starts the closest-point projection on the master's exact
surface (node-to-surface), or every quadrature point of the slave face is
projected and the slave elements are cut at the master's element edges
(weighted gap). Timed: building the master surface (its candidates and
tree; "index s") and the pairing itself ("pairing s"), on one core; the
bodies' spaces are built beforehand and nothing is assembled. The
exponent is the least-squares slope of log(index + pairing seconds)
against log(pairs) over the rows of each pairing and discretisation;
n log n over 10^2..10^5 fits a slope of about 1.1.

Usage: build/contact_search [--max-pairs 100000] [--repeat 1]
           [--pairings node-to-surface,weighted-gap]
           [--types nurbs,lagrange]
)";

  using namespace dealii;
  using namespace igabde;

  double
  seconds_since(const std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
      .count();
  }



  /// A plate [0, 1]^2 x [z0, z0 + 0.2], @p n x @p n x 1 spans, degree 2.
  discretization::BodyDescription<3>
  plate(const std::string &name, const double z0, const unsigned int n)
  {
    discretization::BodyDescription<3> d;
    d.name                    = name;
    d.material.youngs_modulus = 1000.;
    d.material.poisson_ratio  = 0.3;
    d.geometry =
      nurbs::make_box<3>(Point<3>(0., 0., z0), Point<3>(1., 1., z0 + 0.2));
    nurbs::elevate_to_degree(d.geometry, 2);
    nurbs::subdivide(d.geometry, std::array<unsigned int, 3>{{n, n, 1}});
    return d;
  }



  /// Spans (NURBS) or cells (FE_Q(2)) per direction of the upper plate for
  /// about @p pairs pairs: (n + 2)^2 Greville points, (2 n + 1)^2 nodes.
  unsigned int
  spans_for(const discretization::Type type, const double pairs)
  {
    return type == discretization::Type::nurbs ?
             static_cast<unsigned int>(std::lround(std::sqrt(pairs) - 2.)) :
             static_cast<unsigned int>(
               std::lround(0.5 * (std::sqrt(pairs) - 1.)));
  }



  std::vector<std::string>
  split(const std::string &text)
  {
    std::vector<std::string> parts;
    std::stringstream        s(text);
    std::string              part;
    while (std::getline(s, part, ','))
      parts.push_back(part);
    return parts;
  }
} // namespace



int
main(int argc, char **argv)
{
  benchmarks::answer_help(argc, argv, usage);
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  double                           max_pairs = 1e5;
  unsigned int                     repeat    = 1;
  std::string                      pairings  = "node-to-surface,weighted-gap";
  std::string                      types     = "nurbs,lagrange";
  for (int a = 1; a < argc; ++a)
    {
      const std::string arg = argv[a];
      if (arg == "--max-pairs" && a + 1 < argc)
        max_pairs =
          benchmarks::option_value<double>("contact_search", arg, argv[++a]);
      else if (arg == "--repeat" && a + 1 < argc)
        repeat = benchmarks::option_value<unsigned int>("contact_search",
                                                        arg,
                                                        argv[++a]);
      else if (arg == "--pairings" && a + 1 < argc)
        pairings = argv[++a];
      else if (arg == "--types" && a + 1 < argc)
        types = argv[++a];
      else
        {
          std::cerr << "contact_search: unknown option '" << arg
                    << "' (see --help)\n";
          return 2;
        }
    }
  if (!(max_pairs >= 100.) || repeat == 0)
    {
      std::cerr << "contact_search: --max-pairs must be >= 100 and --repeat "
                   ">= 1\n";
      return 2;
    }

  std::cout << "| pairing | type | slave spans | master spans | pairs | "
               "index s | pairing s | us per pair |\n"
               "|---|---|---|---|---|---|---|---|\n";
  for (const std::string &pairing_name : split(pairings))
    for (const std::string &type_name : split(types))
      {
        const contact::Pairing pairing =
          base::value_of(contact::pairing_names, pairing_name);
        const discretization::Type type =
          base::value_of(discretization::type_names, type_name);
        std::vector<double> log_pairs, log_seconds;
        for (double target = 100.; target <= max_pairs * 1.0001;
             target *= std::sqrt(10.))
          {
            const unsigned int n = spans_for(type, target);
            const unsigned int m =
              std::max(1u, static_cast<unsigned int>(std::lround(0.7 * n)));
            discretization::DiscretizationSettings settings;
            settings.type   = type;
            settings.degree = 2;
            // The spaces only: no rank factorises, nothing is assembled.
            discretization::ParallelLayout layout;
            layout.group             = MPI_COMM_NULL;
            layout.matrix_everywhere = false;
            std::vector<std::unique_ptr<discretization::Body<3>>> bodies;
            bodies.push_back(
              discretization::create_body<3>(plate("upper", 0., n), settings));
            bodies.push_back(
              discretization::create_body<3>(plate("lower", -0.2, m),
                                             settings));
            for (auto &body : bodies)
              {
                body->set_parallel_layout(layout);
                body->setup_system();
              }
            double      index_seconds = 1e300, pairing_seconds = 1e300;
            std::size_t n_pairs = 0;
            for (unsigned int r = 0; r < repeat; ++r)
              {
                auto       start  = std::chrono::steady_clock::now();
                const auto master = std::make_unique<contact::BodyFace<3>>(
                  *bodies[1],
                  std::vector<types::boundary_id>{5});
                index_seconds = std::min(index_seconds, seconds_since(start));
                const auto strategy =
                  contact::create_pairing_strategy<3>(pairing);
                start            = std::chrono::steady_clock::now();
                const auto pairs = strategy->make_pairs(*bodies[0],
                                                        {4},
                                                        *master,
                                                        "contact_search");
                pairing_seconds =
                  std::min(pairing_seconds, seconds_since(start));
                n_pairs = pairs.size();
              }
            const double total = index_seconds + pairing_seconds;
            log_pairs.push_back(std::log(double(n_pairs)));
            log_seconds.push_back(std::log(total));
            std::cout << "| " << pairing_name << " | " << type_name << " | "
                      << n << " x " << n << " | " << m << " x " << m << " | "
                      << n_pairs << " | " << std::setprecision(3)
                      << index_seconds << " | " << pairing_seconds << " | "
                      << std::fixed << std::setprecision(1)
                      << 1e6 * total / n_pairs << std::defaultfloat << " |"
                      << std::endl;
          }
        // Least-squares slope of log seconds against log pairs.
        const double k  = log_pairs.size();
        double       sx = 0., sy = 0., sxx = 0., sxy = 0.;
        for (std::size_t i = 0; i < log_pairs.size(); ++i)
          {
            sx += log_pairs[i];
            sy += log_seconds[i];
            sxx += log_pairs[i] * log_pairs[i];
            sxy += log_pairs[i] * log_seconds[i];
          }
        std::cout << "| " << pairing_name << " | " << type_name
                  << " | exponent | | | | | " << std::setprecision(3)
                  << (k * sxy - sx * sy) / (k * sxx - sx * sx) << " |"
                  << std::endl;
      }
  return 0;
}
