#pragma once
// Camera files: a depth camera's intrinsics (and lens distortion, and sometimes its depth scale) as
// the tools people calibrate with write them. The format is recognised from the content, not the
// name:
//   - keyturn's own: JSON {"fx": …, "fy": …, "cx": …, "cy": …} or flat YAML `fx: 570.3` lines, an
//     optional depth_scale (metres per unit);
//   - ROS camera_info YAML (camera_calibration_parsers: image_width, camera_matrix {rows, cols,
//     data}, distortion_model, distortion_coefficients) and a sensor_msgs/CameraInfo message as
//     `rostopic echo` / `ros2 topic echo` print it (width, height, K / k, D / d, distortion_model);
//   - Open3D's PinholeCameraIntrinsic JSON (width, height, intrinsic_matrix: 9 values, column-major);
//   - OpenCV's calibration YAML written by cv::FileStorage (%YAML:1.0, camera_matrix and
//     distortion_coefficients as !!opencv-matrix).
// Lens distortion is kept when it is plumb_bob or rational_polynomial and refused for any other model
// with non-zero coefficients (docs/camera.md).
#include <string>

#include "keyturn/core/depth_image.h"

namespace keyturn {

// The camera file's intrinsics, distortion and (keyturn's own format only) depth scale. Every
// failure — no such file, neither JSON nor YAML, a missing or non-numeric value, a camera matrix
// of the wrong size, an unsupported distortion model — throws keyturn::Error naming the file.
DepthImageOptions readCameraFile(const std::string& path);

}  // namespace keyturn
