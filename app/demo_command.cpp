// keyturn demo: the whole job on simulated devices in one command — simulate a
// small dataset of shipped objects through the real drivers, verify it,
// describe every view, and summarise the keypoint counts per object.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "commands.h"
#include "keyturn/core/error.h"
#include "keyturn/core/install_layout.h"


namespace fs = std::filesystem;

namespace keyturn::app {
namespace {

struct DemoArgs {
  std::string out = "out/demo";  // as scripts/demo.sh
  std::string data;  // empty: keyturn::dataDirectory()
  double step = 30;
};

std::string self() {
  char buf[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) throw Error("demo: cannot find the keyturn executable");
  buf[n] = '\0';
  return buf;
}

int run(const std::string& cmd) {
  std::fprintf(stderr, "\n$ %s\n", cmd.c_str());
  std::fflush(stderr);
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : 1;
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

int runDemo(const DemoArgs& a) {
  const std::string kt = quote(self());
  const std::string data = a.data.empty() ? dataDirectory().string() : a.data;
  fs::create_directories(a.out);
  // Four shipped objects of different shapes and sizes.
  const std::string list = a.out + "/objects.csv";
  {
    std::ofstream f(list);
    f << "class,instance,mesh\n";
    for (const char* m : {"mug__ycb_025_mug", "can__ycb_005_tomato_soup_can", "box__ycb_004_sugar_box",
                          "bottle__ycb_006_mustard_bottle"}) {
      const std::string name = m;
      const auto sep = name.find("__");
      f << name.substr(0, sep) << ',' << name.substr(sep + 2) << ',' << fs::absolute(data + "/objects/" + name + ".ply").string() << "\n";
    }
  }
  const std::string ds = a.out + "/dataset";
  std::ostringstream step;
  step << a.step;
  if (run(kt + " simulate --objects " + quote(list) + " --elevations 30 --step " + step.str() + " --out " + quote(ds)) != 0)
    return 1;
  if (run(kt + " verify " + quote(ds)) != 0) return 1;
  const std::string csv = a.out + "/features.csv";
  if (run(kt + " describe " + quote(ds) + " --features kpd2,kpd3,kpa3,gkpd1,gkpd2,gkpcd2,d2,a3 --out " + quote(csv)) != 0)
    return 1;

  // Keypoint count K per object: min / mean / max over its views.
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  struct Stat { int n = 0, min = 1 << 30, max = 0; double sum = 0; };
  std::map<std::string, Stat> by_object;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string file, points, k;
    std::getline(ss, file, ',');
    std::getline(ss, points, ',');
    std::getline(ss, k, ',');
    const fs::path rel = fs::relative(file, ds);
    const std::string obj = (rel.begin())->string() + "/" + std::next(rel.begin())->string();
    Stat& s = by_object[obj];
    const int kv = std::stoi(k);
    ++s.n;
    s.sum += kv;
    s.min = std::min(s.min, kv);
    s.max = std::max(s.max, kv);
  }
  std::printf("\nKeypoints per view (ISS3D on the filtered simulated SR4000 view):\n");
  std::printf("  %-36s %6s %6s %6s %6s\n", "object", "views", "min K", "mean K", "max K");
  for (const auto& [obj, s] : by_object)
    std::printf("  %-36s %6d %6d %6.1f %6d\n", obj.c_str(), s.n, s.min, s.sum / s.n, s.max);
  std::printf("\nDataset: %s   Features (one row per view): %s\n", ds.c_str(), csv.c_str());
  return 0;
}

}  // namespace

Command addDemoCommand(CLI::App& app) {
  auto a = std::make_shared<DemoArgs>();
  auto* cmd = app.add_subcommand("demo", "Simulate a small dataset of shipped objects, verify and describe it");
  cmd->add_option("--out,-o", a->out, "Working folder")->capture_default_str();
  cmd->add_option("--data", a->data, "keyturn's data folder (object meshes; default: PREFIX/share/keyturn or $KEYTURN_DATA_DIR)");
  cmd->add_option("--step", a->step, "Turntable step (°)")->capture_default_str();
  return {cmd, [a] { return runDemo(*a); }};
}

}  // namespace keyturn::app
