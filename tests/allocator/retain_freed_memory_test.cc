// base::RetainFreedMemory: while it lives, jemalloc's arenas keep freed
// pages (decay "never"); afterwards each arena's decay is what it was.
// Read back through jemalloc's own mallctl. This test binary is linked
// with jemalloc as the executables are (jemalloc cannot be loaded later:
// its thread-local storage is initial-exec), and only where the build
// uses jemalloc; the unit tests keep the system allocator.

#include <igabde/base/retain_freed_memory.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <dlfcn.h>
#include <memory>
#include <vector>

using igabde::base::RetainFreedMemory;

TEST(RetainFreedMemory, KeepsFreedPagesWhileItLivesAndRestoresTheDecay)
{
  const long before = RetainFreedMemory::dirty_decay_of_first_arena();
  ASSERT_NE(before, -2) << "jemalloc does not serve malloc";
  ASSERT_NE(before, -1); // jemalloc's default decays (10 s)
  {
    const RetainFreedMemory retain;
    EXPECT_EQ(RetainFreedMemory::dirty_decay_of_first_arena(), -1);
    // Large blocks freed and taken again meanwhile change nothing.
    for (int k = 0; k < 3; ++k)
      {
        std::vector<double> block(std::size_t(4) << 20, 1.);
        EXPECT_EQ(block.back(), 1.);
      }
    EXPECT_EQ(RetainFreedMemory::dirty_decay_of_first_arena(), -1);
  }
  EXPECT_EQ(RetainFreedMemory::dirty_decay_of_first_arena(), before);
  // Nested: the inner one restores "never", the outer one the default.
  {
    const auto outer = std::make_unique<RetainFreedMemory>();
    {
      const RetainFreedMemory inner;
      EXPECT_EQ(RetainFreedMemory::dirty_decay_of_first_arena(), -1);
    }
    EXPECT_EQ(RetainFreedMemory::dirty_decay_of_first_arena(), -1);
  }
  EXPECT_EQ(RetainFreedMemory::dirty_decay_of_first_arena(), before);
}
