#include "keyturn/core/durable_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "keyturn/core/error.h"

namespace fs = std::filesystem;

namespace keyturn {
namespace {

void syncPath(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw Error(path + ": cannot open to sync: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw Error(path + ": fsync failed: " + std::strerror(errno));
}

std::string parentOf(const std::string& path) {
  const fs::path p = fs::path(path).parent_path();
  return p.empty() ? "." : p.string();
}

}  // namespace

void commitFile(const std::string& tmp, const std::string& path) {
  syncPath(tmp, O_RDONLY);
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw Error(path + ": cannot move the written file into place: " + ec.message());
  syncPath(parentOf(path), O_RDONLY | O_DIRECTORY);
}

void syncDirectory(const std::string& dir) { syncPath(dir, O_RDONLY | O_DIRECTORY); }

void syncFile(const std::string& path) { syncPath(path, O_RDONLY); }

void writeFileDurably(const std::string& path, const std::string& bytes) {
  std::error_code ec;
  fs::create_directories(parentOf(path), ec);
  if (ec) throw Error(path + ": cannot create its folder: " + ec.message());
  // A temporary of its own beside the target (two processes filling one cache never share one),
  // removed again when anything fails.
  std::string tmp = path + ".tmp.XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw Error(path + ": cannot open for writing (" + std::strerror(errno) + ")");
  const auto fail = [&](const std::string& what) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    ::unlink(tmp.c_str());
    throw Error(path + ": " + what + " (" + reason + ")");
  };
  if (::fchmod(fd, 0644) != 0) fail("cannot set its permissions");  // mkstemp makes it 0600
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("write failed");
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) fail("fsync failed");
  ::close(fd);
  try {
    commitFile(tmp, path);
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
}

void appendLineDurably(const std::string& path, const std::string& line) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT, 0644);
  if (fd < 0) throw Error(path + ": cannot open for appending: " + std::strerror(errno));
  const std::string text = line + "\n";
  const ssize_t n = ::write(fd, text.data(), text.size());
  const int rc = ::fsync(fd);
  ::close(fd);
  if (n != static_cast<ssize_t>(text.size()) || rc != 0) throw Error(path + ": append failed: " + std::strerror(errno));
}

}  // namespace keyturn
