#include <igabde/base/retain_freed_memory.h>

#include <cstddef>
#include <dlfcn.h>
#include <string>
#include <sys/types.h>

namespace igabde
{
  namespace base
  {
    namespace retain_freed_memory_detail
    {
      using mallctl_type =
        int (*)(const char *, void *, std::size_t *, void *, std::size_t);

      // jemalloc's mallctl if jemalloc serves malloc, else nullptr.
      mallctl_type
      jemalloc_mallctl()
      {
        return reinterpret_cast<mallctl_type>(dlsym(RTLD_DEFAULT, "mallctl"));
      }

      bool
      read_decay(const mallctl_type mallctl,
                 const std::string &name,
                 long              &value)
      {
        ssize_t     v    = 0;
        std::size_t size = sizeof(v);
        if (mallctl(name.c_str(), &v, &size, nullptr, 0) != 0)
          return false;
        value = v;
        return true;
      }

      void
      write_decay(const mallctl_type mallctl,
                  const std::string &name,
                  const long         value)
      {
        ssize_t v = value;
        mallctl(name.c_str(), nullptr, nullptr, &v, sizeof(v));
      }
    } // namespace retain_freed_memory_detail



    RetainFreedMemory::RetainFreedMemory()
    {
      using namespace retain_freed_memory_detail;
      const mallctl_type mallctl = jemalloc_mallctl();
      if (mallctl == nullptr)
        return;
      unsigned int n    = 0;
      std::size_t  size = sizeof(n);
      if (mallctl("arenas.narenas", &n, &size, nullptr, 0) != 0)
        return;
      // The arenas past the automatic ones: the one for allocations of
      // 8 MiB and more (opt.oversize_threshold), which purges what is
      // freed at once. The automatic arenas keep their gradual decay:
      // retaining their pages too raised the peak memory on the
      // contact-patch family's full path and gained nothing.
      const int first = large_block_arena();
      if (first < 0)
        return;
      for (unsigned int i = first; i < n; ++i)
        {
          const std::string arena = "arena." + std::to_string(i) + ".";
          Saved             s{i, 0, 0};
          if (!read_decay(mallctl, arena + "dirty_decay_ms", s.dirty) ||
              !read_decay(mallctl, arena + "muzzy_decay_ms", s.muzzy))
            continue;
          saved.push_back(s);
          write_decay(mallctl, arena + "dirty_decay_ms", -1);
          write_decay(mallctl, arena + "muzzy_decay_ms", -1);
        }
    }



    RetainFreedMemory::~RetainFreedMemory()
    {
      using namespace retain_freed_memory_detail;
      const mallctl_type mallctl = jemalloc_mallctl();
      if (mallctl == nullptr)
        return;
      for (const Saved &s : saved)
        {
          const std::string arena = "arena." + std::to_string(s.index) + ".";
          write_decay(mallctl, arena + "dirty_decay_ms", s.dirty);
          write_decay(mallctl, arena + "muzzy_decay_ms", s.muzzy);
        }
    }



    long
    RetainFreedMemory::dirty_decay(const unsigned int index)
    {
      using namespace retain_freed_memory_detail;
      const mallctl_type mallctl = jemalloc_mallctl();
      long               value   = -2;
      if (mallctl != nullptr)
        read_decay(mallctl,
                   "arena." + std::to_string(index) + ".dirty_decay_ms",
                   value);
      return value;
    }



    int
    RetainFreedMemory::large_block_arena()
    {
      using namespace retain_freed_memory_detail;
      const mallctl_type mallctl = jemalloc_mallctl();
      unsigned int       n_auto  = 0;
      std::size_t        size    = sizeof(n_auto);
      if (mallctl == nullptr ||
          mallctl("opt.narenas", &n_auto, &size, nullptr, 0) != 0)
        return -1;
      return static_cast<int>(n_auto);
    }
  } // namespace base
} // namespace igabde
