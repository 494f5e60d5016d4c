// base::RetainFreedMemory: while it lives, jemalloc's arena for large
// blocks keeps freed pages (decay "never"); afterwards its decay is what it
// was, and the automatic arenas are never touched. Read back through
// jemalloc's own mallctl. This test binary is linked with jemalloc as the
// executables are (jemalloc cannot be loaded later: its thread-local
// storage is initial-exec), and only where the build uses jemalloc; the
// unit tests keep the system allocator.

#include <igabde/base/retain_freed_memory.h>

#include <gtest/gtest.h>

#include <memory>
#include <vector>

using igabde::base::RetainFreedMemory;

TEST(RetainFreedMemory, KeepsLargeFreedBlocksWhileItLivesAndRestoresTheDecay)
{
  const int large = RetainFreedMemory::large_block_arena();
  ASSERT_GE(large, 0) << "jemalloc does not serve malloc";
  {
    // A block of 32 MiB creates the arena for large blocks.
    std::vector<double> block(std::size_t(4) << 20, 1.);
    EXPECT_EQ(block.back(), 1.);
  }
  const long before = RetainFreedMemory::dirty_decay(large);
  const long first  = RetainFreedMemory::dirty_decay(0);
  ASSERT_NE(before, -2) << "no arena for large blocks";
  ASSERT_NE(before, -1); // jemalloc's own setting purges
  {
    const RetainFreedMemory retain;
    EXPECT_EQ(RetainFreedMemory::dirty_decay(large), -1);
    EXPECT_EQ(RetainFreedMemory::dirty_decay(0), first);
    // Large blocks freed and taken again meanwhile change nothing.
    for (int k = 0; k < 3; ++k)
      {
        std::vector<double> block(std::size_t(4) << 20, 1.);
        EXPECT_EQ(block.back(), 1.);
      }
    EXPECT_EQ(RetainFreedMemory::dirty_decay(large), -1);
  }
  EXPECT_EQ(RetainFreedMemory::dirty_decay(large), before);
  // Nested: the inner one restores "never", the outer one jemalloc's.
  {
    const auto outer = std::make_unique<RetainFreedMemory>();
    {
      const RetainFreedMemory inner;
      EXPECT_EQ(RetainFreedMemory::dirty_decay(large), -1);
    }
    EXPECT_EQ(RetainFreedMemory::dirty_decay(large), -1);
  }
  EXPECT_EQ(RetainFreedMemory::dirty_decay(large), before);
}
