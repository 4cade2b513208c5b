// PCD and PLY point clouds as keyturn loads them (loadCloud). The first byte
// picks the format. Only keyturn::Error may come out; anything else is a bug.
#include "fuzz_file.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string path = keyturn::fuzz::writeInput(data + 1, size - 1, data[0] & 1 ? "in.ply" : "in.pcd");
  try {
    const keyturn::Cloud c = keyturn::loadCloud(path);
    (void)c.validCount();
  } catch (const keyturn::Error&) {
  }
  return 0;
}
