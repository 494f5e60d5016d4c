#include <igabde/scene/interrupt.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <csignal>
#include <fcntl.h>
#include <unistd.h>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /**
       * What a SIGINT or SIGTERM leaves behind. While a run goes on, the
       * simulator keeps here, rendered in advance, the summary.json it would
       * end with if interrupted now (the finished load steps, status
       * 'interrupted' and the reason) and the line for the screen; the
       * handler only writes them out (open/write/close are
       * async-signal-safe) and ends the process with 128 + the signal. Two
       * buffers: the simulator renders into the one the handler does not
       * read, then publishes it.
       */
      struct InterruptRecord
      {
        /// Set by InterruptHandler: only the command-line run handles
        /// signals.
        bool        enabled = false;
        std::string summary_path;
        std::string steps_path;
        std::string log_path;
        /// [buffer][0: SIGINT, 1: SIGTERM]: the summary and the screen line.
        std::array<std::array<std::string, 2>, 2> summary;
        std::array<std::array<std::string, 2>, 2> line;
        /// [buffer]: steps.csv with the same steps as the summary.
        std::array<std::string, 2> steps;
        std::atomic<int>           published{-1};
      };

      InterruptRecord interrupt_record;

      extern "C" void
      write_interrupted_summary_and_exit(int signal)
      {
        const int b = interrupt_record.published.load();
        const int s = (signal == SIGINT ? 0 : 1);
        if (b >= 0)
          {
            const auto write_out = [](const std::string &path,
                                      const std::string &text) {
              const int fd =
                ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
              if (fd >= 0)
                {
                  [[maybe_unused]] const auto n =
                    ::write(fd, text.data(), text.size());
                  ::close(fd);
                }
            };
            write_out(interrupt_record.summary_path,
                      interrupt_record.summary[b][s]);
            write_out(interrupt_record.steps_path, interrupt_record.steps[b]);
            const std::string          &line = interrupt_record.line[b][s];
            [[maybe_unused]] const auto n =
              ::write(STDERR_FILENO, line.data(), line.size());
            const int log =
              ::open(interrupt_record.log_path.c_str(), O_WRONLY | O_APPEND);
            if (log >= 0)
              {
                [[maybe_unused]] const auto m =
                  ::write(log, line.data(), line.size());
                ::close(log);
              }
          }
        ::_exit(128 + signal);
      }
    } // namespace



    InterruptHandler::InterruptHandler()
    {
      interrupt_record.enabled = true;
      struct sigaction handler = {};
      handler.sa_handler       = write_interrupted_summary_and_exit;
      sigemptyset(&handler.sa_mask);
      sigaction(SIGINT, &handler, &previous_int);
      sigaction(SIGTERM, &handler, &previous_term);
    }



    InterruptHandler::~InterruptHandler()
    {
      interrupt_record.published.store(-1);
      sigaction(SIGINT, &previous_int, nullptr);
      sigaction(SIGTERM, &previous_term, nullptr);
      interrupt_record.enabled = false;
      interrupt_record.summary_path.clear();
      interrupt_record.steps_path.clear();
      interrupt_record.log_path.clear();
    }



    bool
    interrupts_handled()
    {
      return interrupt_record.enabled;
    }



    void
    publish_interrupted_summary(const nlohmann::json &summary,
                                const std::string    &steps_csv,
                                const std::string    &output_directory,
                                const std::string    &run_phase)
    {
      if (!interrupt_record.enabled)
        return;
      const int      b    = 1 - std::max(0, interrupt_record.published.load());
      nlohmann::json copy = summary;
      copy["status"]      = "interrupted";
      for (const int s : {0, 1})
        {
          const std::string reason = std::string("interrupted by ") +
                                     (s == 0 ? "SIGINT" : "SIGTERM") +
                                     " during " + run_phase;
          copy["error"]                  = reason;
          interrupt_record.summary[b][s] = copy.dump(2) + "\n";
          interrupt_record.line[b][s]    = "igabde: " + reason +
                                        "; the finished steps are in " +
                                        output_directory + "/\n";
        }
      // Set once, before the first publication: the handler reads it.
      if (interrupt_record.summary_path.empty())
        {
          interrupt_record.summary_path = output_directory + "/summary.json";
          interrupt_record.steps_path   = output_directory + "/steps.csv";
          interrupt_record.log_path     = output_directory + "/log.txt";
        }
      interrupt_record.steps[b] = steps_csv;
      interrupt_record.published.store(b);
    }



    void
    withdraw_interrupted_summary()
    {
      if (interrupt_record.enabled)
        interrupt_record.published.store(-1);
    }
  } // namespace scene
} // namespace igabde
