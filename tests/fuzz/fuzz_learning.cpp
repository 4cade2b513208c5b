// What keyturn's learning tools read from disk: model sidecars (model.json)
// and feature caches (CSV, possibly from other machines' shards). The first
// byte picks the kind.
#include "fuzz_file.h"
#include "keyturn/core/error.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/model_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  try {
    if (data[0] & 1) {
      const auto m = keyturn::learning::parseModelSidecar(
          std::string(reinterpret_cast<const char*>(data + 1), size - 1), "model.json");
      (void)keyturn::learning::specDifferences(m.spec, {{"bins", "32"}});
    } else {
      const auto t = keyturn::learning::loadFeatureTable(keyturn::fuzz::writeInput(data + 1, size - 1, "features.csv"));
      if (!t.rows.empty() && !t.blocks.empty()) (void)t.select({t.blocks.front()}, {0});
    }
  } catch (const keyturn::Error&) {
  }
  return 0;
}
