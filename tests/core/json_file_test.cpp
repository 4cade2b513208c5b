// The one reader of keyturn's JSON files (json_file.h): a bad file is one line naming it and what
// was wrong, whichever reader meets it.
#include <gtest/gtest.h>

#include <string>

#include "keyturn/core/camera_file.h"
#include "keyturn/core/json_file.h"
#include "keyturn/drivers/canopen_pose.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

using keyturn::JsonShape;
using keyturn::parseJson;
using keyturn::readJsonFile;
using keyturn::test::errorOf;
using keyturn::test::ScratchFolder;
using keyturn::test::writeText;

namespace {

TEST(JsonFile, AGoodFileIsRead) {
  ScratchFolder dir("json_file_good");
  const std::string p = writeText(dir.made() / "ok.json", R"({"classes": ["mug", "drill"], "inputs": 12})");
  const auto j = readJsonFile(p, JsonShape::Object);
  EXPECT_EQ(j.at("inputs").get<int>(), 12);
  EXPECT_EQ(j.at("classes").size(), 2u);
  EXPECT_EQ(readJsonFile(writeText(dir.path / "list.json", "[1, 2, 3]"), JsonShape::Array).size(), 3u);
}

TEST(JsonFile, ABadFileIsOneLineNamingItAndWhatWasWrong) {
  ScratchFolder dir("json_file_bad");
  const auto at = [&](const std::string& name, const std::string& text) { return writeText(dir.made() / name, text); };
  const std::string empty = at("empty.json", "");
  EXPECT_EQ(errorOf([&] { readJsonFile(empty); }), empty + ": empty file, expected JSON");
  // A copy cut short: where it ends and what the parser still wanted.
  const std::string cut = at("cut.json", R"({"classes": ["mug", "dri)");
  EXPECT_EQ(errorOf([&] { readJsonFile(cut); }), cut + ": not JSON at byte 24 (invalid string: missing closing quote; last read: '\"dri')");
  const std::string open = at("open.json", R"({"inputs": 12)");
  EXPECT_EQ(errorOf([&] { readJsonFile(open); }), open + ": not JSON at byte 13 (unexpected end of input; expected '}')");
  // A PNG given for a JSON file: its bytes are quoted printable, its line breaks not kept.
  const std::string png = at("image.json", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
  EXPECT_EQ(errorOf([&] { readJsonFile(png); }), png + ": not JSON at byte 1 (invalid literal; last read: '\\x89')");
  const std::string spaces = at("spaces.json", " \n\t\n");
  EXPECT_EQ(errorOf([&] { readJsonFile(spaces); }), spaces + ": not JSON at byte 4 (unexpected end of input; expected '[', '{', or a literal)");
  // A number past a double's range (found by fuzz_dataset, fuzz_configs and fuzz_learning: it ended the process).
  const std::string huge = at("huge.json", R"({"step": 22223e3022})");
  EXPECT_EQ(errorOf([&] { readJsonFile(huge); }), huge + ": not JSON (number overflow parsing '22223e3022')");
  // The wrong kind of value at the top.
  const std::string list = at("list.json", "[1, 2]");
  EXPECT_EQ(errorOf([&] { readJsonFile(list, JsonShape::Object); }), list + ": expected a JSON object, found an array");
  EXPECT_EQ(errorOf([&] { readJsonFile(at("text.json", "\"x\""), JsonShape::Array); }),
            (dir.path / "text.json").string() + ": expected a JSON array, found a string");
  EXPECT_EQ(errorOf([&] { readJsonFile(at("null.json", "null"), JsonShape::Object); }),
            (dir.path / "null.json").string() + ": expected a JSON object, found null");
  // Nothing to read.
  const std::string none = (dir.path / "none.json").string();
  EXPECT_EQ(errorOf([&] { readJsonFile(none); }), none + ": cannot read (No such file or directory)");
  EXPECT_EQ(errorOf([&] { readJsonFile(dir.path.string()); }), dir.path.string() + ": cannot read (a folder, not a JSON file)");
  // A text read elsewhere (a built-in profile, a sidecar in memory) gets the same words.
  EXPECT_EQ(errorOf([] { parseJson("", "keyturn-sim"); }), "keyturn-sim: empty file, expected JSON");
  EXPECT_EQ(errorOf([] { parseJson("{\"a\": 1", "m.json"); }), "m.json: not JSON at byte 7 (unexpected end of input; expected '}')");
}

// The readers of other folders meet a bad file with the same line (each one's own checks follow).
TEST(JsonFile, EveryReaderSaysItTheSameWay) {
  ScratchFolder dir("json_file_readers");
  const std::string empty = writeText(dir.made() / "empty.json", "");
  const std::string object = writeText(dir.path / "object.json", "{}");
  const std::string cut = writeText(dir.path / "cut.json", "{\"mesh\": ");
  EXPECT_EQ(errorOf([&] { keyturn::sim::MesaSrSimConfig::fromFile(empty); }), empty + ": empty file, expected JSON");
  EXPECT_EQ(errorOf([&] { keyturn::sim::MesaSrSimConfig::fromFile(cut); }),
            cut + ": not JSON at byte 9 (unexpected end of input; expected '[', '{', or a literal)");
  EXPECT_EQ(errorOf([&] { keyturn::drivers::CanOpenAxis::loadAll(object); }), object + ": expected a JSON array, found an object");
  EXPECT_EQ(errorOf([&] { keyturn::drivers::CanOpenAxis::loadAll(empty); }), empty + ": empty file, expected JSON");
  EXPECT_EQ(errorOf([&] { keyturn::readCameraFile(cut); }),
            cut + ": not JSON at byte 9 (unexpected end of input; expected '[', '{', or a literal)");
}

}  // namespace
