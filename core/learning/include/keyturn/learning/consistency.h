#pragma once
// How much one object's description changes as it turns (the paper's Figs 15–16):
// the dissimilarity of the view at each rotation to the first view of its
// elevation, per feature block, over a dataset's feature table.
#include <string>
#include <utility>
#include <vector>

#include "keyturn/core/dissimilarity.h"
#include "keyturn/learning/feature_table.h"
#include "keyturn/core/report_plot_specs.h"

namespace keyturn::learning {

struct ConsistencyQuery {
  std::string object;                 // CLASS/INSTANCE (checked by objectParts)
  std::string elevation;              // one elevation label, or empty: each
  std::vector<std::string> blocks;    // "kpd2", "d2", …
  Dissimilarity measure = Dissimilarity::Bhattacharyya;
  std::string measure_name = "bhattacharyya";  // as the report names it
};

struct ConsistencyReport {
  std::string csv;    // elevation,angle_deg,keypoints,BLOCK… (nan where a view lacks a block)
  ReportPlots plots;  // consistency_eLABEL.png: one curve per block
};

// "CLASS/INSTANCE" → {CLASS, INSTANCE}; throws keyturn::Error naming the object otherwise.
std::pair<std::string, std::string> objectParts(const std::string& object);

// Throws keyturn::Error for a bad object name, a view name without its angle (…/aANGLE), a block
// the table lacks, or no views of the object (dataset names the table in that message).
ConsistencyReport consistency(const FeatureTable& table, const ConsistencyQuery& query, const std::string& dataset);

}  // namespace keyturn::learning
