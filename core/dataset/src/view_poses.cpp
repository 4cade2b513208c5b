#include "keyturn/dataset/view_poses.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "keyturn/core/error.h"
#include "keyturn/core/json_file.h"
#include "keyturn/dataset/dataset.h"
#include "keyturn/dataset/dataset_views.h"

namespace keyturn::dataset {

std::string sidecarPathOf(const std::string& view_path) {
  return std::filesystem::path(view_path).replace_extension(".json").string();
}

double readViewAzimuth(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": no sidecar, so the view has no turntable pose");
  const nlohmann::json j = readJsonFile(path, JsonShape::Object);
  const auto it = j.find("measured_deg");
  if (it == j.end() || !it->is_number() || !std::isfinite(it->get<double>()))
    throw Error(path + ": no measured_deg, so the view has no turntable pose");
  return it->get<double>();
}

std::map<std::string, double> datasetAzimuths(const std::string& root) {
  std::vector<ViewRecord> records;
  const auto views = datasetViews(root, nullptr, &records);
  std::map<std::string, double> out;
  for (std::size_t i = 0; i < views.size() && i < records.size(); ++i) out[views[i].id] = records[i].measured_deg;
  return out;
}

}  // namespace keyturn::dataset
