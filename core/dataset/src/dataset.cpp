#include "keyturn/dataset/dataset.h"

#include <openssl/evp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/core/durable_file.h"
#include "keyturn/core/view_files.h"
#include "keyturn/dataset/feature_cache_files.h"
#include "utc_time.h"

#ifndef KEYTURN_VERSION
#define KEYTURN_VERSION "unknown"
#endif

namespace fs = std::filesystem;

namespace keyturn::dataset {

std::string isoNow() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  char buf[40];
  std::tm tm{};
  gmtime_r(&t, &tm);
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(ms));
  return buf;
}

namespace {

constexpr int kColumns = 9;

// A file the studio saved beside the views (kSnapshotsFolder/NAME: not in a subfolder, where a
// class of that name would keep its views).
bool isSnapshot(const std::string& rel) {
  const std::string prefix = std::string(kSnapshotsFolder) + "/";
  return rel.rfind(prefix, 0) == 0 && rel.find('/', prefix.size()) == std::string::npos;
}

// What a writer keeps beside the views before the first one: the dataset's description and
// manifest, the axis calibration, the simulator's state and the writers' lock.
bool isWritersOwnFile(const std::string& rel) {
  return rel == kDescriptionFile || rel == kManifestFile || rel == kCalibrationFile || rel == kLockFile ||
         rel.rfind(std::string(kSimulatorFolder) + "/", 0) == 0;
}

std::string fmt(double v, int decimals) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

bool safeName(const std::string& s) {
  if (s.empty() || s == "." || s == "..") return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return true;
}

// A manifest's file names are paths inside the dataset folder, made by keyturn from safe names:
// why a row's name is refused (a path leaving the folder, one no file system holds), or "".
std::string unsafeViewFile(const std::vector<std::string>& files) {
  constexpr std::size_t kNameMax = 255;  // bytes per path component (NAME_MAX of Linux file systems)
  for (const auto& f : files) {
    const std::string shown = "'" + (f.size() > 60 ? f.substr(0, 60) + "…" : f) + "'";
    if (f.empty()) return "an empty file name";
    if (f.find('\0') != std::string::npos) return "file name " + shown + " holds a NUL byte";
    if (f.front() == '/') return "file " + shown + " is an absolute path, outside the dataset";
    std::size_t begin = 0;
    while (begin <= f.size()) {
      const std::size_t end = std::min(f.find('/', begin), f.size());
      const std::string part = f.substr(begin, end - begin);
      if (part == "..") return "file " + shown + " leaves the dataset folder ('..')";
      if (part.size() > kNameMax)
        return "file name " + shown + " has a component of " + std::to_string(part.size()) + " bytes (more than " +
               std::to_string(kNameMax) + ")";
      begin = end + 1;
    }
  }
  return "";
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream ss(s);
  while (std::getline(ss, cur, sep)) out.push_back(cur);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

std::string join(const std::vector<std::string>& v, char sep) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? std::string(1, sep) : "") + v[i];
  return out;
}

std::string rowOf(const ViewRecord& r) {
  return r.key.cls + "," + r.key.instance + "," + r.key.elevation + "," + fmt(r.elevation_deg, 3) + "," +
         fmt(r.key.commanded_deg, 3) + "," + fmt(r.measured_deg, 4) + "," + r.captured_at + "," + join(r.files, ';') +
         "," + join(r.sha256, ';');
}

// A capture killed while appending leaves a last row without its newline: that
// view was never complete. Cut the row off so the view is simply taken again.
void repairInterruptedAppend(const std::string& manifest) {
  std::ifstream in(manifest, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.empty() || text.back() == '\n') return;
  const auto keep = text.rfind('\n');
  writeFileDurably(manifest, keep == std::string::npos ? manifestHeader() + "\n" : text.substr(0, keep + 1));
}

std::string fileEndingIn(const std::vector<std::string>& files, const std::string& suffix) {
  for (const auto& f : files)
    if (f.size() > suffix.size() && f.compare(f.size() - suffix.size(), suffix.size(), suffix) == 0) return f;
  return "";
}

// Spreadsheets and Windows editors save CSV with CRLF endings and a UTF-8 byte order mark.
constexpr const char* kUtf8Bom = "\xEF\xBB\xBF";

void stripLineEnding(std::string& line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
}

// Why a first line is not keyturn's manifest header, in one line.
std::string headerProblem(const std::string& line) {
  if (line.empty()) return "line 1 is empty, expected the header '" + manifestHeader() + "'";
  const auto got = split(line, ',');
  const auto want = split(manifestHeader(), ',');
  for (std::size_t i = 0; i < std::min(got.size(), want.size()); ++i)
    if (got[i] != want[i])
      return "line 1: column " + std::to_string(i + 1) + " is '" + got[i] + "', expected '" + want[i] +
             "' (header: " + manifestHeader() + ")";
  return "line 1: header has " + std::to_string(got.size()) + " columns, expected " + std::to_string(want.size()) +
         " (" + manifestHeader() + ")";
}

}  // namespace

std::string sha256File(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read to checksum");
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr);
  char buf[65536];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) EVP_DigestUpdate(ctx.get(), buf, static_cast<std::size_t>(in.gcount()));
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned len = 0;
  EVP_DigestFinal_ex(ctx.get(), md, &len);
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned i = 0; i < len; ++i) {
    out += hex[md[i] >> 4];
    out += hex[md[i] & 15];
  }
  return out;
}


std::string ViewRecord::pcd() const { return fileEndingIn(files, ".pcd"); }
std::string ViewRecord::sidecar() const { return fileEndingIn(files, ".json"); }

bool ViewKey::operator==(const ViewKey& o) const {
  return cls == o.cls && instance == o.instance && elevation == o.elevation &&
         std::abs(commanded_deg - o.commanded_deg) < 5e-4;
}

std::string manifestHeader() {
  return "class,instance,elevation,elevation_deg,commanded_deg,measured_deg,captured_at,files,sha256";
}

Dataset::Dataset(std::string root) : Dataset(root, DatasetLock(root)) {}

Dataset::Dataset(std::string root, DatasetLock lock) : root_(std::move(root)), lock_(std::move(lock)) {
  const std::string info = datasetPath(root_, kDescriptionFile);
  if (!fs::exists(info)) {
    const nlohmann::json j = {{"format", "keyturn-dataset"}, {"version", 1}, {"created", isoNow()},
                              {"keyturn_version", KEYTURN_VERSION}};
    writeFileDurably(info, j.dump(2) + "\n");
  }
  // The lock keeps other writers out; the feature cache (.keyturn/) may be filling in another process,
  // and the simulator keeps its own state.
  temporaries_removed_ = removeInterruptedWriteTemporaries(root_, {kKeyturnFolder, kSimulatorFolder});
  const std::string manifest = manifestPath(root_);
  if (!fs::exists(manifest)) writeFileDurably(manifest, manifestHeader() + "\n");
  repairInterruptedAppend(manifest);
  std::vector<std::string> bad;
  views_ = readManifest(root_, &bad);
  if (!bad.empty()) throw Error(manifest + ": " + bad.front() + " (run keyturn verify)");
}

bool Dataset::has(const ViewKey& key) const {
  for (const auto& v : views_)
    if (v.key == key) return true;
  return false;
}

std::string Dataset::viewStem(const ViewKey& k) const {
  for (const auto* s : {&k.cls, &k.instance, &k.elevation})
    if (!safeName(*s)) throw Error("'" + *s + "': class, instance and elevation may use letters, digits, _ - . only");
  return k.cls + "/" + k.instance + "/e" + k.elevation + "/a" + fmt(k.commanded_deg, 1);
}

namespace {

// The sidecar's keys every view has, captured or imported.
nlohmann::json baseSidecar(const ViewKey& key, const ViewMetadata& meta) {
  nlohmann::json j;
  j["class"] = key.cls;
  j["instance"] = key.instance;
  j["elevation"] = {{"label", key.elevation}, {"degrees", meta.elevation_deg}};
  j["commanded_deg"] = key.commanded_deg;
  j["measured_deg"] = meta.measured_deg;
  if (meta.camera_from_turntable) {
    nlohmann::json m = nlohmann::json::array();
    for (int row = 0; row < 4; ++row) {
      nlohmann::json rj = nlohmann::json::array();
      for (int c = 0; c < 4; ++c) rj.push_back((*meta.camera_from_turntable)(row, c));
      m.push_back(rj);
    }
    j["camera_from_turntable"] = m;
  } else {
    j["camera_from_turntable"] = nullptr;  // not calibrated
  }
  j["pose_source"] = meta.pose_source;
  return j;
}

}  // namespace

// A view taken again after an interrupted capture starts clean: the files the interrupted take left
// (no row names them) go, so none of them outlives the retake (a camera that gave a confidence map
// then and none now). Only the kinds a view has (writeFrameFiles' and the sidecar) are touched.
void Dataset::removeFilesWithoutRow(const std::string& abs_stem) const {
  std::set<std::string> referenced;
  for (const auto& v : views_) referenced.insert(v.files.begin(), v.files.end());
  for (const char* suffix : {".pcd", kDistanceImageSuffix, kAmplitudeImageSuffix, kConfidenceImageSuffix, ".json"}) {
    const std::string path = abs_stem + suffix;
    std::error_code ec;
    if (!referenced.count(path.substr(root_.size() + 1)) && fs::is_regular_file(path, ec)) fs::remove(path, ec);
  }
}

ViewRecord Dataset::beginView(const ViewKey& key, const ViewMetadata& meta, std::string& abs_stem) const {
  if (has(key)) throw Error(root_ + ": view " + viewStem(key) + " already captured");
  abs_stem = root_ + "/" + viewStem(key);
  fs::create_directories(fs::path(abs_stem).parent_path());
  removeFilesWithoutRow(abs_stem);
  ViewRecord r;
  r.key = key;
  r.elevation_deg = meta.elevation_deg;
  r.measured_deg = meta.measured_deg;
  r.captured_at = isoNow();
  return r;
}

ViewRecord Dataset::commitView(ViewRecord r, const std::string& abs_stem, const std::string& sidecar_json) {
  writeFileDurably(abs_stem + ".json", sidecar_json);
  r.files.push_back(abs_stem.substr(root_.size() + 1) + ".json");
  syncDirectory(fs::path(abs_stem).parent_path().string());
  // Every file is durable under its final name by now (each one renamed into place after its
  // temporary was flushed): the checksums are of the bytes committed, the row comes after them.
  for (const auto& f : r.files) r.sha256.push_back(sha256File(root_ + "/" + f));
  appendLineDurably(manifestPath(root_), rowOf(r));  // the view exists from here on
  views_.push_back(r);
  return r;
}

ViewRecord Dataset::writeCaptured(const ViewKey& key, const ViewMetadata& meta, const SidecarCamera& camera,
                                  const FileWriter& write_files) {
  std::string abs_stem;
  ViewRecord r = beginView(key, meta, abs_stem);
  for (const auto& f : write_files(abs_stem + ".pcd")) r.files.push_back(f.substr(root_.size() + 1));
  nlohmann::json j = baseSidecar(key, meta);
  nlohmann::json& c = j["camera"];
  c = {{"device", camera.device}, {"serial", camera.serial}};
  if (camera.modulation_mhz) c["modulation_mhz"] = *camera.modulation_mhz;
  if (camera.integration_time) c["integration_time"] = *camera.integration_time;
  if (camera.auto_exposure) c["auto_exposure"] = *camera.auto_exposure;
  if (camera.amplitude_threshold) c["amplitude_threshold"] = *camera.amplitude_threshold;
  if (camera.acquire_mode) c["acquire_mode"] = *camera.acquire_mode;
  j["frames"] = {{"discarded", meta.frames_discarded}, {"taken", meta.frames_taken}, {"redos", meta.redos}};
  j["captured_at"] = r.captured_at;
  j["keyturn_version"] = KEYTURN_VERSION;
  return commitView(r, abs_stem, j.dump(2) + "\n");
}

ViewRecord Dataset::writeImported(const ViewKey& key, const ViewMetadata& meta, const Cloud& cloud,
                                  const std::string& source, const std::string& importer) {
  std::string abs_stem;
  ViewRecord r = beginView(key, meta, abs_stem);
  saveCloud(abs_stem + ".pcd", cloud, PcdEncoding::BinaryCompressed);
  r.files.push_back(abs_stem.substr(root_.size() + 1) + ".pcd");
  nlohmann::json j = baseSidecar(key, meta);
  j["source"] = source;
  j["imported_by"] = importer;
  j["imported_at"] = r.captured_at;
  j["keyturn_version"] = KEYTURN_VERSION;
  return commitView(r, abs_stem, j.dump(2) + "\n");
}

std::vector<ViewRecord> Dataset::readManifest(const std::string& root, std::vector<std::string>* bad_rows) {
  std::vector<ViewRecord> out;
  const std::string path = manifestPath(root);
  std::ifstream in(path);
  if (!in) throw Error(path + ": no manifest (not a keyturn dataset?)");
  std::string line;
  std::getline(in, line);
  stripLineEnding(line);
  if (line.rfind(kUtf8Bom, 0) == 0) line.erase(0, std::strlen(kUtf8Bom));
  if (line != manifestHeader()) throw Error(path + ": " + headerProblem(line));
  int n = 1;
  while (std::getline(in, line)) {
    ++n;
    stripLineEnding(line);
    if (in.eof() && !line.empty()) {
      // A row without its newline was cut off mid-append: not a view.
      if (bad_rows) bad_rows->push_back("line " + std::to_string(n) + ": unterminated row (interrupted append)");
      break;
    }
    if (line.empty()) continue;
    const auto c = split(line, ',');
    try {
      if (c.size() != kColumns) throw std::invalid_argument("columns");
      ViewRecord r;
      r.key = {c[0], c[1], c[2], std::stod(c[4])};
      r.elevation_deg = std::stod(c[3]);
      r.measured_deg = std::stod(c[5]);
      r.captured_at = c[6];
      r.files = split(c[7], ';');
      r.sha256 = split(c[8], ';');
      if (r.files.size() != r.sha256.size() || r.files.empty()) throw std::invalid_argument("files");
      if (const std::string why = unsafeViewFile(r.files); !why.empty()) {
        if (bad_rows) bad_rows->push_back("line " + std::to_string(n) + ": " + why);
        continue;
      }
      out.push_back(r);
    } catch (const std::exception&) {
      if (bad_rows) bad_rows->push_back("line " + std::to_string(n) + ": malformed row");
    }
  }
  return out;
}

VerifyReport Dataset::verify(const std::string& root) {
  VerifyReport rep;
  const auto views = readManifest(root, &rep.bad_rows);
  rep.views = views.size();
  std::set<std::string> referenced;
  for (std::size_t i = 0; i < views.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (views[j].key == views[i].key) rep.duplicates.push_back(views[i].files.front());
    for (std::size_t f = 0; f < views[i].files.size(); ++f) {
      const std::string& rel = views[i].files[f];
      referenced.insert(rel);
      const std::string abs = root + "/" + rel;
      // One file's trouble (a path the system refuses, no permission) is that file's, not the dataset's.
      std::error_code ec;
      const auto st = fs::status(abs, ec);
      if (st.type() == fs::file_type::not_found) rep.missing.push_back(rel);
      else if (ec) rep.corrupt.push_back(rel + " (cannot be read: " + ec.message() + ")");
      else if (st.type() != fs::file_type::regular) rep.corrupt.push_back(rel + " (not a regular file)");
      else {
        try {
          if (sha256File(abs) != views[i].sha256[f]) rep.corrupt.push_back(rel);
        } catch (const Error&) {
          rep.corrupt.push_back(rel + " (cannot be read)");
        }
      }
    }
  }
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    std::error_code rel_ec;
    const std::string rel = fs::relative(it->path(), root, rel_ec).string();
    if (rel_ec) continue;
    // keyturn's own files beside the views: the writers' (the simulator's state, the lock), the
    // feature cache (.keyturn/) and the studio's snapshots.
    if (isWritersOwnFile(rel) || rel.rfind(std::string(kKeyturnFolder) + "/", 0) == 0 || isSnapshot(rel)) continue;
    if (referenced.count(rel)) continue;
    if (isInterruptedWriteTemporary(rel)) rep.temporaries.push_back(rel);
    else rep.orphans.push_back(rel);
  }
  return rep;
}

void removeDatasetWithoutViews(const std::string& root) {
  // Only what a capture writes before its first view: a folder with anything else in it (a
  // manifest that is not keyturn's, a user's own files) is left as it is, and so is one that
  // another writer holds (it may be about to write its first view).
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return;
  std::optional<DatasetLock> lock;
  try {
    lock.emplace(root);
  } catch (const Error&) {
    return;
  }
  for (auto it = fs::recursive_directory_iterator(root, ec); it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const std::string rel = fs::relative(it->path(), root).string();
    if (!isWritersOwnFile(rel) && !isInterruptedWriteTemporary(rel)) return;
  }
  if (ec) return;
  if (fs::exists(fs::path(root) / kManifestFile)) {
    std::vector<std::string> bad;
    try {
      if (!Dataset::readManifest(root, &bad).empty() || !bad.empty()) return;  // views, or not keyturn's
    } catch (const Error&) {
      return;
    }
  }
  fs::remove_all(root, ec);
}

std::string VerifyReport::text(const std::string& root) const {
  std::ostringstream out;
  auto list = [&out](const char* what, const std::vector<std::string>& v) {
    for (const auto& f : v) out << what << ": " << f << "\n";
  };
  list("missing", missing);
  list("corrupt", corrupt);
  list("orphan", orphans);
  list("duplicate", duplicates);
  list("bad manifest row", bad_rows);
  list("temporary", temporaries);
  if (!temporaries.empty())
    out << temporaries.size() << " leftover temporary file" << (temporaries.size() == 1 ? "" : "s")
        << " from an interrupted write (not part of any view; the next capture removes them)\n";
  out << root << ": " << views << " views, " << missing.size() << " missing, " << corrupt.size() << " corrupt, "
      << orphans.size() << " orphan, " << duplicates.size() << " duplicate files"
      << (good() ? " — OK" : ok() ? " — EMPTY (no views)" : " — PROBLEMS") << "\n";
  return out.str();
}

}  // namespace keyturn::dataset
