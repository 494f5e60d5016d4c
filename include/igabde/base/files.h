#ifndef igabde_base_files_h
#define igabde_base_files_h

#include <streambuf>
#include <string>

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
  } // namespace base
} // namespace igabde

#endif
