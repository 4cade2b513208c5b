#include "keyturn/drivers/tof_camera.h"

namespace keyturn::drivers {

double modulationMHz(int f) {
  static const double mhz[] = {40, 30, 21, 20, 19, 60, 15, 10, 29, 31, 14.5, 15.5};
  return f >= 0 && f < 12 ? mhz[f] : 0.0;
}

double nonAmbiguousRange(int f) {
  const double mhz = modulationMHz(f);
  return mhz > 0 ? 299.792458 / (2.0 * mhz) : 0.0;
}

}  // namespace keyturn::drivers
