#ifndef igabde_scene_interrupt_h
#define igabde_scene_interrupt_h

#include <atomic>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <string>
#include <utility>
#include <vector>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief While it lives, a SIGINT or SIGTERM ends the process with
     * 128 + the signal, leaving behind the summary.json last published
     * with publish_interrupted_summary() (status 'interrupted' and why),
     * its steps.csv and .pvd series, and one line on the screen and in
     * log.txt. Only the command-line run
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
     * @brief What an interruption leaves when the first @p steps load steps
     * are finished and their files written: the running summary (its
     * status and error are set when published), steps.csv and the other
     * files of the run's records, as (path, text) (the .pvd series), and
     * the run's phase for the reason.
     */
    struct InterruptedRun
    {
      unsigned int                                     steps = 0;
      nlohmann::json                                   summary;
      std::string                                      steps_csv;
      std::vector<std::pair<std::string, std::string>> files;
      std::string                                      run_phase;
    };

    /**
     * @brief Renders, in advance, what an interruption now would leave:
     * summary.json in @p output_directory with status 'interrupted' and the
     * reason (the signal and the run phase), steps.csv, the other files and
     * the screen line. @p candidates, by increasing steps, are the runs an
     * interruption may find written: the handler takes the last one whose
     * steps have all been written by then, @p group_offset plus the count
     * @p written_groups (a BackgroundWriter's, one group per step run in
     * this process), else the first. Nothing without an InterruptHandler.
     */
    void
    publish_interrupted_summary(std::vector<InterruptedRun>      candidates,
                                const std::atomic<unsigned int> *written_groups,
                                const unsigned int               group_offset,
                                const std::string &output_directory);

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
