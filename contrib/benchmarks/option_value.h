// The number a benchmark's command-line option holds. A value that is not
// a number of the asked type (or not finite, or out of the type's range)
// ends the program with one line naming the tool, the option and the value,
// and exit status 2, as igabde itself does for bad input.

#ifndef igabde_contrib_benchmarks_option_value_h
#define igabde_contrib_benchmarks_option_value_h

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <type_traits>

namespace igabde::benchmarks
{
  /// @p text read whole as a @p Number (an integer or a double); @p tool
  /// and @p option name it in the one-line error otherwise.
  template <typename Number>
  Number
  option_value(const std::string &tool,
               const std::string &option,
               const std::string &text)
  {
    Number      value{};
    const char *first  = text.data();
    const char *last   = text.data() + text.size();
    const auto  result = std::from_chars(first, last, value);
    bool        ok     = result.ec == std::errc() && result.ptr == last;
    if constexpr (std::is_floating_point_v<Number>)
      ok = ok && std::isfinite(value);
    if (!ok)
      {
        std::cerr << tool << ": " << option << ": '" << text << "' is not "
                  << (std::is_floating_point_v<Number> ? "a number" :
                      std::is_unsigned_v<Number>       ? "a whole number >= 0" :
                                                         "a whole number")
                  << "\n";
        std::exit(2);
      }
    return value;
  }

  /// Prints @p usage and ends the program with status 0 when an argument
  /// is -h or --help: every helper program answers --help.
  inline void
  answer_help(const int argc, char **argv, const char *usage)
  {
    for (int a = 1; a < argc; ++a)
      if (std::string(argv[a]) == "-h" || std::string(argv[a]) == "--help")
        {
          std::cout << usage;
          std::exit(0);
        }
  }
} // namespace igabde::benchmarks

#endif
