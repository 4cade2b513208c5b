// Object meshes for the simulator: PLY, OBJ, STL, OFF (sim::loadMesh).
#include "fuzz_file.h"
#include "keyturn/core/error.h"
#include "keyturn/sim/mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* names[] = {"in.ply", "in.obj", "in.stl", "in.off"};
  const std::string path = keyturn::fuzz::writeInput(data + 1, size - 1, names[data[0] & 3]);
  try {
    const auto m = keyturn::sim::loadMesh(path);
    (void)m.boundsMax();
  } catch (const keyturn::Error&) {
  }
  return 0;
}
