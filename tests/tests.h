// Minimal counterpart of deal.II's tests/tests.h for igabde's output tests:
// attaches deallog to the file `output` that the test harness compares.
#ifndef igabde_tests_tests_h
#define igabde_tests_tests_h

#include <deal.II/base/logstream.h>

#include <fstream>
#include <iomanip>

using namespace dealii;

std::ofstream logfile("output");

inline void
initlog()
{
  deallog.attach(logfile);
  deallog.depth_console(0);
  deallog << std::setprecision(6);
}

#endif
