// The light Open MPI singleton's private session base
// (igabde::base::LightMpiSingleton).

#include <igabde/base/utilities.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace
{
  std::optional<std::string>
  environment(const char *name)
  {
    const char *value = std::getenv(name);
    if (value == nullptr)
      return std::nullopt;
    return std::string(value);
  }
} // namespace



// Two runs started together once failed in MPI_Init: every isolated
// singleton used the session directory jf.0/1 under the same base, and one
// process's clean-up removed it while the other created it. Each process
// gets a base of its own, and leaves nothing behind.
TEST(LightMpiSingleton, EachProcessHasItsOwnSessionBaseAndRemovesIt)
{
  for (const char *launcher_variable :
       {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (environment(launcher_variable))
      GTEST_SKIP() << "started by an MPI launcher: no singleton";
  const char *variable = "OMPI_MCA_orte_tmpdir_base";
  const auto  outer    = environment(variable);
  unsetenv(variable);

  std::string first, second;
  {
    const igabde::base::LightMpiSingleton singleton;
    ASSERT_TRUE(environment(variable).has_value());
    first = *environment(variable);
    EXPECT_TRUE(std::filesystem::is_directory(first));
    EXPECT_TRUE(std::filesystem::is_empty(first));
    unsetenv(variable);
    const igabde::base::LightMpiSingleton another;
    ASSERT_TRUE(environment(variable).has_value());
    second = *environment(variable);
    EXPECT_NE(first, second);
  }
  EXPECT_FALSE(std::filesystem::exists(first));
  EXPECT_FALSE(std::filesystem::exists(second));

  // A base the user chose is kept and left alone.
  setenv(variable, first.c_str(), 1);
  {
    const igabde::base::LightMpiSingleton singleton;
    EXPECT_EQ(*environment(variable), first);
  }

  if (outer)
    setenv(variable, outer->c_str(), 1);
  else
    unsetenv(variable);
}
