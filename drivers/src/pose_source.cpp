#include "keyturn/drivers/pose_source.h"

#include "keyturn/core/error.h"

namespace keyturn::drivers {

void PoseSource::unsupported(const char* what) const {
  throw Error(describe() + ": cannot " + std::string(what) + " (a read-only pose source)");
}

}  // namespace keyturn::drivers
