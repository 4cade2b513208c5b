#include "worker_protocol.h"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>

namespace keyturn::worker {

bool readAll(int fd, void* data, std::size_t size) {
  auto* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t got = ::read(fd, p, size);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    p += got;
    size -= static_cast<std::size_t>(got);
  }
  return true;
}

bool writeAll(int fd, const void* data, std::size_t size) {
  const auto* p = static_cast<const char*>(data);
  while (size > 0) {
    // send's MSG_NOSIGNAL: a worker that died is an error here, not a SIGPIPE for the process.
    const ssize_t put = ::send(fd, p, size, MSG_NOSIGNAL);
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0) return false;
    p += put;
    size -= static_cast<std::size_t>(put);
  }
  return true;
}

}  // namespace keyturn::worker
