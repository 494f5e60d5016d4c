#include <igabde/base/files.h>

#include <igabde/scene/interrupt.h>
#include <igabde/scene/simulator.h>
#include <igabde/scene/step_results.h>

#include <algorithm>
#include <fstream>

// What the run writes besides each step's files: summary.json, steps.csv,
// timing.txt and the .pvd series, and what an interruption would leave.

namespace igabde
{
  namespace scene
  {
    template <int dim>
    void
    Simulator<dim>::write_summary(const std::string &status,
                                  const std::string &error)
    {
      run_summary.status = status;
      if (!error.empty())
        run_summary.error = error;
      if (!root)
        return;
      std::vector<std::string> histories;
      for (const auto &h : parameters.load_path.histories)
        histories.push_back(h.first);
      const auto steps_csv = [&](const std::vector<StepRecord> &records) {
        return step_table(records,
                          histories,
                          contact_stage != nullptr,
                          parameters.finite_strain(),
                          dim);
      };
      // What an interruption now would leave: the steps whose files are
      // all written, in summary.json, steps.csv and the .pvd series; one
      // candidate for each count of steps from @p written on, of which the
      // interruption takes the largest the writer has finished by then.
      const auto publish = [&](const RunSummary &summary,
                               const std::size_t written) {
        std::vector<InterruptedRun> candidates;
        for (std::size_t k = written; k <= summary.load_steps.size(); ++k)
          {
            RunSummary part = summary;
            part.load_steps.resize(k);
            InterruptedRun run;
            run.steps     = k;
            run.summary   = to_json(part);
            run.steps_csv = steps_csv(part.load_steps);
            for (const auto &postprocessor : postprocessors)
              for (auto &file : postprocessor->series(k))
                run.files.push_back(std::move(file));
            run.run_phase =
              run_phase + (run_phase.rfind("load step", 0) != 0 ? "" :
                           k == 0 ? " (no step finished and written)" :
                                    " (steps 1.." + std::to_string(k) +
                                      " finished and written)");
            candidates.push_back(std::move(run));
          }
        publish_interrupted_summary(std::move(candidates),
                                    &writer.written_groups_counter(),
                                    resumed_steps,
                                    output_directory);
      };

      // While the run goes on, the files are refreshed at most once a
      // second (a scene of many millisecond steps spent more time creating
      // them than solving; the fields of the last steps may still be
      // being written in the background); the run's end, failed or not,
      // writes everything.
      if (status == "running" && written_once && since_written.wall_time() < 1.)
        {
          RunSummary running = run_summary;
          running.timing     = timing_seconds(timer);
          // (In 64 bits: written_groups() is the largest unsigned int when
          // nothing is being written.)
          publish(running,
                  std::min<std::size_t>(running.load_steps.size(),
                                        std::size_t(resumed_steps) +
                                          writer.written_groups()));
          return;
        }
      since_written.restart();
      written_once = true;
      // The series name finished files only. An error of a file job ends
      // the run (the failed summary's call finds no job left to wait for).
      try
        {
          writer.wait();
        }
      catch (...)
        {
          // A failed run keeps its own error; otherwise this one ends it.
          if (status != "failed")
            throw;
        }
      run_summary.output_background_seconds = writer.seconds();
      for (const auto &postprocessor : postprocessors)
        for (const auto &file :
             postprocessor->series(run_summary.load_steps.size()))
          base::write_file_atomically(file.first, file.second);
      base::write_file_atomically(output_directory + "/steps.csv",
                                  steps_csv(run_summary.load_steps));

      run_summary.timing = final_timing ? *final_timing : timing_seconds(timer);
      const nlohmann::json json = to_json(run_summary);
      base::write_file_atomically(output_directory + "/summary.json",
                                  json.dump(2) + "\n");
      if (status == "running")
        publish(run_summary, run_summary.load_steps.size());
      else
        withdraw_interrupted_summary();

      // deal.II's timing table, to a file always and to the screen at the
      // end of a run that finished unless the scene switches it off (after
      // a failure the error line stays the last one).
      timing_table.str("");
      timer.print_summary();
      std::ofstream(output_directory + "/timing.txt") << timing_table.str();
      if (parameters.output.print_timing && status == "ok")
        pcout << timing_table.str() << std::flush;
    }



    template void
    Simulator<2>::write_summary(const std::string &, const std::string &);
    template void
    Simulator<3>::write_summary(const std::string &, const std::string &);
  } // namespace scene
} // namespace igabde
