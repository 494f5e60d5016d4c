#ifndef igabde_base_files_h
#define igabde_base_files_h

#include <deal.II/base/thread_management.h>

#include <functional>
#include <mutex>
#include <streambuf>
#include <string>
#include <vector>

namespace igabde
{
  namespace base
  {
    /**
     * @brief Writes to two stream buffers at once (the screen and log.txt).
     */
    class TeeBuffer : public std::streambuf
    {
    public:
      TeeBuffer(std::streambuf *a, std::streambuf *b);

    protected:
      int
      overflow(int c) override;

      int
      sync() override;

    private:
      std::streambuf *a, *b;
    };

    /**
     * @brief Writes @p text to @p path through a neighbouring temporary file
     * and a rename, so a reader (or an interrupted run) finds either the old
     * file or the new one, never half of one.
     */
    void
    write_file_atomically(const std::string &path, const std::string &text);

    /**
     * @brief Writes files in the background while the run goes on, as
     * ASPECT writes its graphical output: each job (one file or a few) is
     * a task of deal.II's thread pool (TBB); wait() returns when every job
     * has finished and rethrows the first error one of them threw.
     *
     * A job must own copies of what it writes and only read what the run
     * does not change (the bodies' meshes and maps).
     */
    class BackgroundWriter
    {
    public:
      /// Waits for the jobs still running; their errors are dropped (the
      /// run has already ended, or is ending with an error of its own).
      ~BackgroundWriter();

      /// Starts a new group of jobs (e.g. one load step's files).
      void
      begin_group();

      /// Starts @p job as a task of the current group.
      void
      add(std::function<void()> job);

      /// Waits for the jobs of every group but the current and the one
      /// before it; rethrows the first error.
      void
      wait_all_but_last_group();

      /// Waits for every job started so far; rethrows the first error.
      void
      wait();

      /// The last group whose jobs, and all earlier groups' jobs, have
      /// been waited for (0: none).
      unsigned int
      finished_groups() const;

      /// Wall seconds the jobs have taken, summed over jobs.
      double
      seconds() const;

    private:
      /// Waits for the jobs of groups up to @p last; rethrows the first
      /// error.
      void
      join_through(const unsigned int last);

      /// Each job with its group.
      std::vector<std::pair<unsigned int, dealii::Threads::Task<void>>> jobs;
      unsigned int       group          = 0;
      unsigned int       joined_through = 0;
      mutable std::mutex mutex;
      double             job_seconds = 0.;
    };
  } // namespace base
} // namespace igabde

#endif
