#ifndef igabde_scene_interrupt_h
#define igabde_scene_interrupt_h

#include <nlohmann/json.hpp>
#include <signal.h>
#include <string>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief While it lives, a SIGINT or SIGTERM ends the process with
     * 128 + the signal, leaving behind the summary.json last published
     * with publish_interrupted_summary() (status 'interrupted' and why) and
     * its steps.csv, and
     * one line on the screen and in log.txt. Only the command-line run
     * (run_scene) creates one; the previous handlers come back with its
     * destruction.
     */
    class InterruptHandler
    {
    public:
      InterruptHandler();
      ~InterruptHandler();
      InterruptHandler(const InterruptHandler &) = delete;
      InterruptHandler &
      operator=(const InterruptHandler &) = delete;

    private:
      struct sigaction previous_int, previous_term;
    };

    /**
     * @brief Renders, in advance, what an interruption now would leave: the
     * running @p summary with status 'interrupted' and the reason (the
     * signal and @p run_phase) for summary.json in @p output_directory, and
     * the screen line. Nothing without an InterruptHandler.
     */
    void
    publish_interrupted_summary(const nlohmann::json &summary,
                                const std::string    &steps_csv,
                                const std::string    &output_directory,
                                const std::string    &run_phase);

    /**
     * @brief From now on an interruption writes nothing (the run has ended
     * and written its own summary).
     */
    void
    withdraw_interrupted_summary();

    /// Whether an InterruptHandler is installed.
    bool
    interrupts_handled();
  } // namespace scene
} // namespace igabde

#endif
