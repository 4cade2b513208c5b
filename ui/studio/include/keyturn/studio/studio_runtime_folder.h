#pragma once
// The studio's private runtime folder, TMPDIR/keyturn-studio-PID: the simulated rig's files (the
// world the simulated camera and turntable share, the camera's configuration, its unplug flag).
// A studio removes it when it closes; one that is killed (kill -9, a crash) cannot. So the folder is
// held for the studio's lifetime by the lock every dataset writer takes (dataset::DatasetLock, an
// flock the kernel drops however its holder exits), and each studio that starts removes the
// keyturn-studio-* folders no running studio holds.
#include <optional>
#include <string>

#include "keyturn/dataset/dataset_lock.h"

namespace keyturn::studio {

class StudioRuntimeFolder {
 public:
  // Makes and locks TEMP/keyturn-studio-PID (TEMP: std::filesystem::temp_directory_path()), then
  // removes the abandoned ones beside it. Throws keyturn::Error when the folder cannot be made.
  StudioRuntimeFolder();
  ~StudioRuntimeFolder();
  StudioRuntimeFolder(const StudioRuntimeFolder&) = delete;
  StudioRuntimeFolder& operator=(const StudioRuntimeFolder&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::optional<dataset::DatasetLock> lock_;
};

// Removes the keyturn-studio-* folders in `temp` whose lock no process holds (their studio is gone,
// or predates the lock); returns how many it removed. A folder some studio holds is left alone.
int removeAbandonedStudioFolders(const std::string& temp);

}  // namespace keyturn::studio
