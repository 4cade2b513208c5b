// support/crash_stack.cpp, linked into every gtest binary: a test process that dies of a signal
// prints where, then still dies of that signal (ctest must see the crash, not a pass or a failure).
#include <gtest/gtest.h>
#include <signal.h>

#include "support/under_asan.h"

namespace {

#ifdef KEYTURN_UNDER_ASAN
constexpr bool kAsan = true;
#else
constexpr bool kAsan = false;
#endif

// A real fault, not raise(): the kernel's SIGSEGV with a fault address.
void writeThroughNull() {
  volatile int* volatile p = nullptr;
  *p = 1;
}

}  // namespace

TEST(CrashStack, ATestDyingOfASignalPrintsItsStackAndStillDiesOfIt) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  if (kAsan) {  // the sanitizer's own report, the handler not installed
    EXPECT_EXIT(writeThroughNull(), [](int status) { return status != 0; }, "AddressSanitizer: SEGV");
    return;
  }
  EXPECT_EXIT(writeThroughNull(), ::testing::KilledBySignal(SIGSEGV),
              "signal 11 \\(SEGV\\), fault address \\(nil\\); stack:\n.*keyturn_support_tests.*\\*\\*\\* end of stack");
}
