// The drivers' retry policy: backoff doubling, recovery before each retry, a refusal not retried.
#include "keyturn/drivers/retry.h"

#include <gtest/gtest.h>

#include <vector>

#include "support/error_of.h"

using namespace keyturn;
using namespace keyturn::drivers;

TEST(Retry, RecoversBeforeEachRetryWithDoublingWaits) {
  int tries = 0, recovered = 0;
  std::vector<int> waits;
  const int v = withRetries(
      RetryPolicy{3, 1},
      [&] {
        if (++tries < 3) throw Error("flaky " + std::to_string(tries));
        return 42;
      },
      [&] { ++recovered; }, [&](int, int wait, const std::string&) { waits.push_back(wait); },
      [](const std::string& last) { return Error("gave up: " + last); });
  EXPECT_EQ(v, 42);
  EXPECT_EQ(tries, 3);
  EXPECT_EQ(recovered, 2);
  EXPECT_EQ(waits, (std::vector<int>{1, 2}));
}

TEST(Retry, GivesUpWithTheLastErrorAndNeverRetriesARefusal) {
  int tries = 0;
  const auto fail = [&] {
    return withRetries(
        RetryPolicy{2, 0}, [&]() -> int { throw Error("try " + std::to_string(++tries)); }, [] {},
        [](int, int, const std::string&) {}, [](const std::string& last) { return Error("gave up: " + last); });
  };
  EXPECT_EQ(test::errorOf([&] { fail(); }), "gave up: try 3");
  int refusals = 0;
  EXPECT_EQ(test::errorOf([&] {
              withRetries(
                  RetryPolicy{5, 0}, [&]() -> int { ++refusals; throw DeviceRefused("no"); }, [] {},
                  [](int, int, const std::string&) {}, [](const std::string& last) { return Error(last); });
            }),
            "no");
  EXPECT_EQ(refusals, 1);
  // A failing recovery uses up its retry.
  int attempts = 0;
  EXPECT_EQ(test::errorOf([&] {
              withRetries(
                  RetryPolicy{2, 0}, [&]() -> int { ++attempts; throw Error("down"); },
                  [] { throw Error("cannot reconnect"); }, [](int, int, const std::string&) {},
                  [](const std::string& last) { return Error(last); });
            }),
            "cannot reconnect");
  EXPECT_EQ(attempts, 1);
}
