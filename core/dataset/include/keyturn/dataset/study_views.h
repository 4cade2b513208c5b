#pragma once
// The posed views a repeatability study compares: a calibrated keyturn dataset's
// views (each sidecar's camera_from_turntable), or any pose file core reads.
#include <string>
#include <vector>

#include "keyturn/core/pose_list.h"
#include "keyturn/studies/repeatability_study.h"

namespace keyturn::dataset {

// A dataset folder, or a pose file (docs/repeatability.md); throws keyturn::Error.
std::vector<StudyView> studyViews(const std::string& input, const PoseReadOptions& poses);

}  // namespace keyturn::dataset
