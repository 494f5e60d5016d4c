#ifndef igabde_base_choice_names_h
#define igabde_base_choice_names_h

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace igabde
{
  namespace base
  {
    /**
     * @brief One enum's values with the names a scene file writes them by:
     * the one table from which a parameter's Selection pattern, its parser
     * and the enum's to_string() come, so that a new value is one new row.
     *
     * @code
     *   inline constexpr base::ChoiceNames<Path, 3> path_names = {
     *     {{Path::condensed, "condensed"}, {Path::full, "full"},
     *      {Path::automatic, "auto"}}};
     * @endcode
     * The rows' order is the order the Selection lists them in.
     */
    template <typename Enum, std::size_t n>
    using ChoiceNames = std::array<std::pair<Enum, const char *>, n>;

    /** @brief The name of @p value in @p names (an empty string if it has
     * none, which a complete table rules out). */
    template <typename Enum, std::size_t n>
    std::string
    name_of(const ChoiceNames<Enum, n> &names, const Enum value)
    {
      for (const auto &[v, name] : names)
        if (v == value)
          return name;
      return "";
    }

    /** @brief The names of @p names joined by '|': the text of a
     * dealii::Patterns::Selection. */
    template <typename Enum, std::size_t n>
    std::string
    selection_of(const ChoiceNames<Enum, n> &names)
    {
      std::string text;
      for (const auto &row : names)
        text += (text.empty() ? "" : "|") + std::string(row.second);
      return text;
    }

    /**
     * @brief The value named @p name in @p names. A Selection pattern built
     * by selection_of() has refused every other text when the scene was
     * read, so a miss is an internal error.
     */
    template <typename Enum, std::size_t n>
    Enum
    value_of(const ChoiceNames<Enum, n> &names, const std::string &name)
    {
      for (const auto &[v, text] : names)
        if (name == text)
          return v;
      throw std::invalid_argument("'" + name + "' is not one of " +
                                  selection_of(names));
    }
  } // namespace base
} // namespace igabde

#endif
