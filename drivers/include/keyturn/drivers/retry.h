#pragma once
// The drivers' one retry policy: after a failure, report it, wait (an initial
// backoff doubled per retry), recover (reconnect, reopen) and try again, up to
// `retries` more times. A device's refusal is not retried: asking again will not
// change its answer.
#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "keyturn/core/error.h"

namespace keyturn::drivers {

// The device understood and said no (a Modbus exception, a CANopen SDO abort).
struct DeviceRefused : Error {
  using Error::Error;
};

struct RetryPolicy {
  int retries = 3;
  int backoff_initial_ms = 50;  // before retry k: initial × 2^(k-1); 0 retries at once
  int waitMs(int retry) const { return backoff_initial_ms << (retry - 1); }
};

// Returns what attempt() returns. A keyturn::Error from attempt() or recover() is remembered;
// before retry k (1 … retries) calls report(k, wait_ms, last), sleeps, then recover() — a
// failing recover() uses up that retry. DeviceRefused passes through at once. When every try
// failed, throws give_up(last) (a keyturn::Error naming the device).
template <typename Attempt, typename Recover, typename Report, typename GiveUp>
auto withRetries(const RetryPolicy& policy, Attempt&& attempt, Recover&& recover, Report&& report, GiveUp&& give_up)
    -> decltype(attempt()) {
  std::string last;
  for (int k = 0; k <= policy.retries; ++k) {
    try {
      if (k > 0) {
        const int wait = policy.waitMs(k);
        report(k, wait, last);
        if (wait > 0) std::this_thread::sleep_for(std::chrono::milliseconds(wait));
        recover();
      }
      return attempt();
    } catch (const DeviceRefused&) {
      throw;
    } catch (const Error& e) {
      last = e.what();
    }
  }
  throw give_up(last);
}

// A camera's frame read under that policy: reopened between tries, each retry one line on `log`
// ("DEVICE: LAST; reopening in W ms (attempt K of N)"), giving up as one error naming `device`.
template <typename Attempt, typename Reopen>
auto withReopening(const std::string& device, const RetryPolicy& policy,
                   const std::function<void(const std::string&)>& log, Attempt&& attempt, Reopen&& reopen)
    -> decltype(attempt()) {
  return withRetries(
      policy, attempt, reopen,
      [&](int k, int wait, const std::string& last) {
        if (log)
          log(device + ": " + last + "; reopening in " + std::to_string(wait) + " ms (attempt " + std::to_string(k) +
              " of " + std::to_string(policy.retries) + ")");
      },
      [&](const std::string& last) {
        return Error(device + ": giving up after " + std::to_string(policy.retries) + " reopen attempts: " + last);
      });
}

}  // namespace keyturn::drivers
