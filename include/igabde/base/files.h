#ifndef igabde_base_files_h
#define igabde_base_files_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/thread_management.h>

#include <atomic>
#include <exception>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
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
     * @brief A stream buffer that passes to @p target only the lines that
     * are warnings or errors (that contain "warning:" or "error:"), whole:
     * the screen of a run with --quiet, beside a log file that keeps every
     * line.
     */
    class WarningLines : public std::streambuf
    {
    public:
      explicit WarningLines(std::streambuf *target);

      ~WarningLines() override;

    protected:
      int
      overflow(int c) override;

      int
      sync() override;

    private:
      /// Passes the line held so far on when it is a warning or an error.
      void
      end_line();

      std::streambuf *target;
      std::string     line;
    };

    /**
     * @brief Writes @p text to @p path through a neighbouring temporary file
     * and a rename, so a reader (or an interrupted run) finds either the old
     * file or the new one, never half of one.
     */
    void
    write_file_atomically(const std::string &path, const std::string &text);

    /**
     * @brief Opens @p path for writing, removing a file of that name first:
     * a new file costs less than truncating an old one does on ext4,
     * which flushes a truncated-and-rewritten file when it is closed
     * (doc/performance.md), and a scene run again into its own folder
     * meets its old files every time. A file that cannot be opened throws
     * base::ExcInput naming the path and the parameter @p setting that
     * chose it.
     */
    std::ofstream
    open_for_writing(const std::string &path,
                     const std::string &setting = "Output/Directory");

    /**
     * @brief The VTU flags of every field file igabde writes: binary, and
     * zlib-compressed at its fastest level only when the file's data
     * (points and values, 4 bytes each) reach 1 MiB. Below that, zlib's
     * set-up per data array costs more time than the smaller file saves
     * (a 2D body of 800 points); above it the files shrink severalfold for
     * a small rise in writing time (doc/performance.md).
     */
    template <int dim, int spacedim>
    dealii::DataOutBase::VtkFlags
    vtu_flags(
      const std::vector<dealii::DataOutBase::Patch<dim, spacedim>> &patches);

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

      /**
       * @brief The last group before the first one with a job still running
       * or failed: every job of groups 1..written_groups() has ended and
       * written its files (a group being filled counts once its jobs end;
       * with no job running or failed, the largest unsigned int). An atomic
       * read, safe in a signal handler (written_groups_counter()).
       */
      unsigned int
      written_groups() const;

      /// The counter written_groups() reads, for a signal handler.
      const std::atomic<unsigned int> &
      written_groups_counter() const;

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
      /// What the jobs threw, with their group. Kept here because
      /// deal.II 9.4's Task<void>::join() does not rethrow a task's
      /// exception (its void result is never read from the future): an
      /// output file that could not be written ended as a silent "ok".
      std::vector<std::pair<unsigned int, std::exception_ptr>> errors;

      /// Recomputes written (under the mutex).
      void
      update_written();

      unsigned int group = 0;
      /// Jobs still running, per group (under the mutex).
      std::map<unsigned int, unsigned int> running;
      /// The first group a job of which failed (0: none).
      unsigned int              first_failed = 0;
      std::atomic<unsigned int> written{
        std::numeric_limits<unsigned int>::max()};
      mutable std::mutex mutex;
      double             job_seconds = 0.;
    };
  } // namespace base
} // namespace igabde

#endif
