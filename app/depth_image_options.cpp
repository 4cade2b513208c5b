#include "depth_image_options.h"

#include <sstream>
#include <tuple>

#include "keyturn/core/camera_file.h"
#include "keyturn/core/error.h"
#include "keyturn/core/string_format.h"

namespace keyturn::app {

void DepthImageFlags::add(CLI::App& cmd) {
  const char* group = "Depth images (.png views)";
  cmd.add_option("--camera", camera, "Camera file: fx fy cx cy (JSON or YAML, optional depth_scale), ROS camera_info YAML, OpenCV calibration YAML or Open3D intrinsic JSON (docs/camera.md)")
      ->group(group);
  for (auto [flag, field, what] : {std::tuple{"--fx", &fx, "Focal length in x (pixels)"},
                                   std::tuple{"--fy", &fy, "Focal length in y (pixels)"},
                                   std::tuple{"--cx", &cx, "Principal point x (pixels, 0-based)"},
                                   std::tuple{"--cy", &cy, "Principal point y (pixels, 0-based)"}})
  {
    double* target = field;  // a structured binding cannot be captured before C++20 (clang refuses)
    cmd.add_option_function<double>(flag, [this, target](double v) { *target = v; pinhole.push_back(v); }, what)
        ->group(group);
  }
  cmd.add_option("--depth-scale", depth_scale, "Metres per depth unit (default 0.001: millimetres)")
      ->check(CLI::PositiveNumber)->group(group);
  cmd.add_option("--mask", mask, "Mask PNG for every depth image (non-zero = object; default: NAME_mask[crop].png beside it)")
      ->group(group);
  cmd.add_option("--crop-offset", crop, "U,V: the crop's top-left pixel in the full image, 0-based (default: NAME_loc.txt beside it)")
      ->group(group);
}

DepthImageOptions DepthImageFlags::toOptions() const {
  DepthImageOptions o;
  if (!camera.empty() && !pinhole.empty()) throw Error("--camera and --fx/--fy/--cx/--cy: give one or the other");
  if (!camera.empty()) o = readCameraFile(camera);
  if (!pinhole.empty()) {
    if (pinhole.size() != 4) throw Error("--fx, --fy, --cx and --cy go together: give all four");
    if (!(fx > 0) || !(fy > 0)) throw Error("--fx and --fy must be positive");
    o.intrinsics = DepthIntrinsics{fx, fy, cx, cy};
  }
  if (depth_scale > 0) o.depth_scale = depth_scale;
  o.mask = mask;
  if (!crop.empty()) {
    std::istringstream in(crop);
    int u = -1, v = -1;
    char comma = 0;
    std::string rest;
    if (!(in >> u >> comma >> v) || comma != ',' || (in >> rest) || u < 0 || v < 0)
      throw Error("--crop-offset '" + crop + "': expected U,V (0-based pixels)");
    o.crop = CropOffset{u, v};
  }
  return o;
}

std::string depthScaleMessage(const DepthScaleError& e) {
  std::string out;
  appendFormat(out, "depth scale %g puts the median distance at %s (%zu of %zu points within the filter's range); "
               "--depth-scale %g",
               e.scale, formatMetres(e.median_m).c_str(), e.in_range, e.valid, e.suggested_scale);
  if (e.reciprocal()) appendFormat(out, " (1/%g)", e.scale);
  out += " would put it at " + formatMetres(e.suggested_median_m);
  out += e.reciprocal() ? ": keyturn counts metres per unit, Open3D units per metre"
                        : ": keyturn counts metres per unit (0.001 for millimetres)";
  return out;
}

}  // namespace keyturn::app
