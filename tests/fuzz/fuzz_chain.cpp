// The whole chain on clouds that load fine but are geometrically degenerate: filter → working
// resolution → resolution → ISS → keypoint functions → graph → geodesics → Osada → PDFs, as
// `keyturn describe` (describeView) and live recognition (Recognizer::describe, with the
// geodesic paths) run it. The first byte picks the layout and the path; then the options
// (chain_input.h), then the cloud. Only keyturn::Error may come out, and a described view's
// PDFs must be finite.
#include <cstdio>
#include <cstdlib>

#include "chain_input.h"
#include "keyturn/learning/recognizer.h"

namespace {

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_chain: %s\n", what);
  std::abort();
}

void checkPdfs(const std::vector<std::vector<double>>& pdfs) {
  for (const auto& pdf : pdfs)
    for (double v : pdf) check(std::isfinite(v) && v >= 0 && v <= 1 + 1e-9, "a PDF value outside [0, 1]");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  keyturn::fuzz::Bytes in(data, size);
  const std::uint8_t mode = in.u8();
  const keyturn::DescriptorOptions options = keyturn::fuzz::decodeOptions(in);
  const keyturn::Cloud cloud = keyturn::fuzz::decodeCloud(in, mode & 1);
  try {
    if (mode & 2) {
      const keyturn::learning::Recognizer describer(options);
      const auto r = describer.describe(cloud, mode & 4);
      checkPdfs(r.descriptor.pdfs);
      for (const auto& path : r.descriptor.geodesic_paths)
        for (const auto& p : path) check(p.allFinite(), "a geodesic path through a non-finite point");
    } else {
      keyturn::PointSet prepared;
      const auto d = keyturn::describeView(cloud, options, &prepared);
      checkPdfs(d.pdfs);
      checkPdfs(d.scaled_pdfs);
      checkPdfs(d.random_keypoint_pdfs);
      for (int i : d.keypoint_index) check(i >= 0 && static_cast<std::size_t>(i) < prepared.size(), "a keypoint index out of range");
    }
  } catch (const keyturn::Error&) {
  }
  return 0;
}
