#pragma once
// keyturn repeatability's option syntax: the lists its flags take, turned into the study's
// typed options (keyturn/studies/repeatability_study.h); errors name the flag.
#include <string>
#include <vector>

#include "keyturn/core/keypoint_detectors.h"

namespace keyturn::app {

// --eps: START:STOP:STEP (STOP included) or a comma list, in multiples of the resolution.
std::vector<double> parseEpsList(const std::string& text);
// --detectors: a comma list of detector names.
std::vector<Detector> parseDetectorList(const std::string& text);

}  // namespace keyturn::app
