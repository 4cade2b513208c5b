#pragma once
// The one-line message of the keyturn::Error a call throws ("" if it throws none).
#include <functional>
#include <string>

#include "keyturn/core/error.h"

namespace keyturn::test {

inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace keyturn::test
