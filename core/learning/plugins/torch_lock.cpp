#include "torch_lock.h"

namespace keyturn::learning {

std::mutex& torchMutex() {
  static std::mutex m;
  return m;
}

}  // namespace keyturn::learning
