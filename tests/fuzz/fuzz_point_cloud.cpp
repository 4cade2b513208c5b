// PCD and PLY point clouds and 16-bit depth PNGs as keyturn loads them (loadCloud). The first
// byte picks the format (… & 3 == 2: PNG, else bit 0: PLY or PCD). Only keyturn::Error may come
// out; anything else is a bug.
#include "fuzz_file.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const bool png = (data[0] & 3) == 2;
  const std::string path =
      keyturn::fuzz::writeInput(data + 1, size - 1, png ? "in_depth.png" : data[0] & 1 ? "in.ply" : "in.pcd");
  keyturn::DepthImageOptions depth;
  depth.intrinsics = keyturn::DepthIntrinsics{525, 525, 319.5, 239.5};
  try {
    const keyturn::Cloud c = keyturn::loadCloud(path, depth);
    (void)c.validCount();
  } catch (const keyturn::Error&) {
  }
  return 0;
}
