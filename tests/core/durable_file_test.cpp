// Durable files: whole or not at all, and one clear line when they cannot be written.
#include "keyturn/core/durable_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

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
  const fs::path d = fresh("keyturn_durable_write_" + std::to_string(::getpid()));
  const fs::path f = d / "sub" / "a.txt";
  writeFileDurably(f.string(), std::string("one\0two", 7));
  EXPECT_EQ(read(f), std::string("one\0two", 7)) << "bytes as given, folders created";
  writeFileDurably(f.string(), "three\n");
  EXPECT_EQ(read(f), "three\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(d / "sub"), fs::directory_iterator()), 1);
}

TEST(DurableFile, AppendsWholeLinesAndCommitsATemporary) {
  const fs::path d = fresh("keyturn_durable_append_" + std::to_string(::getpid()));
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

TEST(DurableFile, AFileThatCannotBeWrittenIsOneLineNamingItAndLeavesNoTemporary) {
  const fs::path d = fresh("keyturn_durable_fail_" + std::to_string(::getpid()));
  fs::create_directories(d);
  // Its folder cannot be made: a file stands where it would go.
  std::ofstream(d / "plain") << "x";
  const std::string under_file = (d / "plain" / "f.txt").string();
  std::string e = test::errorOf([&] { writeFileDurably(under_file, "x"); });
  EXPECT_EQ(e.rfind(under_file + ": cannot create its folder", 0), 0u) << e;
  // It cannot be moved into place: a folder with contents has its name.
  fs::create_directories(d / "taken" / "f.txt" / "inside");
  const std::string target = (d / "taken" / "f.txt").string();
  e = test::errorOf([&] { writeFileDurably(target, "x"); });
  EXPECT_EQ(e.rfind(target + ": cannot move the written file into place", 0), 0u) << e;
  EXPECT_EQ(std::distance(fs::directory_iterator(d / "taken"), fs::directory_iterator()), 1) << "the temporary is removed";
  const std::string missing = (d / "none.tmp").string();
  EXPECT_EQ(test::errorOf([&] { commitFile(missing, (d / "none").string()); }).rfind(missing + ": cannot open to sync", 0), 0u);
  EXPECT_NE(test::errorOf([&] { appendLineDurably((d / "no" / "dir.csv").string(), "x"); }).find("cannot open for appending"),
            std::string::npos);
}

TEST(DurableFile, WrittenFilesAreReadableByOthers) {
  const fs::path d = fresh("keyturn_durable_mode_" + std::to_string(::getpid()));
  writeFileDurably((d / "m.json").string(), "{}");
  EXPECT_EQ(fs::status(d / "m.json").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
}
