#ifndef igabde_base_retain_freed_memory_h
#define igabde_base_retain_freed_memory_h

#include <vector>

namespace igabde
{
  namespace base
  {
    /**
     * @brief While an object of this class lives, jemalloc keeps the pages
     * of freed blocks of 8 MiB and more instead of returning them to the
     * kernel (the dirty and muzzy decay of its arena for such blocks set
     * to -1, "never", if that arena exists); the destructor restores the
     * decay, and with it the purging. The other arenas keep their
     * gradual decay.
     *
     * For loops that free and allocate the same large blocks again: the
     * full path's Newton iterations factorise the coupled matrix anew each
     * time, and MUMPS frees its workspace and allocates it again. With
     * jemalloc's default decay the freed workspace was partly returned
     * (all of it, at once, in the arena for allocations of 8 MiB and
     * more), so that the next factorisation faulted its pages in again
     * and the kernel zeroed them: on V7 with NURBS on the full path every
     * other factorisation ran at a markedly lower rate
     * (doc/architecture.md, "Figures behind the code's choices").
     *
     * Does nothing when jemalloc does not serve malloc (looked up at run
     * time, as base::memory_allocator() does). Not thread-safe against
     * another object of this class living at the same time in another
     * thread (the decays are per process).
     */
    class RetainFreedMemory
    {
    public:
      RetainFreedMemory();
      ~RetainFreedMemory();

      RetainFreedMemory(const RetainFreedMemory &) = delete;
      RetainFreedMemory &
      operator=(const RetainFreedMemory &) = delete;

      /**
       * @brief The dirty decay in milliseconds (-1: never; 0: at once) of
       * arena @p index, or -2 without jemalloc or without that arena.
       * For tests.
       */
      static long
      dirty_decay(const unsigned int index);

      /**
       * @brief The index of the arena for large blocks (the first past
       * jemalloc's automatic arenas), or -1 without jemalloc.
       */
      static int
      large_block_arena();

    private:
      /// Arena index, dirty decay, muzzy decay as they were.
      struct Saved
      {
        unsigned int index;
        long         dirty, muzzy;
      };
      std::vector<Saved> saved;
    };
  } // namespace base
} // namespace igabde

#endif
