#pragma once
// Training a model on a whole feature table (keyturn train); applying one is
// model_predictions.h.
#include <optional>
#include <string>
#include <vector>

#include "keyturn/learning/feature_table.h"
#include "keyturn/learning/model_file.h"
#include "keyturn/learning/open_set_calibration.h"
#include "keyturn/learning/protocols.h"

namespace keyturn::learning {

// A classifier of params.kind on the blocks of every row, labelled by kind, with its sidecar
// (the table's specification, the class names and means). fit_s: the training time.
// open_set: calibrate the first of its methods on the table's categories (open_set_calibration.h)
// and store it in the model; none: a closed-set model. Fewer than three categories cannot be
// calibrated: an error, or a closed-set model when open_set->required is false.
// azimuth_deg: each row's turntable angle (or empty); with every angle known, the open set's turn
// threshold is calibrated too (turn_fusion.h). Throws keyturn::Error when it is not one per row.
// The open set trainModel calibrates, on the rows x (the table's rows in `blocks`) labelled y with
// `params`' classifier: the first of options.methods, each row's category, camera and instance from
// the table, turns when every row has its angle. Throws keyturn::Error as calibrateOpenSets does, and
// for a distance that cannot measure the blocks (checkOpenSetDistanceFor).
OpenSet calibrateModelOpenSet(const FeatureTable& table, const Matrix& x, const std::vector<int>& y,
                              const std::vector<std::string>& blocks, const ClassifierParams& params,
                              const OpenSetOptions& options, const std::vector<double>& azimuth_deg);

Model trainModel(const FeatureTable& table, const std::vector<std::string>& blocks, LabelKind kind,
                 const ClassifierParams& params, double* fit_s = nullptr,
                 const std::optional<OpenSetOptions>& open_set = std::nullopt,
                 const std::vector<double>& azimuth_deg = {});

}  // namespace keyturn::learning
