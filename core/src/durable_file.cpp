#include "keyturn/core/durable_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "keyturn/core/error.h"

namespace fs = std::filesystem;

namespace keyturn {
namespace {

// PATH + this + six random characters (+ PATH's extension): a temporary being written.
constexpr const char* kTemporaryInfix = ".tmp.";

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

void writeFileDurablyWith(const std::string& path, const std::function<void(const std::string& tmp)>& fill) {
  std::error_code ec;
  fs::create_directories(parentOf(path), ec);
  if (ec) throw Error(path + ": cannot create its folder: " + ec.message());
  // A temporary of its own beside the target (two processes filling one cache never share one),
  // ending in the target's extension, removed again when anything fails.
  const std::string extension = fs::path(path).extension().string();
  std::string tmp = path + kTemporaryInfix + "XXXXXX" + extension;
  const int fd = ::mkstemps(tmp.data(), static_cast<int>(extension.size()));
  if (fd < 0) throw Error(path + ": cannot open for writing (" + std::strerror(errno) + ")");
  const bool mode_set = ::fchmod(fd, 0644) == 0;  // mkstemp makes it 0600
  const std::string mode_error = std::strerror(errno);
  ::close(fd);
  try {
    if (!mode_set) throw Error(path + ": cannot set its permissions (" + mode_error + ")");
    fill(tmp);
    commitFile(tmp, path);
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
}

void writeFileDurably(const std::string& path, const std::string& bytes) {
  writeFileDurablyWith(path, [&](const std::string& tmp) {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_TRUNC);
    if (fd < 0) throw Error(path + ": cannot open for writing (" + std::strerror(errno) + ")");
    for (std::size_t done = 0; done < bytes.size();) {
      const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const std::string reason = std::strerror(errno);
        ::close(fd);
        throw Error(path + ": write failed (" + reason + ")");
      }
      done += static_cast<std::size_t>(n);
    }
    ::close(fd);  // commitFile syncs it
  });
}

bool isInterruptedWriteTemporary(const std::string& name) {
  const std::string base = fs::path(name).filename().string();
  const auto endsWith = [&base](const std::string& tail) {
    return base.size() > tail.size() && base.compare(base.size() - tail.size(), tail.size(), tail) == 0;
  };
  // The fixed names saveCloud and savePng16 used before they wrote through here.
  if (endsWith(".pcd.tmp") || endsWith(".ply.tmp") || endsWith(".tmp.png")) return true;
  const std::size_t at = base.rfind(kTemporaryInfix);
  if (at == std::string::npos) return false;
  const std::string rest = base.substr(at + std::strlen(kTemporaryInfix));  // XXXXXX, then the extension
  if (rest.size() < 6) return false;
  for (std::size_t i = 0; i < 6; ++i)
    if (!std::isalnum(static_cast<unsigned char>(rest[i]))) return false;
  const std::string extension = rest.substr(6);
  return extension.empty() || (at > extension.size() && base.compare(at - extension.size(), extension.size(), extension) == 0);
}

std::size_t removeInterruptedWriteTemporaries(const std::string& dir, const std::vector<std::string>& skip) {
  std::size_t removed = 0;
  std::error_code walk;
  for (auto it = fs::recursive_directory_iterator(dir, walk); !walk && it != fs::recursive_directory_iterator();
       it.increment(walk)) {
    std::error_code ec;
    if (it->is_directory(ec)) {
      const std::string rel = fs::relative(it->path(), dir, ec).generic_string();
      if (std::find(skip.begin(), skip.end(), rel) != skip.end()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file(ec) && isInterruptedWriteTemporary(it->path().filename().string()) &&
        fs::remove(it->path(), ec))
      ++removed;
  }
  return removed;
}

void appendLineDurably(const std::string& path, const std::string& line) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT, 0644);
  if (fd < 0) throw Error(path + ": cannot open for appending: " + std::strerror(errno));
  const std::string text = line + "\n";
  // One write in the normal case; a signal (Ctrl-C stops a capture) may cut it short, so go on.
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  const int rc = done == text.size() ? ::fsync(fd) : -1;
  const std::string reason = std::strerror(errno);
  ::close(fd);
  if (rc != 0) throw Error(path + ": append failed: " + reason);
}

}  // namespace keyturn
