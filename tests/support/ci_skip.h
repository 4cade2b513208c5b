#pragma once
// A skip of something CI has the means to run (its packages are in scripts/install-deps.sh, it runs
// as root): under CI=true (CI sets it) a failure naming what was skipped and why, elsewhere a skip.
// Use plain GTEST_SKIP() where CI lacks the means (hardware, kernel modules, the CPU), and say so.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

namespace keyturn::test {
inline bool underCi() {
  const char* ci = std::getenv("CI");
  return ci && std::strcmp(ci, "true") == 0;
}
}  // namespace keyturn::test

#define KEYTURN_SKIP_UNLESS_CI(why)                                                       \
  do {                                                                                   \
    if (::keyturn::test::underCi())                                                      \
      GTEST_FAIL() << "skipped under CI=true, which has the means to run it: " << why; \
    GTEST_SKIP() << why;                                                                 \
  } while (0)
