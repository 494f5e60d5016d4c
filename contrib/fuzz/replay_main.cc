// Replays files (or every file of folders) through the fuzz target without
// libFuzzer: the corpus test of ctest, built with the ordinary compiler.
// A finding aborts (sanitizer build) or escapes as an exception.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size);

#ifdef IGABDE_SANITIZE
// As in the executable: OpenMPI's loaded components leak at exit from frames
// LeakSanitizer cannot name, so leak checking is off; ASan and UBSan stay on.
extern "C" const char *
__asan_default_options()
{
  return "detect_leaks=0";
}
#endif

int
main(int argc, char **argv)
{
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i)
    {
      const std::filesystem::path p(argv[i]);
      if (std::filesystem::is_directory(p))
        {
          for (const auto &entry :
               std::filesystem::recursive_directory_iterator(p))
            if (entry.is_regular_file())
              files.push_back(entry.path());
        }
      else
        files.push_back(p);
    }
  for (const auto &f : files)
    {
      std::ifstream           in(f, std::ios::binary);
      const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                    std::istreambuf_iterator<char>());
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t *>(
                               bytes.data()),
                             bytes.size());
    }
  std::cout << "replayed " << files.size() << " inputs" << std::endl;
  return files.empty() ? 1 : 0;
}
