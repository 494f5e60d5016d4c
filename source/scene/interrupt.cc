#include <igabde/scene/interrupt.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <csignal>
#include <fcntl.h>
#include <unistd.h>
#include <vector>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /**
       * What a SIGINT or SIGTERM leaves behind. While a run goes on, the
       * simulator keeps here, rendered in advance, the files it would end
       * with if interrupted now (summary.json with the finished load steps,
       * status 'interrupted' and the reason; steps.csv; the .pvd series)
       * and the line for the screen, for each number of steps that may be
       * written by then; the handler picks the one the background writer's
       * counter allows, only writes (open/write/close are
       * async-signal-safe) and ends the process with 128 + the signal. Two
       * buffers: the simulator renders into the one the handler does not
       * read, then publishes it.
       */
      struct RenderedRun
      {
        unsigned int steps = 0;
        /// [0: SIGINT, 1: SIGTERM]: the summary and the screen line.
        std::array<std::string, 2> summary;
        std::array<std::string, 2> line;
        /// (path, text): steps.csv and the .pvd series.
        std::vector<std::pair<std::string, std::string>> files;
      };

      struct InterruptRecord
      {
        /// Set by InterruptHandler: only the command-line run handles
        /// signals.
        bool        enabled = false;
        std::string summary_path;
        std::string log_path;
        /// [buffer]: the candidates by increasing steps.
        std::array<std::vector<RenderedRun>, 2> runs;
        /// [buffer]: where the written steps are counted, and from which
        /// step.
        std::array<const std::atomic<unsigned int> *, 2> written_groups{};
        std::array<unsigned int, 2>                      group_offset{};
        std::atomic<int>                                 published{-1};
      };

      InterruptRecord interrupt_record;

      void
      write_out(const std::string &path, const std::string &text)
      {
        const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0)
          {
            [[maybe_unused]] const auto n =
              ::write(fd, text.data(), text.size());
            ::close(fd);
          }
      }

      extern "C" void
      write_interrupted_summary_and_exit(int signal)
      {
        const int b = interrupt_record.published.load();
        const int s = (signal == SIGINT ? 0 : 1);
        if (b >= 0 && !interrupt_record.runs[b].empty())
          {
            const auto &runs = interrupt_record.runs[b];
            // The steps whose files have all been written by now (in 64
            // bits: the counter is the largest unsigned int when nothing is
            // being written).
            unsigned long long written = 0;
            if (interrupt_record.written_groups[b] != nullptr)
              written = static_cast<unsigned long long>(
                          interrupt_record.written_groups[b]->load()) +
                        interrupt_record.group_offset[b];
            std::size_t k = 0;
            while (k + 1 < runs.size() && runs[k + 1].steps <= written)
              ++k;
            const RenderedRun &run = runs[k];
            write_out(interrupt_record.summary_path, run.summary[s]);
            for (const auto &file : run.files)
              write_out(file.first, file.second);
            const std::string          &line = run.line[s];
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
      interrupt_record.log_path.clear();
    }



    bool
    interrupts_handled()
    {
      return interrupt_record.enabled;
    }



    void
    publish_interrupted_summary(std::vector<InterruptedRun>      candidates,
                                const std::atomic<unsigned int> *written_groups,
                                const unsigned int               group_offset,
                                const std::string &output_directory)
    {
      if (!interrupt_record.enabled || candidates.empty())
        return;
      const int b = 1 - std::max(0, interrupt_record.published.load());
      std::vector<RenderedRun> &runs = interrupt_record.runs[b];
      runs.assign(candidates.size(), RenderedRun());
      for (std::size_t k = 0; k < candidates.size(); ++k)
        {
          InterruptedRun &candidate = candidates[k];
          nlohmann::json &copy      = candidate.summary;
          copy["status"]            = "interrupted";
          runs[k].steps             = candidate.steps;
          // Rendered once: the two signals' summaries differ in the
          // error's signal name only.
          copy["error"] = "interrupted by SIGINT during " + candidate.run_phase;
          runs[k].summary[0]     = copy.dump(2) + "\n";
          runs[k].summary[1]     = runs[k].summary[0];
          const std::string from = "\"error\": \"interrupted by SIGINT";
          const auto        at   = runs[k].summary[1].find(from);
          if (at != std::string::npos)
            runs[k].summary[1].replace(at,
                                       from.size(),
                                       "\"error\": \"interrupted by SIGTERM");
          for (const int s : {0, 1})
            runs[k].line[s] = std::string("igabde: interrupted by ") +
                              (s == 0 ? "SIGINT" : "SIGTERM") + " during " +
                              candidate.run_phase +
                              "; the finished steps are in " +
                              output_directory + "/\n";
          runs[k].files.emplace_back(output_directory + "/steps.csv",
                                     std::move(candidate.steps_csv));
          for (auto &file : candidate.files)
            runs[k].files.push_back(std::move(file));
        }
      // Set once, before the first publication: the handler reads it.
      if (interrupt_record.summary_path.empty())
        {
          interrupt_record.summary_path = output_directory + "/summary.json";
          interrupt_record.log_path     = output_directory + "/log.txt";
        }
      interrupt_record.written_groups[b] = written_groups;
      interrupt_record.group_offset[b]   = group_offset;
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
