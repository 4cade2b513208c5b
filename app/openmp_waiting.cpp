#include "openmp_waiting.h"

#include <unistd.h>

#include <cstdlib>

namespace keyturn::app {

void waitPassivelyInOpenMp(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY")) return;  // the user's choice, or this is the second start
  ::setenv("OMP_WAIT_POLICY", "PASSIVE", 0);
  ::execv("/proc/self/exe", argv);  // returns only on failure: run on as it is
}

}  // namespace keyturn::app
