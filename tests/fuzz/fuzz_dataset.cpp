// A dataset's manifest and sidecars as verify, capture (resume) and
// repeatability read them. The first byte picks the file.
#include "fuzz_file.h"
#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/dataset/sidecars.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  try {
    switch (data[0] % 3) {
      case 0: {
        const std::string path = keyturn::fuzz::writeInput(data + 1, size - 1, "manifest.csv");
        const std::string root = path.substr(0, path.rfind('/'));
        std::vector<std::string> bad;
        (void)keyturn::dataset::Dataset::readManifest(root, &bad);
        (void)keyturn::dataset::Dataset::verify(root);
        break;
      }
      case 1:
        (void)keyturn::dataset::readViewTransform(keyturn::fuzz::writeInput(data + 1, size - 1, "view.json"));
        break;
      default:
        (void)keyturn::dataset::readAxisCalibration(keyturn::fuzz::writeInput(data + 1, size - 1, "calibration.json"));
    }
  } catch (const keyturn::Error&) {
  }
  return 0;
}
