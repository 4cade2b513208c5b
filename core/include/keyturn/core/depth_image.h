#pragma once
// A 16-bit depth image (PNG, as Kinect-style RGB-D datasets store them) as an organized cloud:
// pinhole intrinsics, the depth scale in metres per unit (0 = no return), an optional object mask
// and the offset of a cropped image in the full frame (Washington RGB-D's _loc.txt).
//
//   z = depth · scale,  x = (u + crop_u − cx) · z / fx,  y = (v + crop_v − cy) · z / fy
//
// u, v and cx, cy are 0-based pixel coordinates (OpenCV's convention). With lens distortion the
// normalised pixel ((u + crop_u − cx) / fx, (v + crop_v − cy) / fy) is undistorted first
// (core/lens_distortion.h). Camera files are read by core/camera_file.h.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "keyturn/core/cloud.h"
#include "keyturn/core/error.h"
#include "keyturn/core/lens_distortion.h"

namespace keyturn {

struct DepthIntrinsics {
  double fx = 0, fy = 0, cx = 0, cy = 0;  // pixels
  LensDistortion distortion;              // none unless the camera file gives non-zero coefficients

  DepthIntrinsics() = default;
  DepthIntrinsics(double fx, double fy, double cx, double cy, const LensDistortion& distortion = {})
      : fx(fx), fy(fy), cx(cx), cy(cy), distortion(distortion) {}
};

struct CropOffset {
  int u = 0, v = 0;  // the crop's top-left pixel in the full image, 0-based
};

// How depth-image views are read. Without intrinsics a depth image is refused.
struct DepthImageOptions {
  std::optional<DepthIntrinsics> intrinsics;
  double depth_scale = 0.001;            // metres per unit (millimetres: 0.001)
  std::string mask;                      // one mask for every image; "" = the image's own companion
  std::optional<CropOffset> crop;        // none = the image's own _loc.txt companion, or (0, 0)
};

// Companions read beside NAME_depthcrop.png / NAME_depth.png when present: NAME_maskcrop.png /
// NAME_mask.png (non-zero = object) and NAME_loc.txt ("u,v" of the crop's top-left, 1-based as
// Washington's MATLAB writes it). "" when the image's name has no companion of that kind.
std::string companionMask(const std::string& depth_png);
std::string companionCropFile(const std::string& depth_png);
CropOffset readCropFile(const std::string& path);

// The image's pixels as points (NaN where the depth is 0 or the mask is 0). `mask` is empty or
// width × height values.
Cloud depthImageToCloud(const std::vector<std::uint16_t>& depth, std::uint32_t width, std::uint32_t height,
                        const DepthIntrinsics& intrinsics, double depth_scale,
                        const std::vector<std::uint8_t>& mask = {}, CropOffset crop = {});

// A depth image read without the camera's intrinsics: a front end may say how its user gives them.
class MissingIntrinsicsError : public Error {
 public:
  using Error::Error;
};

// Whether loadCloud reads `path` as a depth image: its name ends in .png (any case).
bool isDepthImagePath(const std::string& path);

// Reads a 16-bit single-channel PNG (and its mask and crop offset) as an organized cloud. Every
// failure (8-bit or colour image, empty or corrupt file, mask of another size; a depth image
// without intrinsics: MissingIntrinsicsError) throws keyturn::Error naming the file.
Cloud loadDepthImage(const std::string& png, const DepthImageOptions& options);

// Throws keyturn::Error naming the file unless it is a PNG loadDepthImage reads (16-bit, one
// channel, whole): what a PNG among views is, before the intrinsics to read it are known.
void checkDepthImage(const std::string& png);

// A 16-bit single-channel PNG of exactly width × height, row-major (a frame's raw distance,
// amplitude and confidence images); read with the same checks as depth images, throws
// keyturn::Error naming the file.
std::vector<std::uint16_t> loadPng16(const std::string& png, std::uint32_t width, std::uint32_t height);

// A 16-bit single-channel image written as a PNG, durably (temporary name, sync, rename): depth
// images, and a frame's raw distance, amplitude and confidence images.
void savePng16(const std::string& png, const std::vector<std::uint16_t>& depth, std::uint32_t width,
                    std::uint32_t height);

}  // namespace keyturn
