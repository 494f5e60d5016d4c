#include <igabde/base/files.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace igabde
{
  namespace base
  {
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
  } // namespace base
} // namespace igabde
