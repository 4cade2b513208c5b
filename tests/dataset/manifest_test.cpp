// Manifests saved by other tools: a spreadsheet's CRLF endings and UTF-8 byte order mark are read as
// keyturn's own; any other first line is refused in one line naming the file and what differs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "keyturn/core/cloud_io.h"
#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;

namespace {

// ROOT (absent) made a dataset of two views; returns ROOT.
const fs::path& datasetWithTwoViews(const fs::path& root) {
  dataset::Dataset ds(root.string());
  Cloud cloud;
  cloud.width = 2;
  cloud.height = 2;
  cloud.points.assign(4, Eigen::Vector3f(0.f, 0.f, 1.f));
  const auto writePcd = [&cloud](const std::string& pcd) {
    saveCloud(pcd, cloud, PcdEncoding::BinaryCompressed);
    return std::vector<std::string>{pcd};
  };
  for (double a : {0.0, 90.0}) ds.writeCaptured({"box", "b1", "30", a}, dataset::ViewMetadata(), {}, writePcd);
  return root;
}

std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void writeText(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary | std::ios::trunc) << s; }

std::string withCrlf(const std::string& lf) {
  std::string out;
  for (char c : lf) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
  return out;
}

std::string refusal(const fs::path& root) {
  try {
    (void)dataset::Dataset::verify(root.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Manifest, CrlfEndingsAndAByteOrderMarkReadAsTheOriginal) {
  const keyturn::test::ScratchFolder scratch("manifest_crlf");
  const fs::path& root = datasetWithTwoViews(scratch.path);
  const auto original = dataset::Dataset::readManifest(root.string());
  ASSERT_EQ(original.size(), 2u);
  writeText(root / "manifest.csv", "\xEF\xBB\xBF" + withCrlf(readText(root / "manifest.csv")));

  std::vector<std::string> bad;
  const auto read = dataset::Dataset::readManifest(root.string(), &bad);
  EXPECT_TRUE(bad.empty());
  ASSERT_EQ(read.size(), 2u);
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].files, original[i].files);
    EXPECT_EQ(read[i].sha256, original[i].sha256);  // the last column carries no '\r'
    EXPECT_EQ(read[i].captured_at, original[i].captured_at);
  }
  const auto report = dataset::Dataset::verify(root.string());
  EXPECT_TRUE(report.good()) << report.text(root.string());
  EXPECT_EQ(report.views, 2u);
  EXPECT_TRUE(report.orphans.empty());

  // A capture resumed on it appends to it and still finds both views.
  dataset::Dataset reopened(root.string());
  EXPECT_EQ(reopened.views().size(), 2u);
  EXPECT_TRUE(reopened.has({"box", "b1", "30", 90.0}));
}

TEST(Manifest, AnotherHeaderIsRefusedWithTheReason) {
  const keyturn::test::ScratchFolder scratch("manifest_header");
  const fs::path& root = datasetWithTwoViews(scratch.path);
  const std::string text = readText(root / "manifest.csv");
  const std::string rows = text.substr(text.find('\n') + 1);
  const std::string file = (root / "manifest.csv").string();

  writeText(root / "manifest.csv", "class,instance,elev,elevation_deg,commanded_deg,measured_deg,captured_at,files,sha256\n" + rows);
  std::string why = refusal(root);
  EXPECT_EQ(why.rfind(file + ": line 1: column 3 is 'elev', expected 'elevation'", 0), 0u) << why;
  EXPECT_EQ(why.find('\n'), std::string::npos);

  writeText(root / "manifest.csv", "class,instance,elevation,elevation_deg,commanded_deg,measured_deg,captured_at,files\n" + rows);
  why = refusal(root);
  EXPECT_EQ(why.rfind(file + ": line 1: header has 8 columns, expected 9", 0), 0u) << why;

  writeText(root / "manifest.csv", "class;instance;elevation\n" + rows);
  why = refusal(root);
  EXPECT_EQ(why.rfind(file + ": line 1: column 1 is 'class;instance;elevation', expected 'class'", 0), 0u) << why;

  writeText(root / "manifest.csv", "\n" + rows);
  why = refusal(root);
  EXPECT_EQ(why.rfind(file + ": line 1 is empty", 0), 0u) << why;
  EXPECT_THROW(dataset::Dataset reopened(root.string()), Error);
}

// evaluate, train and describe --cache keep the features in DATASET/.keyturn/: keyturn's own file,
// not an orphan of an interrupted capture.
TEST(Manifest, TheFeatureCacheIsNoOrphan) {
  const keyturn::test::ScratchFolder scratch("manifest_cache");
  const fs::path& root = datasetWithTwoViews(scratch.path);
  fs::create_directories(root / ".keyturn");
  writeText(root / ".keyturn" / "features-0123456789abcdef.csv", "# keyturn-features 1\n");
  writeText(root / "box" / "stray.pcd", "x");
  const auto report = dataset::Dataset::verify(root.string());
  EXPECT_EQ(report.orphans, std::vector<std::string>{"box/stray.pcd"});
}

// A row whose file leaves the dataset folder is a bad row: verify must not open (and hash) a file
// outside it, such as ../../../../etc/hostname (issue 35). The other rows are verified.
TEST(Manifest, AFileOutsideTheDatasetIsABadRowAndTheRestIsVerified) {
  const keyturn::test::ScratchFolder scratch("manifest_outside");
  const fs::path& root = datasetWithTwoViews(scratch.path);
  const std::string sha = std::string(64, '0');
  std::ofstream(root / "manifest.csv", std::ios::app)
      << "box,b1,30,30.000,180.000,180.0000,2026-01-01T00:00:00.000Z,../../../../etc/hostname," << sha << "\n"
      << "box,b1,30,30.000,270.000,270.0000,2026-01-01T00:00:00.000Z,/etc/hostname," << sha << "\n";
  const auto report = dataset::Dataset::verify(root.string());
  EXPECT_EQ(report.views, 2u);
  EXPECT_EQ(report.bad_rows,
            (std::vector<std::string>{"line 4: file '../../../../etc/hostname' leaves the dataset folder ('..')",
                                      "line 5: file '/etc/hostname' is an absolute path, outside the dataset"}));
  EXPECT_TRUE(report.missing.empty());
  EXPECT_TRUE(report.corrupt.empty());  // hashed, /etc/hostname would have been "corrupt"
}

// fuzz_dataset, 300 s pass (issue 35): a file name longer than the file system allows made
// std::filesystem::exists throw in verify, which stopped the whole dataset ("unexpected failure").
TEST(Manifest, AFileNameLongerThanTheFileSystemAllowsIsABadRowAndTheRestIsVerified) {
  const keyturn::test::ScratchFolder scratch("manifest_longname");
  const fs::path& root = datasetWithTwoViews(scratch.path);
  std::ofstream(root / "manifest.csv", std::ios::app) << "box,b1,30,30.000,180.000,180.0000,2026-01-01T00:00:00.000Z,box/"
                                                      << std::string(300, 'a') << ".pcd," << std::string(64, '0') << "\n";
  const auto report = dataset::Dataset::verify(root.string());
  EXPECT_EQ(report.views, 2u);
  ASSERT_EQ(report.bad_rows.size(), 1u);
  EXPECT_EQ(report.bad_rows[0].rfind("line 4: file name 'box/aaaa", 0), 0u) << report.bad_rows[0];
  EXPECT_NE(report.bad_rows[0].find("has a component of 304 bytes (more than 255)"), std::string::npos)
      << report.bad_rows[0];
  EXPECT_TRUE(report.missing.empty());
  EXPECT_TRUE(report.corrupt.empty());
}

// Past the component check, the whole path can still be refused by the system (ENAMETOOLONG past
// PATH_MAX): that file is reported, not the dataset stopped.
TEST(Manifest, APathTheSystemRefusesIsThatFilesProblem) {
  const keyturn::test::ScratchFolder scratch("manifest_longpath");
  const fs::path& root = datasetWithTwoViews(scratch.path);
  std::string deep;
  for (int i = 0; i < 30; ++i) deep += std::string(200, 'd') + "/";
  std::ofstream(root / "manifest.csv", std::ios::app) << "box,b1,30,30.000,180.000,180.0000,2026-01-01T00:00:00.000Z,"
                                                      << deep << "v.pcd," << std::string(64, '0') << "\n";
  const auto report = dataset::Dataset::verify(root.string());
  EXPECT_EQ(report.views, 3u);
  ASSERT_EQ(report.corrupt.size(), 1u);
  EXPECT_NE(report.corrupt[0].find("(cannot be read: File name too long)"), std::string::npos) << report.corrupt[0];
}
