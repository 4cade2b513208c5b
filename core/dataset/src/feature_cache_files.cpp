#include "keyturn/dataset/feature_cache_files.h"

#include <algorithm>
#include <filesystem>
#include <regex>

namespace fs = std::filesystem;

namespace keyturn::dataset {


std::string featureCacheFile(const std::string& root, const std::string& hash, int shard, int shards) {
  std::string name = "features-" + hash;
  if (shards > 1) name += ".shard-" + std::to_string(shard + 1) + "-of-" + std::to_string(shards);
  return (fs::path(root) / kKeyturnFolder / (name + ".csv")).string();
}

std::map<int, std::vector<std::string>> featureCacheShards(const std::string& root, const std::string& hash) {
  std::map<int, std::vector<std::string>> sets;
  const std::regex shard_re("features-" + hash + R"(\.shard-(\d+)-of-(\d+)\.csv)");
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(root) / kKeyturnFolder, ec)) {
    std::smatch m;
    const std::string name = e.path().filename().string();
    if (std::regex_match(name, m, shard_re)) sets[std::stoi(m[2])].push_back(e.path().string());
  }
  for (auto& [n, files] : sets) std::sort(files.begin(), files.end());
  return sets;
}

}  // namespace keyturn::dataset
