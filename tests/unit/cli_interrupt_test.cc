// A run ended by SIGINT or SIGTERM at any moment keeps every load step that
// finished and whose files are written, and its records agree with the
// files on disk: summary.json, steps.csv and every .pvd series name the
// same steps, and every file they name is there and complete.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

namespace cli_interrupt
{
  std::string
  scene_path(const std::string &name)
  {
    return cli::join(cli::join(std::string(IGABDE_SOURCE_DIR), "prm"), name);
  }

  std::string
  step_number(const std::size_t step)
  {
    char number[8];
    std::snprintf(number, sizeof(number), "%04zu", step);
    return number;
  }

  /// Whether @p path holds a whole VTU file (deal.II ends it so).
  bool
  complete_vtu(const std::string &path)
  {
    if (!std::filesystem::exists(path))
      return false;
    const std::string text = cli::read_file(path);
    return text.find("</VTKFile>") != std::string::npos;
  }

  /**
   * The files of step @p step of a run with contact and VTU output in
   * @p out, for the bodies @p bodies: all there and complete.
   */
  bool
  step_files_written(const std::string              &out,
                     const std::vector<std::string> &bodies,
                     const std::size_t               step)
  {
    const std::string n = step_number(step);
    if (!std::filesystem::exists(cli::join(out, "contact-" + n + ".csv")) ||
        !complete_vtu(cli::join(out, "contact-" + n + ".vtu")))
      return false;
    for (const auto &body : bodies)
      if (!complete_vtu(cli::join(out, "solution-" + body + "-" + n + ".vtu")))
        return false;
    return true;
  }

  /**
   * Runs @p arguments in @p folder, sends @p signal after @p delay seconds
   * and checks what is left in out/ against itself and against the
   * @p n_steps steps the run would take; returns the steps kept.
   */
  std::size_t
  interrupt_and_check(const std::string              &folder,
                      const std::string              &arguments,
                      const std::vector<std::string> &bodies,
                      const std::size_t               n_steps,
                      const double                    delay,
                      const std::string              &signal)
  {
    std::filesystem::remove_all(cli::join(folder, "out"));
    char seconds[32];
    std::snprintf(seconds, sizeof(seconds), "%.3f", delay);
    const auto result = cli::run_in(
      folder,
      cli::executable() + " " + arguments +
        " --set 'Output/Directory=out' > screen.txt 2>&1 & pid=$!; sleep " +
        seconds + "; kill -" + signal + " $pid 2> /dev/null; wait $pid;" +
        " echo \"exit $?\"");
    const std::string out = cli::join(folder, "out");
    // A signal before the run has written anything (while the process
    // loads) leaves nothing: no record, no file.
    if (!std::filesystem::exists(cli::join(out, "summary.json")))
      {
        EXPECT_NE(result.output.find(signal == "INT" ? "exit 130" : "exit 143"),
                  std::string::npos)
          << result.output;
        EXPECT_FALSE(std::filesystem::exists(cli::join(out, "steps.csv")));
        EXPECT_FALSE(step_files_written(out, bodies, 1));
        return 0;
      }
    const nlohmann::json summary =
      nlohmann::json::parse(cli::read_file(cli::join(out, "summary.json")));
    const std::string status = summary.at("status");
    // (Absent while no step has finished.)
    const nlohmann::json steps_done =
      summary.value("load_steps", nlohmann::json::array());
    const std::size_t kept = steps_done.size();
    if (status == "ok")
      {
        // Finished before the signal, or the signal came after the last
        // record while the process was ending (freeing its memory,
        // MPI_Finalize): the records are the whole run either way.
        EXPECT_TRUE(
          result.output.find("exit 0") != std::string::npos ||
          result.output.find(signal == "INT" ? "exit 130" : "exit 143") !=
            std::string::npos)
          << result.output;
        EXPECT_EQ(kept, n_steps);
      }
    else
      {
        EXPECT_EQ(status, "interrupted") << summary.dump(2);
        EXPECT_NE(result.output.find(signal == "INT" ? "exit 130" : "exit 143"),
                  std::string::npos)
          << result.output;
        EXPECT_LT(kept, n_steps + 1);
      }
    // The step records are the steps 1..kept, in order.
    for (std::size_t s = 0; s < kept; ++s)
      EXPECT_EQ(steps_done[s].at("step"), s + 1);
    // steps.csv: the header and one row per kept step.
    const std::string steps = cli::read_file(cli::join(out, "steps.csv"));
    EXPECT_EQ(static_cast<std::size_t>(
                std::count(steps.begin(), steps.end(), '\n')),
              kept + 1)
      << steps;
    // Every .pvd series names exactly the kept steps, each file there and
    // whole; with no step kept there is no series.
    std::vector<std::string> series = {"contact"};
    for (const auto &body : bodies)
      series.push_back("solution-" + body);
    for (const auto &name : series)
      {
        const std::string pvd = cli::join(out, name + ".pvd");
        if (kept == 0)
          {
            EXPECT_FALSE(std::filesystem::exists(pvd)) << pvd;
            continue;
          }
        EXPECT_TRUE(std::filesystem::exists(pvd)) << pvd;
        const std::string        text = cli::read_file(pvd);
        const std::regex         data_set("file=\"([^\"]+)\"");
        std::vector<std::string> files;
        for (auto it = std::sregex_iterator(text.begin(), text.end(), data_set);
             it != std::sregex_iterator();
             ++it)
          files.push_back((*it)[1]);
        EXPECT_EQ(files.size(), kept) << text;
        for (std::size_t s = 0; s < files.size(); ++s)
          {
            EXPECT_EQ(files[s], name + "-" + step_number(s + 1) + ".vtu");
            EXPECT_TRUE(complete_vtu(cli::join(out, files[s]))) << files[s];
          }
      }
    // Every kept step's files are on disk; a later step's files may have
    // been finished by the writer's threads while the signal was handled,
    // but only those of the two steps the writer keeps in flight.
    for (std::size_t s = 1; s <= kept; ++s)
      EXPECT_TRUE(step_files_written(out, bodies, s)) << "step " << s;
    for (std::size_t s = kept + 3; s <= n_steps; ++s)
      EXPECT_FALSE(step_files_written(out, bodies, s)) << "step " << s;
    return kept;
  }

  /**
   * Times one uninterrupted run of @p arguments, then interrupts it at
   * @p moments moments spread over that time (SIGINT and SIGTERM in turn)
   * and checks each; the kept steps must cover 0 .. all.
   */
  void
  interrupt_at_many_moments(const std::string              &name,
                            const std::string              &arguments,
                            const std::vector<std::string> &bodies,
                            const std::size_t               n_steps,
                            const unsigned int              moments)
  {
    const cli::ScratchFolder folder(name, "interrupt");
    const auto               start = std::chrono::steady_clock::now();
    const auto               full =
      cli::run_in(folder,
                  cli::executable() + " " + arguments +
                    " --set 'Output/Directory=out' > screen.txt 2>&1");
    const double total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
    ASSERT_EQ(full.status, 0)
      << cli::read_file(cli::join(folder.path, "screen.txt"));
    std::vector<std::size_t> kept;
    for (unsigned int i = 0; i < moments; ++i)
      {
        const double delay = total * (i + 0.5) / moments;
        SCOPED_TRACE("signal after " + std::to_string(delay) + " s of " +
                     std::to_string(total));
        kept.push_back(interrupt_and_check(folder.path,
                                           arguments,
                                           bodies,
                                           n_steps,
                                           delay,
                                           i % 2 ? "TERM" : "INT"));
      }
    // The moments reach from before the first step to the last ones.
    EXPECT_EQ(*std::min_element(kept.begin(), kept.end()), 0u);
    EXPECT_GE(*std::max_element(kept.begin(), kept.end()), n_steps - 1);
  }
} // namespace cli_interrupt



TEST(CliInterrupt, TwentyMomentsOfAFiveStep2dRun)
{
  // V4's block slid in five steps, its pair and field files every step (on
  // the full path, about half a second a step).
  cli_interrupt::interrupt_at_many_moments(
    "v4",
    "'" + cli_interrupt::scene_path("v4-sliding-block.prm") +
      "' --set Discretization/Refinements=4 --set Contact/Path=full"
      " --set 'Load path/Load factors=1, 1, 1, 1, 1'"
      " --set 'Load path/Displacement factors=0, 0.25, 0.5, 0.75, 1'",
    {"body1"},
    5,
    20);
}



TEST(CliInterrupt, TwentyMomentsOfAThreeStep3dRun)
{
  // The 3D contact patch pressed in three steps (on the full path).
  cli_interrupt::interrupt_at_many_moments(
    "v3-3d",
    "'" + cli_interrupt::scene_path("v3-contact-patch-3d.prm") +
      "' --set Discretization/Refinements=3 --set Contact/Path=full"
      " --set 'Load path/Load factors=0.4, 0.7, 1'",
    {"body1", "body2"},
    3,
    20);
}
