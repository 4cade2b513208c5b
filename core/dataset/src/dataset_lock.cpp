#include "keyturn/dataset/dataset_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <utility>

#include "keyturn/core/string_format.h"
#include "utc_time.h"

namespace keyturn::dataset {


namespace {

// This process's command line, its arguments separated by spaces.
std::string commandLine() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!text.empty() && text.back() == '\0') text.pop_back();
  for (char& c : text)
    if (c == '\0') c = ' ';
  return text;
}

std::string hostName() {
  char name[256] = {};
  return ::gethostname(name, sizeof name - 1) == 0 ? name : "unknown host";
}

// Who holds the lock, as its file records it: "pid 1234 (keyturn capture …) on HOST since TIME".
std::string holder(int fd) {
  std::string text(4096, '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object() || !j.contains("pid")) return "another process (it has not yet said which)";
  return "pid " + j["pid"].dump() + " (" + printableText(j.value("command", "?")) + ") on " +
         printableText(j.value("host", "?")) + " since " + printableText(j.value("started", "?"));
}

}  // namespace

DatasetLock::DatasetLock(const std::string& root) {
  std::error_code ec;
  std::filesystem::create_directories(root, ec);
  if (ec) throw Error(root + ": cannot create dataset folder: " + ec.message());
  const std::string path = root + "/" + kLockFile;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error(path + ": cannot open the dataset's lock file: " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    const std::string who = err == EWOULDBLOCK ? holder(fd_) : "";
    ::close(fd_);
    fd_ = -1;
    if (err != EWOULDBLOCK) throw Error(path + ": cannot lock the dataset: " + std::strerror(err));
    throw DatasetBusyError(root + ": already being written by " + who + "; one writer at a time");
  }
  const nlohmann::json j = {{"pid", ::getpid()}, {"command", commandLine()}, {"host", hostName()}, {"started", isoNow()}};
  const std::string text = j.dump() + "\n";
  if (::ftruncate(fd_, 0) == 0) {
    const ssize_t written = ::pwrite(fd_, text.data(), text.size(), 0);
    (void)written;  // best effort: the lock holds whether or not its holder could be recorded
  }
}

DatasetLock::~DatasetLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the last descriptor releases the lock
}

DatasetLock::DatasetLock(DatasetLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

DatasetLock& DatasetLock::operator=(DatasetLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

}  // namespace keyturn::dataset
