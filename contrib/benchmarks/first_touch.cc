// first_touch: see `usage` below (also printed by --help).

#include "option_value.h"
#include <algorithm>
#include <chrono>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <limits>
#include <string>
#include <sys/mman.h>

namespace
{
  const char *const usage =
    R"(What writing fresh memory costs on this machine against writing memory
already mapped: the floor under a sparse factorisation that fills
gigabytes of factor and working space once (doc/performance.md, "B2 at
16x64x16"). One anonymous mapping of --gib GiB, written twice with
memset: the first pass maps every page (the kernel zeroes it, and a
virtual machine's host may have to back it), the second only writes.
With 2 MiB (transparent huge) pages and with 4 KiB pages, --repeat times
each: the first write of the first mapping (memory new to the process),
and the best first and second writes of the repeats (later mappings may
get back the pages the earlier ones returned).

Usage: build/first_touch [--gib 2] [--repeat 3]
)";
} // namespace

namespace
{
  double
  seconds_since(const std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
      .count();
  }
} // namespace

int
main(int argc, char **argv)
{
  igabde::benchmarks::answer_help(argc, argv, usage);
  using igabde::benchmarks::option_value;
  double       gib    = 2.;
  unsigned int repeat = 3;
  for (int a = 1; a < argc; ++a)
    {
      const std::string arg = argv[a];
      if (arg == "--gib" && a + 1 < argc)
        gib = option_value<double>("first_touch", arg, argv[++a]);
      else if (arg == "--repeat" && a + 1 < argc)
        repeat = option_value<unsigned int>("first_touch", arg, argv[++a]);
      else
        {
          std::cerr << "first_touch: unknown option '" << arg
                    << "' (usage: first_touch [--gib 2] [--repeat 3])\n";
          return 2;
        }
    }
  if (!(gib > 0.) || repeat == 0)
    {
      std::cerr << "first_touch: --gib must be > 0 and --repeat >= 1\n";
      return 2;
    }
  const std::size_t bytes = static_cast<std::size_t>(gib * (1u << 30));

  std::cout
    << "| pages | first write s/GiB (first mapping, best) | second write s/GiB | first mapping / second write |\n"
       "|---|---|---|---|\n";
  for (const bool huge : {true, false})
    {
      double first = std::numeric_limits<double>::max(), second = first;
      double first_of_first = 0.;
      for (unsigned int r = 0; r < repeat; ++r)
        {
          void *const p = mmap(nullptr,
                               bytes,
                               PROT_READ | PROT_WRITE,
                               MAP_PRIVATE | MAP_ANONYMOUS,
                               -1,
                               0);
          if (p == MAP_FAILED)
            {
              std::cerr << "first_touch: cannot map " << gib << " GiB\n";
              return 1;
            }
          madvise(p, bytes, huge ? MADV_HUGEPAGE : MADV_NOHUGEPAGE);
          auto start = std::chrono::steady_clock::now();
          std::memset(p, 1, bytes);
          const double t = seconds_since(start) / gib;
          if (r == 0)
            first_of_first = t;
          first = std::min(first, t);
          start = std::chrono::steady_clock::now();
          std::memset(p, 2, bytes);
          second = std::min(second, seconds_since(start) / gib);
          munmap(p, bytes);
        }
      std::cout << std::setprecision(3) << "| "
                << (huge ? "2 MiB (MADV_HUGEPAGE)" : "4 KiB (MADV_NOHUGEPAGE)")
                << " | " << first_of_first << ", " << first << " | " << second
                << " | " << std::setprecision(2) << first_of_first / second
                << " |\n";
    }
  return 0;
}
