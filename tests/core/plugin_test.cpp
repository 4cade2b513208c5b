// The plugin loader (core/plugin.h): where it looks, and the one line it gives when a plugin or an
// entry point is missing or a file in its path is not a plugin.
#include "keyturn/core/plugin.h"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "keyturn/core/error.h"
#include "support/error_of.h"
#include "support/scratch_path.h"

namespace keyturn {
namespace {

namespace fs = std::filesystem;

TEST(Plugin, AShippedPluginIsFoundAndItsEntryPointResolved) {
  EXPECT_NE(pluginSymbol("png", "keyturn_png_decode"), nullptr);
  // Loaded once: the same address again.
  EXPECT_EQ(pluginSymbol("png", "keyturn_png_decode"), pluginSymbol("png", "keyturn_png_decode"));
}

TEST(Plugin, AMissingPluginNamesItselfAndTheFoldersSearched) {
  const std::string msg = test::errorOf([] { pluginSymbol("no_such_plugin", "anything"); });
  EXPECT_NE(msg.find("plugin 'no_such_plugin' (libkeyturn_no_such_plugin.so) not found in "), std::string::npos) << msg;
  EXPECT_NE(msg.find("KEYTURN_PLUGIN_PATH"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(Plugin, AMissingEntryPointIsNamed) {
  const std::string msg = test::errorOf([] { pluginSymbol("png", "keyturn_no_such_entry"); });
  EXPECT_NE(msg.find("plugin 'png' has no entry point 'keyturn_no_such_entry'"), std::string::npos) << msg;
}

TEST(Plugin, KeyturnPluginPathIsSearchedFirstAndABadFileIsNamed) {
  const test::ScratchFolder scratch("plugin_test");
  const fs::path& dir = scratch.made();
  std::ofstream(dir / "libkeyturn_bogus.so") << "not a shared object\n";
  ::setenv("KEYTURN_PLUGIN_PATH", ("/nonexistent:" + dir.string()).c_str(), 1);
  const std::string msg = test::errorOf([] { pluginSymbol("bogus", "anything"); });
  ::unsetenv("KEYTURN_PLUGIN_PATH");
  EXPECT_NE(msg.find("plugin 'bogus' (" + (dir / "libkeyturn_bogus.so").string() + ") cannot be loaded: "),
            std::string::npos)
      << msg;
}

}  // namespace
}  // namespace keyturn
