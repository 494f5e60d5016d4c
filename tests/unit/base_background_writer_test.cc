// BackgroundWriter: the output jobs run on tasks, and what a job throws (a
// file that cannot be opened, a full disk) must reach the run that waits
// for it. deal.II 9.4's Task<void>::join() does not rethrow a task's
// exception, so the writer keeps the errors itself.

#include <igabde/base/files.h>

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

TEST(BackgroundWriter, WaitRethrowsWhatAJobThrewOnce)
{
  igabde::base::BackgroundWriter writer;
  std::atomic<int>               done{0};
  writer.begin_group();
  writer.add([&done]() {
    ++done;
  });
  writer.add([]() {
    throw std::runtime_error("disk full");
  });
  writer.add([&done]() {
    ++done;
  });
  try
    {
      writer.wait();
      ADD_FAILURE() << "wait() returned although a job threw";
    }
  catch (const std::runtime_error &e)
    {
      EXPECT_STREQ(e.what(), "disk full");
    }
  // The other jobs ran to their end; the error is handed over once.
  EXPECT_EQ(done, 2);
  writer.begin_group();
  writer.add([&done]() {
    ++done;
  });
  EXPECT_NO_THROW(writer.wait());
  EXPECT_EQ(done, 3);
}



// A step's error belongs to its group: waiting for the groups before the
// last two does not see the last group's error, waiting one group later
// does.
TEST(BackgroundWriter, AnErrorIsRethrownWhenItsGroupIsWaitedFor)
{
  igabde::base::BackgroundWriter writer;
  writer.begin_group(); // group 1
  writer.add([]() {
    throw std::runtime_error("step 1");
  });
  writer.begin_group(); // group 2
  writer.add([]() {});
  EXPECT_NO_THROW(writer.wait_all_but_last_group()); // groups <= 0
  writer.begin_group();                              // group 3
  EXPECT_THROW(writer.wait_all_but_last_group(),     // groups <= 1
               std::runtime_error);
  EXPECT_NO_THROW(writer.wait());
}
