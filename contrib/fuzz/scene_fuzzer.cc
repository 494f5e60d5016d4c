// libFuzzer target over the scene reader: the bytes of a scene file go
// through the parser (parameter syntax, includes, every value check of the
// body grammar) and the size estimate (the knot vectors, control points and
// weights of the geometry builders). A scene may be refused, with one
// deal.II exception carrying the message; anything else (a crash, a
// sanitizer report, another exception type, a timeout or a memory blow-up)
// is a finding. doc/robustness.md says how to run it.

#include <igabde/scene/scene_reader.h>
#include <igabde/scene/size_estimate.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  // One scratch scene file per process, rewritten for every input.
  static const std::string file =
    "igabde-fuzz-" + std::to_string(::getpid()) + ".prm";
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char *>(data),
              static_cast<std::streamsize>(size));
  }
  try
    {
      dealii::ParameterHandler           prm;
      const igabde::scene::AllParameters parameters =
        igabde::scene::parse_scene(prm, file, {});
      const igabde::scene::SizeEstimate estimate =
        igabde::scene::estimate_size(parameters, file);
      (void)estimate.total_bytes();
    }
  catch (const dealii::ExceptionBase &)
    {
      // A refused scene: the expected outcome for most inputs.
    }
  return 0;
}
