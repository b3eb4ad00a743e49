// Linked into every test program: LeakSanitizer's check runs when the tests end, before the
// process exits (see src/app/leak_check.hpp for why).
#include "app/leak_check.hpp"

#include <gtest/gtest.h>

namespace {

class LeakCheckBeforeExit : public ::testing::Environment {
 public:
  void TearDown() override { jellysim::app::check_leaks_before_exit(); }
};

[[maybe_unused]] ::testing::Environment* const kLeakCheck =
    ::testing::AddGlobalTestEnvironment(new LeakCheckBeforeExit);

}  // namespace
