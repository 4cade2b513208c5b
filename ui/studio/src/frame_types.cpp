#include "frame_types.h"

namespace keyturn::studio {

void registerStudioMetaTypes() {
  qRegisterMetaType<FramePtr>("keyturn::studio::FramePtr");
  qRegisterMetaType<ViewResultPtr>("keyturn::studio::ViewResultPtr");
  qRegisterMetaType<std::shared_ptr<drivers::PoseSource>>("std::shared_ptr<keyturn::drivers::PoseSource>");
}

}  // namespace keyturn::studio
