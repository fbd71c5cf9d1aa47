// The test binary's end-of-main leak check (vm/core/leak_check.h says why): the tests
// load OpenImageIO in this process, and gtest_main owns main, so the check runs when the last test
// environment is torn down.
#include <gtest/gtest.h>

#include "vm/core/leak_check.h"

namespace {

class LeakCheckAfterTheTests : public testing::Environment {
 public:
  void TearDown() override { vs11::CheckForLeaksNow(); }
};

// GoogleTest owns and deletes the environment.
[[maybe_unused]] testing::Environment* const leak_check = testing::AddGlobalTestEnvironment(new LeakCheckAfterTheTests);

}  // namespace
