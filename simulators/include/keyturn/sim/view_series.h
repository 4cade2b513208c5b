#pragma once
// Simulated SR4000 views of one mesh at several turntable angles, each saved as
// an organized PCD (keyturn render).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"

namespace keyturn::sim {

struct ViewSeries {
  std::string mesh;                 // a mesh file or builtin:NAME
  std::vector<double> angles;       // turntable degrees
  double elevation_deg = 30.0;
  double distance = 0.0;            // 0: the operator's placement (operatorDistance)
  std::uint64_t seed = 1;           // view i gets seed + i
  bool noise = true;
  std::string out;                  // PCD path; {angle} becomes the angle in whole degrees, 3 digits (045)
};

// The file of one view; throws keyturn::Error when several angles would share a pattern without {angle}.
std::string seriesFileName(const std::string& pattern, double angle, bool several);

// Renders and saves each view; written(path, cloud, distance, angle) after each.
void renderSeries(const ViewSeries& series,
                  const std::function<void(const std::string& path, const Cloud& cloud, double distance, double angle)>& written);

}  // namespace keyturn::sim
