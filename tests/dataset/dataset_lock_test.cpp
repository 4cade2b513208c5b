// One writer per dataset (issue 52, item 17): a second Dataset opened for writing while one holds
// the dataset — in this process or another — is refused in one line naming the dataset and the
// holder; the lock goes with its holder, however it ends (kill -9 included); verify and the removal
// of an empty dataset take the lock file for the dataset's own.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <string>

#include "keyturn/dataset/dataset.h"
#include "keyturn/dataset/dataset_lock.h"
#include "support/scratch_path.h"

namespace fs = std::filesystem;
using namespace keyturn;

namespace {

// The message of the DatasetBusyError that opening `root` for writing throws ("" when it opens).
std::string refusal(const fs::path& root) {
  try {
    dataset::Dataset second(root.string());
  } catch (const dataset::DatasetBusyError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(DatasetLock, ASecondWriterInTheSameProcessIsRefusedNamingTheDatasetAndTheHolder) {
  const keyturn::test::ScratchFolder scratch("lock_same");
  const fs::path& root = scratch.path;
  {
    dataset::Dataset first(root.string());
    const std::string why = refusal(root);
    EXPECT_EQ(why.rfind(root.string() + ": already being written by pid " + std::to_string(::getpid()) + " (", 0), 0u) << why;
    EXPECT_NE(why.find("keyturn_dataset_tests"), std::string::npos) << why;  // the holder's command
    EXPECT_NE(why.find(" since 20"), std::string::npos) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;
  }
  EXPECT_EQ(refusal(root), "");  // released with its Dataset
  fs::remove_all(root);
}

TEST(DatasetLock, AWriterKilledWithSigkillLeavesTheLockFileButNotTheLock) {
  const keyturn::test::ScratchFolder scratch("lock_killed");
  const fs::path& root = scratch.path;
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    dataset::Dataset held(root.string());
    (void)!::write(ready[1], "x", 1);
    ::pause();
    ::_exit(0);
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);  // the child holds the dataset
  const std::string why = refusal(root);
  EXPECT_EQ(why.rfind(root.string() + ": already being written by pid " + std::to_string(child) + " (", 0), 0u) << why;
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
  ::close(ready[0]);
  ::close(ready[1]);
  EXPECT_TRUE(fs::exists(root / dataset::kLockFile));
  EXPECT_EQ(refusal(root), "");  // the kernel released it: no stale lock to clear
  fs::remove_all(root);
}

TEST(DatasetLock, VerifyTakesTheLockFileForTheDatasetsOwn) {
  const keyturn::test::ScratchFolder scratch("lock_verify");
  const fs::path& root = scratch.path;
  { dataset::Dataset ds(root.string()); }
  ASSERT_TRUE(fs::exists(root / dataset::kLockFile));
  EXPECT_TRUE(dataset::Dataset::verify(root.string()).orphans.empty());
  // An empty dataset is removed whole, its lock file too, unless another writer holds it.
  {
    dataset::Dataset holder(root.string());
    dataset::removeDatasetWithoutViews(root.string());
    EXPECT_TRUE(fs::exists(root / "manifest.csv"));
  }
  dataset::removeDatasetWithoutViews(root.string());
  EXPECT_FALSE(fs::exists(root));
}
