// Running the igabde executable from the command-line tests.
#ifndef igabde_tests_unit_cli_helpers_h
#define igabde_tests_unit_cli_helpers_h

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace cli
{
  /**
   * A scratch folder below the system's temporary folder, named
   * igabde-<prefix>-<name>-<pid>, emptied on creation and removed with
   * everything in it when the test ends (also when an assertion fails).
   */
  struct ScratchFolder
  {
    /// The folder's path.
    std::string path;

    explicit ScratchFolder(const std::string &name,
                           const std::string &prefix = "cli")
      : path(
          (std::filesystem::temp_directory_path() /
           ("igabde-" + prefix + "-" + name + "-" + std::to_string(getpid())))
            .string())
    {
      std::filesystem::remove_all(path);
      std::filesystem::create_directories(path);
    }

    ScratchFolder(const ScratchFolder &) = delete;
    ScratchFolder &
    operator=(const ScratchFolder &) = delete;

    ~ScratchFolder()
    {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }

    /// The folder, so that a ScratchFolder reads as the path it holds.
    operator const std::string &() const
    {
      return path;
    }
  };

  /// Exit status and the merged stdout+stderr of a command.
  struct RunResult
  {
    int         status = -1;
    std::string output;
  };

  /// Runs the shell command @p command inside @p folder (created if
  /// needed); the command is grouped, so '&' and ';' in it stay there.
  inline RunResult
  run_in(const std::string &folder, const std::string &command)
  {
    std::filesystem::create_directories(folder);
    const std::string full =
      "cd '" + folder + "' && { " + command + " ; } 2>&1";
    RunResult              result;
    FILE                  *pipe = popen(full.c_str(), "r");
    std::array<char, 4096> buffer;
    while (fgets(buffer.data(), buffer.size(), pipe) != nullptr)
      result.output += buffer.data();
    result.status = WEXITSTATUS(pclose(pipe));
    return result;
  }

  /**
   * The igabde executable the tests run: the environment variable
   * IGABDE_EXECUTABLE if set (the sanitizer job of contrib/run-tests runs
   * these tests with the AddressSanitizer build's executable), else the one
   * built beside the tests.
   */
  inline std::string
  executable()
  {
    const char *env = std::getenv("IGABDE_EXECUTABLE");
    return env != nullptr && *env != '\0' ? env : IGABDE_EXECUTABLE;
  }

  /// Runs igabde with @p arguments in @p folder.
  inline RunResult
  run_igabde(const std::string &arguments, const std::string &folder)
  {
    return run_in(folder, executable() + " " + arguments);
  }

  /**
   * @p folder and the relative path @p relative joined by the filesystem
   * library (so that no path in the sources starts at the root).
   */
  inline std::string
  join(const std::string &folder, const std::string &relative)
  {
    return (std::filesystem::path(folder) / relative).string();
  }

  /// What a run of a scene left: exit status, output and summary.json
  /// (null when the run wrote none).
  struct SceneRun
  {
    int            status = -1;
    std::string    output;
    nlohmann::json summary;
  };

  /**
   * Runs the scene prm/@p scene of the source tree in @p folder, quiet,
   * its output in @p folder/out without VTU files or the timing table,
   * with the further arguments @p sets (e.g. "--set 'Body 1/...'").
   */
  inline SceneRun
  run_prm_scene(const std::string &folder,
                const std::string &scene,
                const std::string &sets = "")
  {
    const RunResult result = run_igabde(
      "'" + join(std::string(IGABDE_SOURCE_DIR), "prm/" + scene) +
        "' --quiet --set 'Output/Directory=out' --set 'Output/Write vtu=false' "
        "--set 'Output/Print timing=false' " +
        sets,
      folder);
    SceneRun run;
    run.status = result.status;
    run.output = result.output;
    std::ifstream in(join(folder, "out/summary.json"));
    if (in)
      run.summary = nlohmann::json::parse(in, nullptr, false);
    return run;
  }

  inline std::string
  read_file(const std::string &path)
  {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)),
                       std::istreambuf_iterator<char>());
  }

  /// The rows of the CSV file @p path split at commas (the header first);
  /// no quoting, as igabde writes none.
  inline std::vector<std::vector<std::string>>
  read_csv(const std::string &path)
  {
    std::vector<std::vector<std::string>> rows;
    std::ifstream                         in(path);
    std::string                           line;
    while (std::getline(in, line))
      {
        rows.emplace_back();
        std::stringstream s(line);
        std::string       cell;
        while (std::getline(s, cell, ','))
          rows.back().push_back(cell);
      }
    return rows;
  }

  /// A CSV table whose columns are found by their header names.
  struct CsvTable
  {
    std::vector<std::string>              header;
    std::vector<std::vector<std::string>> rows; ///< without the header

    /// The index of column @p name; a test failure (and column 0) when
    /// the table has none.
    std::size_t
    column(const std::string &name) const
    {
      for (std::size_t c = 0; c < header.size(); ++c)
        if (header[c] == name)
          return c;
      ADD_FAILURE() << "the table has no column " << name;
      return 0;
    }

    /// The entry of row @p row (0: the first after the header) in column
    /// @p name, as a number ("nan" reads as NaN).
    double
    number(const std::size_t row, const std::string &name) const
    {
      return std::stod(rows.at(row).at(column(name)));
    }
  };

  /// read_csv() with the first row as the header.
  inline CsvTable
  read_table(const std::string &path)
  {
    auto rows = read_csv(path);
    EXPECT_FALSE(rows.empty()) << path << " is empty or missing";
    CsvTable table;
    if (!rows.empty())
      {
        table.header = rows.front();
        table.rows.assign(rows.begin() + 1, rows.end());
      }
    return table;
  }
  /// A shipped scene's summary.json and one of its CSV tables.
  struct SceneTable
  {
    nlohmann::json summary;
    CsvTable       table;
  };

  /**
   * Runs prm/@p scene in a scratch folder @p name of @p group (removed
   * afterwards) as run_prm_scene() does, expects exit status 0, and reads
   * summary.json and the table @p table (relative to the folder).
   */
  inline SceneTable
  run_prm_scene_table(const std::string &name,
                      const std::string &group,
                      const std::string &scene,
                      const std::string &sets,
                      const std::string &table = "out/contact-0001.csv")
  {
    const ScratchFolder scratch(name, group);
    const SceneRun      run = run_prm_scene(scratch.path, scene, sets);
    EXPECT_EQ(run.status, 0) << run.output;
    SceneTable result;
    result.summary = run.summary;
    result.table   = read_table(join(scratch.path, table));
    return result;
  }

  /**
   * Writes @p text to @p folder/scene.prm and runs it as run_prm_scene()
   * runs a shipped scene; expects exit status 0 and returns summary.json.
   */
  inline nlohmann::json
  run_scene_text(const std::string &folder, const std::string &text)
  {
    std::ofstream(join(folder, "scene.prm")) << text;
    const RunResult result =
      run_igabde("scene.prm --quiet --set 'Output/Directory=out' "
                 "--set 'Output/Write vtu=false'",
                 folder);
    EXPECT_EQ(result.status, 0) << result.output;
    std::ifstream in(join(folder, "out/summary.json"));
    return in ? nlohmann::json::parse(in, nullptr, false) : nlohmann::json();
  }


  /**
   * Runs igabde with @p arguments in @p folder and expects it refused with
   * exit status 2 and one line of output that says @p says.
   */
  inline void
  expect_refused(const std::string &arguments,
                 const std::string &folder,
                 const std::string &says)
  {
    SCOPED_TRACE(arguments);
    const auto result = run_igabde(arguments, folder);
    EXPECT_EQ(result.status, 2) << result.output;
    EXPECT_EQ(result.output.find('\n'), result.output.size() - 1)
      << result.output;
    EXPECT_NE(result.output.find(says), std::string::npos) << result.output;
  }
} // namespace cli

#endif
