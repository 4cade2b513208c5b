// Durable files: whole or not at all, and one clear line when they cannot be written.
#include "keyturn/core/durable_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "support/error_of.h"

using namespace keyturn;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

fs::path fresh(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / name;
  fs::remove_all(d);
  return d;
}

}  // namespace

TEST(DurableFile, WritesReplacesAndLeavesNoTemporary) {
  const fs::path d = fresh("keyturn_durable_write");
  const fs::path f = d / "sub" / "a.txt";
  writeFileDurably(f.string(), std::string("one\0two", 7));
  EXPECT_EQ(read(f), std::string("one\0two", 7)) << "bytes as given, folders created";
  writeFileDurably(f.string(), "three\n");
  EXPECT_EQ(read(f), "three\n");
  EXPECT_FALSE(fs::exists(f.string() + ".tmp"));
  EXPECT_EQ(std::distance(fs::directory_iterator(d / "sub"), fs::directory_iterator()), 1);
}

TEST(DurableFile, AppendsWholeLinesAndCommitsATemporary) {
  const fs::path d = fresh("keyturn_durable_append");
  fs::create_directories(d);
  const std::string log = (d / "m.csv").string();
  appendLineDurably(log, "a,1");
  appendLineDurably(log, "b,2");
  EXPECT_EQ(read(log), "a,1\nb,2\n");
  const std::string tmp = (d / "x.tmp").string();
  std::ofstream(tmp) << "payload";
  commitFile(tmp, (d / "x").string());
  EXPECT_EQ(read(d / "x"), "payload");
  EXPECT_FALSE(fs::exists(tmp));
}

TEST(DurableFile, AFileThatCannotBeWrittenIsOneLineNamingIt) {
  const fs::path d = fresh("keyturn_durable_fail");
  fs::create_directories(d / "taken");
  // A folder where the temporary file would go.
  fs::create_directories(d / "taken" / "f.txt.tmp");
  const std::string target = (d / "taken" / "f.txt").string();
  const std::string e = test::errorOf([&] { writeFileDurably(target, "x"); });
  EXPECT_EQ(e.rfind(target + ": cannot open for writing", 0), 0u) << e;
  EXPECT_FALSE(fs::exists(target));
  const std::string missing = (d / "none.tmp").string();
  EXPECT_EQ(test::errorOf([&] { commitFile(missing, (d / "none").string()); }).rfind(missing + ": cannot open to sync", 0), 0u);
  EXPECT_NE(test::errorOf([&] { appendLineDurably((d / "no" / "dir.csv").string(), "x"); }).find("cannot open for appending"),
            std::string::npos);
}
