#include <igabde/base/utilities.h>

#include <igabde/scene/scene_reader.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {



    namespace
    {
      /// Levenshtein distance, case-insensitive.
      unsigned int
      edit_distance(const std::string &a, const std::string &b)
      {
        std::vector<unsigned int> row(b.size() + 1);
        for (unsigned int j = 0; j <= b.size(); ++j)
          row[j] = j;
        for (unsigned int i = 1; i <= a.size(); ++i)
          {
            unsigned int diagonal = row[0];
            row[0]                = i;
            for (unsigned int j = 1; j <= b.size(); ++j)
              {
                const unsigned int up = row[j];
                row[j]                = std::min({row[j] + 1,
                                                  row[j - 1] + 1,
                                                  diagonal + (std::tolower(a[i - 1]) !=
                                               std::tolower(b[j - 1]))});
                diagonal              = up;
              }
          }
        return row[b.size()];
      }



      /**
       * For an undeclared entry, the message names the nearest declared
       * parameter, so that a misspelling is fixed at once.
       */
      std::string
      suggest_parameter(const ParameterHandler &prm, const std::string &message)
      {
        const std::string key = "No entry with name <";
        const auto        at  = message.find(key);
        if (at == std::string::npos)
          return message;
        const auto        end = message.find('>', at + key.size());
        const std::string name =
          message.substr(at + key.size(), end - at - key.size());
        std::ostringstream listing;
        prm.print_parameters(listing, ParameterHandler::ShortPRM);
        std::istringstream in(listing.str());
        std::string        line, best;
        unsigned int       best_distance = 1000;
        while (std::getline(in, line))
          {
            line = base::trim(line);
            if (line.rfind("set ", 0) != 0)
              continue;
            const std::string candidate =
              base::trim(line.substr(4, line.find('=') - 4));
            const unsigned int d = edit_distance(name, candidate);
            if (d < best_distance)
              {
                best_distance = d;
                best          = candidate;
              }
          }
        std::string result = message;
        if (best_distance <= std::max<std::size_t>(3, name.size() / 3))
          result += " Did you mean '" + best + "'?";
        return result + " (igabde --print-parameters lists every parameter.)";
      }



      /**
       * " Did you mean 'Section/Name'?" with the declared parameter path
       * nearest to @p path (for --set, where the whole path is known), and
       * where to find the list.
       */
      std::string
      suggest_path(const ParameterHandler &prm, const std::string &path)
      {
        std::ostringstream listing;
        prm.print_parameters(listing, ParameterHandler::ShortPRM);
        std::istringstream       in(listing.str());
        std::vector<std::string> sections;
        std::string              line, best;
        unsigned int             best_distance = 1000;
        while (std::getline(in, line))
          {
            line = base::trim(line);
            if (line.rfind("subsection ", 0) == 0)
              sections.push_back(base::trim(line.substr(11)));
            else if (line == "end" && !sections.empty())
              sections.pop_back();
            else if (line.rfind("set ", 0) == 0)
              {
                std::string candidate;
                for (const auto &section : sections)
                  candidate += section + "/";
                candidate += base::trim(line.substr(4, line.find('=') - 4));
                const unsigned int d = edit_distance(path, candidate);
                if (d < best_distance)
                  {
                    best_distance = d;
                    best          = candidate;
                  }
              }
          }
        std::string result;
        if (best_distance <= std::max<std::size_t>(3, path.size() / 3))
          result += " Did you mean '" + best + "'?";
        return result + " (igabde --print-parameters lists every parameter.)";
      }
    } // namespace



    void
    apply_override(ParameterHandler  &prm,
                   const std::string &path,
                   const std::string &value)
    {
      const std::vector<std::string> parts = base::split(path, '/');
      AssertThrow(!parts.empty(),
                  base::ExcInput("--set: '" + path +
                                 "' is not of the form "
                                 "'Section/Name=value'."));
      for (unsigned int i = 0; i + 1 < parts.size(); ++i)
        prm.enter_subsection(parts[i]);
      try
        {
          prm.set(parts.back(), value);
        }
      catch (const ExceptionBase &e)
        {
          for (unsigned int i = 0; i + 1 < parts.size(); ++i)
            prm.leave_subsection();
          std::string message = base::exception_message(e);
          // An entry deal.II does not know: name the nearest declared one.
          if (message.find("not yet declared") != std::string::npos ||
              message.find("No entry with name") != std::string::npos)
            message =
              "'" + path + "' is not a parameter." + suggest_path(prm, path);
          AssertThrow(false,
                      base::ExcInput("--set " + path + "=" + value + ": " +
                                     message));
        }
      for (unsigned int i = 0; i + 1 < parts.size(); ++i)
        prm.leave_subsection();
    }



    namespace
    {
      /**
       * Reads a .prm scene and the files it includes the way deal.II's
       * ParameterHandler will (include paths as written, relative to the
       * working directory) and refuses what it would crash on or silently
       * ignore: a file that includes itself (directly or through others),
       * an include of a folder or of a missing file. Warns, with both
       * lines, when one file sets the same parameter twice.
       */
      void
      check_prm_file(const std::string        &file,
                     std::vector<std::string> &include_stack)
      {
        for (const auto &open : include_stack)
          AssertThrow(!std::filesystem::exists(open) ||
                        !std::filesystem::equivalent(open, file),
                      base::ExcInput(include_stack.back() + ": 'include " +
                                     file +
                                     "' includes a file that is already "
                                     "being read (an include cycle); remove "
                                     "the include."));
        AssertThrow(!std::filesystem::is_directory(file),
                    base::ExcInput(
                      (include_stack.empty() ? std::string("") :
                                               include_stack.back() + ": ") +
                      "'" + file +
                      "' is a folder, not a parameter file; give the path "
                      "of a .prm file."));
        std::ifstream in(file);
        AssertThrow(in,
                    base::ExcInput(
                      (include_stack.empty() ? std::string("") :
                                               include_stack.back() + ": ") +
                      "cannot read '" + file + "'; check the path."));
        include_stack.push_back(file);
        std::vector<std::string>            sections;
        std::map<std::string, unsigned int> first_set;
        std::string                         line;
        unsigned int                        n = 0;
        while (std::getline(in, line))
          {
            ++n;
            line = base::trim(line.substr(0, line.find('#')));
            if (line.rfind("include", 0) == 0 &&
                (line.size() == 7 || std::isspace(line[7])))
              check_prm_file(base::trim(line.substr(7)), include_stack);
            else if (line.rfind("subsection", 0) == 0)
              sections.push_back(base::trim(line.substr(10)));
            else if (line == "end" && !sections.empty())
              sections.pop_back();
            else if (line.rfind("set ", 0) == 0)
              {
                std::string key;
                for (const auto &sec : sections)
                  key += sec + "/";
                key += base::trim(line.substr(4, line.find('=') - 4));
                const auto [it, inserted] = first_set.emplace(key, n);
                if (!inserted)
                  std::cerr << "igabde: warning: " << file << ":" << n << ": '"
                            << key << "' is set again (first at line "
                            << it->second << "); the value of line " << n
                            << " counts." << std::endl;
              }
          }
        include_stack.pop_back();
      }
    } // namespace



    AllParameters
    parse_scene(
      ParameterHandler                                       &prm,
      const std::string                                      &scene_file,
      const std::vector<std::pair<std::string, std::string>> &overrides)
    {
      AllParameters::declare_parameters(prm);
      AllParameters parameters;
      try
        {
          AssertThrow(std::filesystem::exists(scene_file),
                      base::ExcInput(scene_file +
                                     ": no such scene file; give the path "
                                     "of a .prm file (see prm/)."));
          const std::string extension =
            std::filesystem::path(scene_file).extension();
          const std::string format =
            (extension.empty() ? "parameter" : extension.substr(1));
          if (extension != ".xml" && extension != ".json")
            {
              std::vector<std::string> include_stack;
              check_prm_file(scene_file, include_stack);
            }
          try
            {
              prm.parse_input(scene_file);
            }
          catch (const ParameterHandler::ExcNoSubsection &e)
            {
              // deal.II's "Line <n> of file <f>: There is no such
              // subsection to be entered: name", said as a sentence.
              const std::string text = base::exception_message(e);
              const auto        at   = text.find("entered: ");
              const std::string name = at == std::string::npos ?
                                         text :
                                         base::trim(text.substr(at + 9));
              const auto        line = text.find("Line <");
              const std::string where =
                line == std::string::npos ?
                  std::string() :
                  " (line " +
                    text.substr(line + 6, text.find('>', line) - line - 6) +
                    ")";
              AssertThrow(
                false,
                base::ExcInput(
                  scene_file + ": there is no section '" + name + "'" + where +
                  (name.rfind("Body ", 0) == 0 ?
                     ": igabde models up to " + std::to_string(max_bodies) +
                       " bodies, 'Body 1' ... 'Body " +
                       std::to_string(max_bodies) + "'." :
                     "; igabde --print-parameters lists the sections.")));
            }
          catch (const ExceptionBase &)
            {
              throw;
            }
          catch (const std::exception &e)
            {
              // Boost's XML/JSON readers throw their own exceptions.
              AssertThrow(false,
                          base::ExcInput(
                            scene_file + ": not a readable " + format +
                            " parameter file (" + e.what() +
                            "); write it as 'igabde --print-parameters " +
                            format + "' does."));
            }
          for (const auto &[path, value] : overrides)
            apply_override(prm, path, value);
          parameters.parse_parameters(prm, scene_file);
        }
      catch (const ExceptionBase &e)
        {
          std::string message =
            suggest_parameter(prm, base::exception_message(e));
          if (message.find(scene_file) == std::string::npos)
            message = scene_file + ": " + message;
          throw base::ExcInput(message);
        }
      if (parameters.name.empty())
        parameters.name = std::filesystem::path(scene_file).stem();
      if (parameters.output.directory.empty())
        parameters.output.directory = "output/" + parameters.name;
      return parameters;
    }
  } // namespace scene
} // namespace igabde
