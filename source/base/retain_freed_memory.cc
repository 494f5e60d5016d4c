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
      // The defaults of arenas created later (the one for large
      // allocations is created at the first of them, and keeps a
      // negative default), then every arena in use.
      have_defaults =
        read_decay(mallctl, "arenas.dirty_decay_ms", default_dirty) &&
        read_decay(mallctl, "arenas.muzzy_decay_ms", default_muzzy);
      if (have_defaults)
        {
          write_decay(mallctl, "arenas.dirty_decay_ms", -1);
          write_decay(mallctl, "arenas.muzzy_decay_ms", -1);
        }
      unsigned int n    = 0;
      std::size_t  size = sizeof(n);
      if (mallctl("arenas.narenas", &n, &size, nullptr, 0) != 0)
        return;
      // Every arena in use, the one for large allocations included (its
      // index is among arenas.narenas once it exists); indices of arenas
      // not created yet fail to read and are skipped.
      for (unsigned int i = 0; i < n; ++i)
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
      if (have_defaults)
        {
          write_decay(mallctl, "arenas.dirty_decay_ms", default_dirty);
          write_decay(mallctl, "arenas.muzzy_decay_ms", default_muzzy);
        }
      for (const Saved &s : saved)
        {
          const std::string arena = "arena." + std::to_string(s.index) + ".";
          write_decay(mallctl, arena + "dirty_decay_ms", s.dirty);
          write_decay(mallctl, arena + "muzzy_decay_ms", s.muzzy);
        }
    }



    long
    RetainFreedMemory::dirty_decay_of_first_arena()
    {
      using namespace retain_freed_memory_detail;
      const mallctl_type mallctl = jemalloc_mallctl();
      long               value   = -2;
      if (mallctl != nullptr)
        read_decay(mallctl, "arena.0.dirty_decay_ms", value);
      return value;
    }
  } // namespace base
} // namespace igabde
