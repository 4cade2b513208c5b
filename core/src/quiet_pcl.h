#pragma once
// PCL's console (PCL_ERROR, PCL_WARN) silenced, once per process: its lines ("Not enough inliers
// found to optimize model coefficients! …") would reach the user's terminal beside keyturn's own
// one-line messages. Called before keyturn calls into PCL: loading and saving clouds
// (cloud_io.cpp, where it is defined) and the support plane's RANSAC (filter.cpp). Internal to
// keyturn_core; free of PCL's headers.
namespace keyturn::detail {

void quietPcl();

}  // namespace keyturn::detail
