#pragma once
// keyturn evaluate --protocol cross-sensor's run (app/cross_sensor_evaluate.cpp).
#include <string>

#include "keyturn/core/descriptor.h"
#include "keyturn/learning/classifier.h"
#include "keyturn/learning/protocols.h"

namespace keyturn::app {

struct CrossSensorEvaluateArgs {
  std::string dataset, other_camera, features, classifiers, out;
  learning::ClassifierParams params;
  learning::LabelKind label = learning::LabelKind::Instance;
  DescriptorOptions options;
  int jobs = 0;
  bool json = false, quiet = false;
};

int runCrossSensorEvaluate(const CrossSensorEvaluateArgs& a);

}  // namespace keyturn::app
