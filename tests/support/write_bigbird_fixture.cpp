// Writes small datasets in BigBIRD's layout from the real Kinect cuts in tests/data/real/mosd, for
// the import tests (tests/cli/import_bigbird_cli_test.sh). Usage:
//
//   write_bigbird_fixture MOSD_DIR OUT_DIR
//
// OUT_DIR/bigbird/      box_1 (learn0 o1) and cylinder_1 (learn34 o1), each: NP1_A.h5 and NP3_A.h5 for
//                       A = 0, 3, 6 (the scene's depth in 100 µm units, ±2 mm noise per view), a colour
//                       NPi_A.jpg, masks/NPi_A_mask.pbm (the object's pixels in the colour camera),
//                       poses/NP5_A_pose.h5 and calibration.h5 (NP1 … NP5)
// OUT_DIR/bigbird_bad/  box_1 again, plus what the importer must report one line each: an object
//                       without calibration.h5, a corrupt .h5, an .h5 without "depth", float depth,
//                       a view whose pose is missing, a malformed name
// OUT_DIR/categories.csv  class,instance: box_1 → box, cylinder_1 → cylinder
#include <Eigen/LU>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include "bigbird_files.h"
#include "keyturn/core/cloud_io.h"

namespace fs = std::filesystem;
using namespace keyturn;
using namespace keyturn::test;

namespace {

const std::vector<FixtureCamera> kCameras = [] {
  std::vector<FixtureCamera> c(5);
  const double elevation[5] = {20, 35, 50, 65, kNp5ElevationDeg}, scale[5] = {1.0017, 0.9991, 0.9985, 1.0008, 1};
  for (int i = 0; i < 5; ++i) c[i].np = i + 1, c[i].elevation_deg = elevation[i], c[i].ir_depth_scale = scale[i];
  return c;
}();

struct Scene {
  Cloud full, masked;
};

void writeObject(const fs::path& dir, const Scene& s, unsigned seed, bool with_pose_6 = true) {
  fs::create_directories(dir / "masks");
  fs::create_directories(dir / "poses");
  writeH5((dir / "calibration.h5").string(), calibrationDatasets(kCameras));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> noise(-20, 20);
  const std::uint32_t w = s.full.width, h = s.full.height;
  for (int angle : {0, 3, 6}) {
    if (angle != 6 || with_pose_6)
      writeH5((dir / "poses" / ("NP5_" + std::to_string(angle) + "_pose.h5")).string(),
              {h5Matrix("H_table_from_reference_camera", cameraFromTable(angle, kNp5ElevationDeg).inverse()),
               {"board_frame_offset", H5Type::Float64, {3}, {0.01, 0.02, 0}}});
    for (int np : {1, 3}) {
      const FixtureCamera& cam = kCameras[np - 1];
      const double unit = 1e-4 * cam.ir_depth_scale;
      std::vector<std::uint16_t> depth(std::size_t(w) * h, 0);
      std::vector<std::uint8_t> mask(1280 * 1024, 0);
      for (std::size_t i = 0; i < depth.size(); ++i) {
        const float z = s.full.points[i].z();
        if (!std::isfinite(z) || z <= 0) continue;
        const long raw = std::lround(z / unit) + noise(rng);
        if (raw <= 0 || raw > 65535) continue;
        depth[i] = static_cast<std::uint16_t>(raw);
        if (!Cloud::isValid(s.masked.points[i])) continue;
        // The object's pixel where the colour camera sees it, 3 × 3 (its image is twice as fine).
        const double zm = raw * unit, u = double(i % w), v = double(i / w);
        const Eigen::Vector4d p = rgbFromIr() * Eigen::Vector4d((u - cam.depth_k.cx) * zm / cam.depth_k.fx,
                                                                (v - cam.depth_k.cy) * zm / cam.depth_k.fy, zm, 1);
        const long ur = std::lround(cam.rgb_k.fx * p.x() / p.z() + cam.rgb_k.cx);
        const long vr = std::lround(cam.rgb_k.fy * p.y() / p.z() + cam.rgb_k.cy);
        for (long dv = -1; dv <= 1; ++dv)
          for (long du = -1; du <= 1; ++du)
            if (ur + du >= 0 && ur + du < 1280 && vr + dv >= 0 && vr + dv < 1024) mask[(vr + dv) * 1280 + ur + du] = 1;
      }
      const std::string stem = "NP" + std::to_string(np) + "_" + std::to_string(angle);
      writeH5((dir / (stem + ".h5")).string(), {h5Depth(depth, w, h)});
      writePbm((dir / "masks" / (stem + "_mask.pbm")).string(), mask, 1280, 1024);
      std::ofstream(dir / (stem + ".jpg")) << "not read: keyturn describes shape only\n";
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: write_bigbird_fixture MOSD_DIR OUT_DIR\n";
    return 2;
  }
  const fs::path mosd = argv[1], out = argv[2];
  auto scene = [&](const std::string& name, const std::string& object) {
    return Scene{loadCloud((mosd / "full" / (name + ".pcd")).string()),
                 loadCloud((mosd / "masked" / (name + "_" + object + ".pcd")).string())};
  };
  const Scene box = scene("learn0", "o1"), cylinder = scene("learn34", "o1");
  writeObject(out / "bigbird" / "box_1", box, 1);
  writeObject(out / "bigbird" / "cylinder_1", cylinder, 2);
  std::ofstream(out / "categories.csv") << "class,instance\nbox,box_1\ncylinder,cylinder_1\n";

  const fs::path bad = out / "bigbird_bad";
  writeObject(bad / "box_1", box, 3, /*with_pose_6=*/false);  // NP1_6.h5 and NP3_6.h5 without their pose
  writeObject(bad / "uncalibrated", cylinder, 4);
  fs::remove(bad / "uncalibrated" / "calibration.h5");
  std::ofstream(bad / "box_1" / "NP5_0.h5") << "\x89HDF\r\n\x1a\n and then nothing an HDF5 library could read";
  fs::copy_file(bad / "box_1" / "poses" / "NP5_0_pose.h5", bad / "box_1" / "NP2_0.h5");  // no "depth"
  writeH5((bad / "box_1" / "NP4_0.h5").string(), {{"depth", H5Type::Float32, {48, 64}, std::vector<double>(64 * 48, 1000)}});
  std::ofstream(bad / "box_1" / "NP7_0.h5") << "";
  std::cout << "bigbird fixtures in " << out.string() << "\n";
  return 0;
}
