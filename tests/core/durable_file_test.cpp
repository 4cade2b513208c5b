// Durable files: whole or not at all, and one clear line when they cannot be written.
#include "keyturn/core/durable_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "keyturn/core/error.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using namespace keyturn;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST(DurableFile, WritesReplacesAndLeavesNoTemporary) {
  const test::ScratchFolder scratch("durable_write");
  const fs::path& d = scratch.path;
  const fs::path f = d / "sub" / "a.txt";
  writeFileDurably(f.string(), std::string("one\0two", 7));
  EXPECT_EQ(read(f), std::string("one\0two", 7)) << "bytes as given, folders created";
  writeFileDurably(f.string(), "three\n");
  EXPECT_EQ(read(f), "three\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(d / "sub"), fs::directory_iterator()), 1);
}

TEST(DurableFile, AppendsWholeLinesAndCommitsATemporary) {
  const test::ScratchFolder scratch("durable_append");
  const fs::path& d = scratch.path;
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
  const test::ScratchFolder scratch("durable_fail");
  const fs::path& d = scratch.path;
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
  const test::ScratchFolder scratch("durable_mode");
  const fs::path& d = scratch.path;
  writeFileDurably((d / "m.json").string(), "{}");
  EXPECT_EQ(fs::status(d / "m.json").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
}

TEST(DurableFile, ALibraryWritesTheTemporaryByNameKeepingTheExtension) {
  const test::ScratchFolder scratch("durable_with");
  const fs::path& d = scratch.path;
  const std::string target = (d / "v" / "a5.0_distance.png").string();
  std::string seen;
  writeFileDurablyWith(target, [&](const std::string& tmp) {
    seen = tmp;
    std::ofstream(tmp, std::ios::trunc) << "png bytes";
  });
  EXPECT_EQ(read(target), "png bytes");
  EXPECT_EQ(seen.rfind(target + ".tmp.", 0), 0u) << seen;
  EXPECT_EQ(seen.substr(seen.size() - 4), ".png") << "an encoder picks its format by the extension: " << seen;
  EXPECT_TRUE(isInterruptedWriteTemporary(seen)) << seen;
  EXPECT_EQ(fs::status(target).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
  // A writer that fails leaves neither the target nor its temporary.
  const std::string other = (d / "v" / "b.pcd").string();
  EXPECT_EQ(test::errorOf([&] {
              writeFileDurablyWith(other, [&](const std::string& tmp) {
                std::ofstream(tmp) << "half";
                throw Error(other + ": could not write the point cloud");
              });
            }),
            other + ": could not write the point cloud");
  EXPECT_EQ(std::distance(fs::directory_iterator(d / "v"), fs::directory_iterator()), 1);
}

TEST(DurableFile, KnowsTheTemporariesAKilledWriteLeaves) {
  for (const char* name : {"a40.0.json.tmp.Ab12Cd", "a40.0.pcd.tmp.x9Y8z7", "a40.0_distance.png.tmp.QwErT1.png",
                           "manifest.csv.tmp.000aaa", "e30/a40.0.pcd.tmp", "a40.0_amplitude.tmp.png"})
    EXPECT_TRUE(isInterruptedWriteTemporary(name)) << name;
  for (const char* name : {"a40.0.json", "a40.0.pcd", "notes.tmp", "a.tmp.Ab12C", "a.tmp.Ab-12C", "x.png.tmp.Ab12Cd.pcd",
                           ".tmp.Ab12Cd.png", "a40.0_distance.png"})
    EXPECT_FALSE(isInterruptedWriteTemporary(name)) << name;
}

TEST(DurableFile, RemovesLeftoverTemporariesButNotUnderSkippedFolders) {
  const test::ScratchFolder scratch("durable_leftovers");
  const fs::path& d = scratch.path;
  for (const char* f : {"m.csv.tmp.Ab12Cd", "c/i/e30/a5.0.json.tmp.Zz99Yy", "c/i/e30/a5.0.json", ".keyturn/f.bin.tmp.Ab12Cd"}) {
    fs::create_directories((d / f).parent_path());
    std::ofstream(d / f) << "x";
  }
  EXPECT_EQ(removeInterruptedWriteTemporaries(d.string(), {".keyturn"}), 2u);
  EXPECT_FALSE(fs::exists(d / "m.csv.tmp.Ab12Cd"));
  EXPECT_FALSE(fs::exists(d / "c/i/e30/a5.0.json.tmp.Zz99Yy"));
  EXPECT_TRUE(fs::exists(d / "c/i/e30/a5.0.json"));
  EXPECT_TRUE(fs::exists(d / ".keyturn/f.bin.tmp.Ab12Cd")) << "another process may be writing it";
  EXPECT_EQ(removeInterruptedWriteTemporaries((d / "none").string()), 0u);
}
