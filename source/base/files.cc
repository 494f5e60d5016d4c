#include <igabde/base/files.h>
#include <igabde/base/utilities.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>

namespace igabde
{
  namespace base
  {
    std::ofstream
    open_for_writing(const std::string &path, const std::string &setting)
    {
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
      std::ofstream out(path);
      AssertThrow(out,
                  ExcInput("cannot open '" + path + "' for writing; check " +
                           setting + "."));
      return out;
    }



    template <int dim, int spacedim>
    dealii::DataOutBase::VtkFlags
    vtu_flags(
      const std::vector<dealii::DataOutBase::Patch<dim, spacedim>> &patches)
    {
      std::size_t values = 0;
      for (const auto &patch : patches)
        values += patch.data.n_elements() +
                  spacedim * (patch.data.n_cols() > 0 ?
                                patch.data.n_cols() :
                                patch.reference_cell.n_vertices());
      dealii::DataOutBase::VtkFlags flags;
      flags.compression_level = (4 * values >= (std::size_t(1) << 20)) ?
                                  dealii::DataOutBase::VtkFlags::best_speed :
                                  dealii::DataOutBase::VtkFlags::no_compression;
      return flags;
    }



    template dealii::DataOutBase::VtkFlags
    vtu_flags(const std::vector<dealii::DataOutBase::Patch<2, 2>> &);
    template dealii::DataOutBase::VtkFlags
    vtu_flags(const std::vector<dealii::DataOutBase::Patch<3, 3>> &);
    template dealii::DataOutBase::VtkFlags
    vtu_flags(const std::vector<dealii::DataOutBase::Patch<0, 2>> &);
    template dealii::DataOutBase::VtkFlags
    vtu_flags(const std::vector<dealii::DataOutBase::Patch<0, 3>> &);



    TeeBuffer::TeeBuffer(std::streambuf *a, std::streambuf *b)
      : a(a)
      , b(b)
    {}



    int
    TeeBuffer::overflow(int c)
    {
      if (c == EOF)
        return !EOF;
      const int r1 = a->sputc(c), r2 = b->sputc(c);
      return (r1 == EOF || r2 == EOF) ? EOF : c;
    }



    int
    TeeBuffer::sync()
    {
      return (a->pubsync() == 0 && b->pubsync() == 0) ? 0 : -1;
    }



    WarningLines::WarningLines(std::streambuf *target)
      : target(target)
    {}



    WarningLines::~WarningLines()
    {
      end_line();
      target->pubsync();
    }



    int
    WarningLines::overflow(int c)
    {
      if (c == EOF)
        return !EOF;
      line.push_back(static_cast<char>(c));
      if (c == '\n')
        end_line();
      return c;
    }



    int
    WarningLines::sync()
    {
      return target->pubsync();
    }



    void
    WarningLines::end_line()
    {
      if (line.find("warning:") != std::string::npos ||
          line.find("error:") != std::string::npos)
        target->sputn(line.data(), static_cast<std::streamsize>(line.size()));
      line.clear();
    }



    void
    write_file_atomically(const std::string &path, const std::string &text)
    {
      const std::string part = path + ".part";
      {
        std::ofstream out(part);
        out << text;
      }
      std::filesystem::rename(part, path);
    }



    BackgroundWriter::~BackgroundWriter()
    {
      for (auto &job : jobs)
        try
          {
            job.second.join();
          }
        catch (...)
          {}
    }



    void
    BackgroundWriter::begin_group()
    {
      ++group;
    }



    void
    BackgroundWriter::add(std::function<void()> job)
    {
      {
        std::lock_guard<std::mutex> lock(mutex);
        ++running[group];
        update_written();
      }
      jobs.emplace_back(group,
                        dealii::Threads::new_task([this, job, g = group]() {
                          const auto start = std::chrono::steady_clock::now();
                          std::exception_ptr error;
                          try
                            {
                              job();
                            }
                          catch (...)
                            {
                              error = std::current_exception();
                            }
                          const std::chrono::duration<double> taken =
                            std::chrono::steady_clock::now() - start;
                          std::lock_guard<std::mutex> lock(mutex);
                          job_seconds += taken.count();
                          if (error)
                            {
                              errors.emplace_back(g, error);
                              if (first_failed == 0 || g < first_failed)
                                first_failed = g;
                            }
                          if (--running[g] == 0)
                            running.erase(g);
                          update_written();
                        }));
    }



    void
    BackgroundWriter::wait_all_but_last_group()
    {
      join_through(group < 2 ? 0u : group - 2);
    }



    void
    BackgroundWriter::wait()
    {
      join_through(group);
    }



    void
    BackgroundWriter::join_through(const unsigned int last)
    {
      // A job keeps what it threw (add()): join() only waits.
      std::vector<std::pair<unsigned int, dealii::Threads::Task<void>>> kept;
      for (auto &job : jobs)
        if (job.first > last)
          kept.push_back(std::move(job));
        else
          job.second.join();
      jobs.swap(kept);
      std::exception_ptr first;
      {
        // The jobs of these groups have ended: their errors, first come
        // first, are the waiter's.
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto &error : errors)
          if (error.first <= last && !first)
            first = error.second;
        errors.erase(std::remove_if(errors.begin(),
                                    errors.end(),
                                    [last](const auto &error) {
                                      return error.first <= last;
                                    }),
                     errors.end());
      }
      if (first)
        std::rethrow_exception(first);
    }



    void
    BackgroundWriter::update_written()
    {
      unsigned int w = std::numeric_limits<unsigned int>::max();
      if (!running.empty())
        w = running.begin()->first - 1;
      if (first_failed > 0)
        w = std::min(w, first_failed - 1);
      written.store(w);
    }



    unsigned int
    BackgroundWriter::written_groups() const
    {
      return written.load();
    }



    const std::atomic<unsigned int> &
    BackgroundWriter::written_groups_counter() const
    {
      return written;
    }



    double
    BackgroundWriter::seconds() const
    {
      std::lock_guard<std::mutex> lock(mutex);
      return job_seconds;
    }
  } // namespace base
} // namespace igabde
