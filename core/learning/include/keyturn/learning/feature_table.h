#pragma once
// The per-view feature cache of a dataset: one row per view with its labels,
// keypoint count and every feature block (PDFs, peer descriptors), stored as
// CSV so shards computed on different machines merge by concatenation and
// any tool can read it. docs/results.md describes the columns.
#include <map>
#include <string>
#include <vector>

#include "keyturn/learning/classifier.h"

namespace keyturn::learning {

struct FeatureRow {
  std::string id;                       // view stem relative to the dataset root
  std::string cls, instance, elevation;
  int keypoints = 0;                    // K (ISS); -1 when the view could not be described
  std::string problem;                  // why a block is missing ("" when none is)
  bool no_object = false;               // too little in view to describe (EmptyViewError); not in the CSV
  std::string camera;                   // the source's organized grid "WxH" (cameraOf), "" unknown; not in the CSV
  std::vector<float> values;            // all blocks back to back; NaN = missing
};

struct FeatureTable {
  std::vector<std::string> blocks;      // "kpd2", "u_kpd2", "d2", "esf", …
  std::vector<int> sizes;               // bins per block
  std::map<std::string, std::string> spec;  // parameters that produced it
  std::vector<FeatureRow> rows;

  int width() const;
  // Columns of the named blocks ("kpd2+gkpd2" concatenates) for the given rows.
  // Throws keyturn::Error naming a block the table lacks.
  Matrix select(const std::vector<std::string>& blocks, const std::vector<std::size_t>& rows) const;
  int offset(const std::string& block) const;     // -1 when absent
  int blockSize(const std::string& block) const;  // 0 when absent
};

// "kpd2+gkpd2" → {"kpd2", "gkpd2"} (a feature set: blocks concatenated); names are checked
// against a table when selected. Throws keyturn::Error for an empty set or part.
std::vector<std::string> featureSetBlocks(const std::string& set);
// "kpd2+kpa3|s_kpd2+kpa3+size" → its candidates (one, "kpd2+kpa3", without a '|'): a choice
// evaluate makes per fold by nested validation. Throws keyturn::Error for an empty candidate.
std::vector<std::string> featureSetChoices(const std::string& set);

// Writes atomically (temporary name, fsync, rename).
void saveFeatureTable(const std::string& path, const FeatureTable& table);
// Throws keyturn::Error "<path>: line N: …" on any malformed content.
FeatureTable loadFeatureTable(const std::string& path);
// Throws keyturn::Error naming other_name when other's blocks or descriptor parameters differ from table's.
void checkSameFeatures(const FeatureTable& table, const FeatureTable& other, const std::string& other_name);
// Whether the table holds every one of these blocks.
bool hasBlocks(const FeatureTable& t, const std::vector<std::string>& blocks);
// When one table's blocks are all among the other's (a cache written before a block existed lacks it,
// FeatureCache::needs), both keep only those, in a's order; otherwise both stay as they are.
void keepCommonBlocks(FeatureTable& a, FeatureTable& b);
// other's rows after table's (checked by checkSameFeatures, on the blocks both have): several datasets'
// views trained on together. Ids may repeat: the same view through another camera keeps its id.
void appendRows(FeatureTable& table, const FeatureTable& other, const std::string& other_name);
// Rows of shards with identical blocks and spec, in order; duplicate ids are an error.
FeatureTable mergeFeatureTables(const std::vector<FeatureTable>& shards, const std::vector<std::string>& names);

}  // namespace keyturn::learning
