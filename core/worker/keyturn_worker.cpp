// keyturn-worker: runs, one request at a time, the routines keyturn keeps out of its own process
// because they may crash it (worker_process.h has the why, worker_protocol.h the protocol). Started
// by keyturn, never by a user: it serves requests on stdin/stdout until stdin ends.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "../src/pcl_features_plugin.h"
#include "../src/worker_protocol.h"
#include "keyturn/core/cloud.h"
#include "keyturn/core/plugin.h"

namespace {

using keyturn::worker::readAll;
using keyturn::worker::writeAll;

// our-cvfh: input = normal radius, then x y z per point; output = PCL's OUR-CVFH histograms.
std::vector<float> ourCvfh(const std::vector<float>& in) {
  if (in.empty() || (in.size() - 1) % 3 != 0) throw std::runtime_error("our-cvfh: input is not a radius and points");
  keyturn::PointSet set;
  for (std::size_t i = 1; i + 2 < in.size(); i += 3) set.points.emplace_back(in[i], in[i + 1], in[i + 2]);
  static const keyturn::detail::PclFeatures* pcl =
      keyturn::pluginFunction<keyturn::detail::PclFeaturesFunction>("pcl_features", "keyturn_pcl_features")();
  return pcl->our_cvfh(set, in[0]);
}

std::vector<float> run(const std::string& job, const std::vector<float>& in) {
  if (job == "our-cvfh") return ourCvfh(in);
  // The two jobs the tests of the mechanism use: the input back, and a crash.
  if (job == "echo") return in;
  if (job == "crash") std::abort();
  throw std::runtime_error("unknown job '" + job + "'");
}

bool reply(std::uint8_t status, const void* data, std::uint32_t n, std::size_t item) {
  return writeAll(STDOUT_FILENO, &status, sizeof status) && writeAll(STDOUT_FILENO, &n, sizeof n) &&
         writeAll(STDOUT_FILENO, data, n * item);
}

}  // namespace

int main() {
  for (;;) {
    std::uint32_t job_size = 0;
    if (!readAll(STDIN_FILENO, &job_size, sizeof job_size)) return 0;  // the caller is done
    std::string job(job_size, '\0');
    std::uint32_t n = 0;
    if (!readAll(STDIN_FILENO, job.data(), job_size) || !readAll(STDIN_FILENO, &n, sizeof n)) return 1;
    std::vector<float> in(n);
    if (!readAll(STDIN_FILENO, in.data(), n * sizeof(float))) return 1;
    bool ok = false;
    try {
      const std::vector<float> out = run(job, in);
      ok = reply(keyturn::worker::kDone, out.data(), static_cast<std::uint32_t>(out.size()), sizeof(float));
    } catch (const std::exception& e) {
      const std::string what = e.what();
      ok = reply(keyturn::worker::kFailed, what.data(), static_cast<std::uint32_t>(what.size()), 1);
    }
    if (!ok) return 1;
  }
}
