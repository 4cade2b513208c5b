#include "keyturn/sim/view_series.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "keyturn/core/checked_integer.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/sim/tof_view.h"

namespace keyturn::sim {

std::string seriesFileName(const std::string& pattern, double angle, bool several) {
  const auto at = pattern.find("{angle}");
  if (at == std::string::npos) {
    if (several) throw Error("output path '" + pattern + "' must contain {angle} when several angles are rendered");
    return pattern;
  }
  char buf[16];
  std::snprintf(buf, sizeof buf, "%03d", static_cast<int>(std::lround(angle)));
  return pattern.substr(0, at) + buf + pattern.substr(at + 7);
}

void renderSeries(const ViewSeries& s,
                  const std::function<void(const std::string&, const Cloud&, double, double)>& written) {
  // File names hold the angle rounded to a degree: two angles that round alike would overwrite.
  std::map<std::string, double> named;
  for (double angle : s.angles) {
    const auto [it, fresh] = named.emplace(seriesFileName(s.out, angle, s.angles.size() > 1), angle);
    if (!fresh)
      throw Error("angles " + numberText(it->second) + " and " + numberText(angle) + " would both write " + it->first);
  }
  const Mesh mesh = loadMeshOrBuiltin(s.mesh);
  TofViewRenderer renderer(mesh);
  const double distance = s.distance > 0 ? s.distance : operatorDistance(mesh);
  for (std::size_t i = 0; i < s.angles.size(); ++i) {
    SceneView v;
    v.turntable_deg = s.angles[i];
    v.elevation_deg = s.elevation_deg;
    v.distance = distance;
    v.seed = s.seed + i;
    v.noise = s.noise;
    const Cloud c = renderer.render(v);
    const std::string path = seriesFileName(s.out, s.angles[i], s.angles.size() > 1);
    saveCloud(path, c);
    if (written) written(path, c, distance, s.angles[i]);
  }
}

}  // namespace keyturn::sim
