// An enrollment stopped half-way (the studio's Cancel: a progress callback that throws, or any
// failure) leaves no rendered views behind and writes no model.
#include "keyturn/rig/object_enrollment.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;

TEST(ObjectEnrollment, AnEnrollmentStoppedWhileRenderingLeavesNoViewsAndNoModel) {
  const keyturn::test::ScratchFolder scratch("object_enrollment");
  rig::ObjectEnrollment request;
  request.simulation.object = {"scissors", "ycb_037_scissors",
                               std::string(KEYTURN_DATA_DIR) + "/objects/scissors__ycb_037_scissors.ply"};
  request.simulation.cameras = {rig::SimulatedCamera::Sr4000};
  request.simulation.elevations = {30};
  request.simulation.step_deg = 90;  // 4 views
  request.model = std::string(KEYTURN_DATA_DIR) + "/models/sim-objects";
  request.out = (scratch.made() / "model").string();
  int rendered = 0;
  rig::EnrollmentProgress progress;
  progress.view_rendered = [&] {
    if (++rendered == 2) throw std::runtime_error("stopped");
  };
  EXPECT_THROW(rig::enrollObject(request, progress), std::runtime_error);
  EXPECT_EQ(rendered, 2);
  EXPECT_FALSE(fs::exists(request.out + ".views")) << "the rendered views are removed";
  EXPECT_FALSE(fs::exists(request.out)) << "no model is written";

  // Asked to keep them, the views rendered so far stay (a later run resumes them).
  request.keep_views = true;
  rendered = 0;
  EXPECT_THROW(rig::enrollObject(request, progress), std::runtime_error);
  EXPECT_TRUE(fs::exists(request.out + ".views"));
  EXPECT_FALSE(fs::exists(request.out));
}
