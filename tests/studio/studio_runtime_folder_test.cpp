// The studio's runtime folder goes with its studio, also when the studio is killed: the next studio
// to start removes the folders no running studio holds (issue 52: keyturn-studio-PID folders piled up
// in /tmp after kill -9).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "keyturn/dataset/dataset_lock.h"
#include "keyturn/studio/studio_runtime_folder.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;

namespace keyturn {
namespace {

// A child process that takes FOLDER's lock as a running studio does, and says so through a pipe.
pid_t studioHolding(const fs::path& folder) {
  int ready[2];
  if (::pipe(ready) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(ready[0]);
    dataset::DatasetLock lock(folder.string());
    test::writeText(folder / "world.json", "{}\n");
    const char byte = 1;
    if (::write(ready[1], &byte, 1) != 1) ::_exit(2);
    for (;;) ::pause();
  }
  ::close(ready[1]);
  char byte = 0;
  const bool ok = ::read(ready[0], &byte, 1) == 1;
  ::close(ready[0]);
  return ok ? pid : -1;
}

TEST(StudioRuntimeFolder, AStudioKilledWithSigkillLeavesAFolderTheNextStudioRemoves) {
  test::ScratchFolder temp("studio_runtime_folder");
  const fs::path held = temp.made() / "keyturn-studio-101";
  const pid_t studio = studioHolding(held);
  ASSERT_GT(studio, 0);
  // An older studio's folder (no lock file at all), and one whose lock nobody holds.
  test::writeText(temp.path / "keyturn-studio-102" / "world.json", "{}\n");
  test::writeText(temp.path / "keyturn-studio-103" / ".keyturn-lock", "{\"pid\": 103}\n");
  test::writeText(temp.path / "keyturn_other_thing" / "kept.txt", "not the studio's\n");

  EXPECT_EQ(studio::removeAbandonedStudioFolders(temp.path.string()), 2);
  EXPECT_TRUE(fs::exists(held / "world.json")) << "a running studio's folder was removed";
  EXPECT_FALSE(fs::exists(temp.path / "keyturn-studio-102"));
  EXPECT_FALSE(fs::exists(temp.path / "keyturn-studio-103"));
  EXPECT_TRUE(fs::exists(temp.path / "keyturn_other_thing" / "kept.txt"));

  ::kill(studio, SIGKILL);
  int status = 0;
  ASSERT_EQ(::waitpid(studio, &status, 0), studio);
  ASSERT_TRUE(fs::exists(held)) << "kill -9 cannot remove the folder: the next studio must";
  EXPECT_EQ(studio::removeAbandonedStudioFolders(temp.path.string()), 1);
  EXPECT_FALSE(fs::exists(held));
  EXPECT_EQ(std::distance(fs::directory_iterator(temp.path), fs::directory_iterator()), 1);  // keyturn_other_thing
}

TEST(StudioRuntimeFolder, IsTheStudiosOwnWhileItRunsAndGoneAfter) {
  test::ScratchFolder temp("studio_runtime_folder_own");
  // The studio makes its folder in the temporary folder: this test's scratch, for the test's length
  // (the scratch's parent is the temporary folder the test started with).
  ::setenv("TMPDIR", temp.made().c_str(), 1);
  test::writeText(temp.path / "keyturn-studio-104" / "world.json", "{}\n");  // a killed studio's
  fs::path path;
  {
    studio::StudioRuntimeFolder folder;
    path = folder.path();
    EXPECT_EQ(path, temp.path / ("keyturn-studio-" + std::to_string(::getpid())));
    EXPECT_TRUE(fs::is_directory(path));
    EXPECT_FALSE(fs::exists(temp.path / "keyturn-studio-104")) << "starting did not sweep";
    EXPECT_EQ(studio::removeAbandonedStudioFolders(temp.path.string()), 0) << "its own folder was swept";
    EXPECT_TRUE(fs::is_directory(path));
  }
  EXPECT_FALSE(fs::exists(path));
  ::setenv("TMPDIR", temp.path.parent_path().c_str(), 1);
}

}  // namespace
}  // namespace keyturn
