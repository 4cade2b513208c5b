#pragma once
// Values that cross between the studio's threads (registered with Qt's meta-type
// system so queued signals can carry them).
#include <QMetaType>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "keyturn/drivers/pose_source.h"
#include "keyturn/drivers/tof_camera.h"
#include "keyturn/learning/recognizer.h"

namespace keyturn::studio {

using FramePtr = std::shared_ptr<const drivers::TofFrame>;

// One processed frame: what the recogniser made of it (or why it could not).
struct ViewResult {
  FramePtr frame;
  std::shared_ptr<const learning::Recognition> recognition;  // null when it failed
  std::shared_ptr<const learning::Recognizer> recognizer;    // the model it used
  std::string error;
  bool no_object = false;  // the error is a view too empty to describe (EmptyViewError)
  std::vector<std::vector<Eigen::Vector3f>> geodesic_paths;  // when asked for
  double latency_ms = 0;  // frame timestamp → result
  std::uint64_t epoch = 0;  // the camera run its frame came from (RecognitionPool::restart)
};
using ViewResultPtr = std::shared_ptr<const ViewResult>;

void registerStudioMetaTypes();

}  // namespace keyturn::studio

Q_DECLARE_METATYPE(keyturn::studio::FramePtr)
Q_DECLARE_METATYPE(keyturn::studio::ViewResultPtr)
Q_DECLARE_METATYPE(std::shared_ptr<keyturn::drivers::PoseSource>)
