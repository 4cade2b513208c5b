#pragma once
// One writer per dataset: an exclusive lock (flock(2)) on DATASET/.keyturn-lock, held by every
// dataset::Dataset — capture, simulate, import and the studio's capture — for as long as it is
// open. The kernel drops the lock when its holder exits, however it exits (kill -9 included), so a
// lock file left behind blocks nobody. The file records the holder (pid, command, host, when it
// took the lock) for the message a second writer gets; it is written in place, not through
// durable_file.h, since a file renamed over it would be another file than the one locked.
#include <string>

#include "keyturn/core/error.h"
#include "keyturn/dataset/dataset_layout.h"  // kLockFile

namespace keyturn::dataset {

// Another writer holds the dataset: one line naming the dataset and the holder.
class DatasetBusyError : public Error {
 public:
  using Error::Error;
};

class DatasetLock {
 public:
  // Creates the dataset folder if need be and takes its lock; throws DatasetBusyError while another
  // writer (another process, or another Dataset in this one) holds it, keyturn::Error when the lock
  // file cannot be made.
  explicit DatasetLock(const std::string& root);
  ~DatasetLock();
  DatasetLock(DatasetLock&& other) noexcept;
  DatasetLock& operator=(DatasetLock&& other) noexcept;
  DatasetLock(const DatasetLock&) = delete;
  DatasetLock& operator=(const DatasetLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace keyturn::dataset
