// OpenBLAS on one thread for small dense matrices
// (igabde::base::SerialDenseAlgebra).

#include <igabde/base/utilities.h>

#include <gtest/gtest.h>

#include <dlfcn.h>

namespace serial_dense_algebra_test
{
  using get_type = int (*)();
  using set_type = void (*)(int);

  get_type
  openblas_get()
  {
    return reinterpret_cast<get_type>(
      dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  }

  set_type
  openblas_set()
  {
    return reinterpret_cast<set_type>(
      dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  }
} // namespace serial_dense_algebra_test



// Below serial_dense_rows the guard runs OpenBLAS on one thread and gives
// the process its thread count back when it ends; at and above it, and
// where OpenBLAS already runs on one thread, it changes nothing.
TEST(SerialDenseAlgebra, OneThreadForSmallMatricesRestoredAfterwards)
{
  using namespace serial_dense_algebra_test;
  using igabde::base::SerialDenseAlgebra;
  const get_type get = openblas_get();
  const set_type set = openblas_set();
  if (get == nullptr || set == nullptr)
    GTEST_SKIP() << "the BLAS is not OpenBLAS";
  const int outer = get();
  set(2);
  if (get() != 2)
    {
      set(outer);
      GTEST_SKIP() << "OpenBLAS was built for one thread";
    }
  {
    const SerialDenseAlgebra serial(SerialDenseAlgebra::serial_dense_rows - 1);
    EXPECT_EQ(get(), 1);
    {
      // Nested: nothing to change, nothing to restore too early.
      const SerialDenseAlgebra inner(10);
      EXPECT_EQ(get(), 1);
    }
    EXPECT_EQ(get(), 1);
  }
  EXPECT_EQ(get(), 2);
  {
    const SerialDenseAlgebra large(SerialDenseAlgebra::serial_dense_rows);
    EXPECT_EQ(get(), 2);
  }
  EXPECT_EQ(get(), 2);
  set(1);
  {
    const SerialDenseAlgebra serial(10);
    EXPECT_EQ(get(), 1);
  }
  EXPECT_EQ(get(), 1);
  set(outer);
}
