#pragma once
// One exception type for every failure keyturn reports to a user: the message is
// a single line that names the file or device and what was wrong with it.
#include <stdexcept>
#include <string>

namespace keyturn {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace keyturn
