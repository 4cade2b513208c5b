#pragma once
// Re-deriving a trained model's open-set answers from the training views it keeps (keyturn
// recalibrate): another stated false-accept rate, method, scale or distance, without the datasets
// it was trained on. The classifier stays as it is; the open set is calibrated as train calibrates
// it (open_set_calibration.h), on the kept views (model_enrollment.h's modelTrainingTable).
#include <string>

#include "keyturn/learning/model_file.h"
#include "keyturn/learning/open_set_calibration.h"

namespace keyturn::learning {

// The options the model's open set was calibrated with (method, rate, scale, class-scale power,
// spread, distance, groups and their shuffle): what enroll and recalibrate start from.
OpenSetOptions openSetOptionsOf(const Model& model);

// The model's open set calibrated anew by `options` on its kept training views, in place. Its pose
// references (classify --fuse), when it has them, are refitted from the same kept views, as enroll
// refits them: both are standardised alike, and the file keeps their rows once. Throws keyturn::Error
// naming `source` for a model without kept views (closed-set, or trained before they were kept), a
// distance that cannot measure its blocks, or kept views whose classes are not the model's.
void recalibrateOpenSet(Model& model, const OpenSetOptions& options, const std::string& source);

}  // namespace keyturn::learning
