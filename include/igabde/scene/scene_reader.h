#ifndef igabde_scene_scene_reader_h
#define igabde_scene_scene_reader_h

#include <igabde/scene/parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief Declares every parameter in @p prm, reads @p scene_file, applies
     * the "Section/Name" = value overrides and returns the checked
     * parameters; throws base::ExcInput with a one-line message on bad input.
     *
     * The scene reader: the file's syntax (includes, repeated entries,
     * malformed or binary files), "did you mean" for misspelled names and
     * every value check of the parameters. It needs no body, solver or
     * output (the fuzz target of contrib/fuzz links it alone).
     */
    /**
     * @brief Sets the parameter @p path ("Section/Name") of @p prm, whose
     * parameters are declared, to @p value (a `--set`); throws
     * base::ExcInput naming the nearest declared parameter when @p path is
     * not one, or the pattern when @p value does not match it.
     */
    void
    apply_override(ParameterHandler  &prm,
                   const std::string &path,
                   const std::string &value);

    AllParameters
    parse_scene(
      ParameterHandler                                       &prm,
      const std::string                                      &scene_file,
      const std::vector<std::pair<std::string, std::string>> &overrides);
  } // namespace scene
} // namespace igabde

#endif
