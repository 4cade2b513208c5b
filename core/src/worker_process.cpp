#include "keyturn/core/worker_process.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

#include "keyturn/core/error.h"

namespace keyturn {

std::vector<float> inWorkerProcess(const std::function<std::vector<float>()>& work, const std::string& name,
                                   const std::string& crashed, const std::string& where) {
  int fds[2];
  if (::pipe(fds) != 0) throw Error(name + ": cannot create a pipe");
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error(name + ": cannot fork");
  }
  if (child == 0) {
    ::close(fds[0]);
    // The routine's own abort text would reach the user's terminal; the parent reports instead.
    const int null_fd = ::open("/dev/null", O_WRONLY);
    if (null_fd >= 0) ::dup2(null_fd, STDERR_FILENO);
    std::vector<float> h;
    try {
      h = work();
    } catch (...) {
      ::_exit(4);
    }
    const std::uint32_t n = static_cast<std::uint32_t>(h.size());
    bool ok = ::write(fds[1], &n, sizeof n) == sizeof n;
    const auto bytes = static_cast<ssize_t>(h.size() * sizeof(float));
    if (ok && n) ok = ::write(fds[1], h.data(), static_cast<std::size_t>(bytes)) == bytes;
    ::_exit(ok ? 0 : 3);
  }
  ::close(fds[1]);
  std::vector<char> data;
  char buf[4096];
  for (ssize_t got; (got = ::read(fds[0], buf, sizeof buf)) != 0;) {
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) break;
    data.insert(data.end(), buf, buf + got);
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status))
    throw Error(crashed + " (signal " + std::to_string(WTERMSIG(status)) + ", " + where + ")");
  std::uint32_t n = 0;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || data.size() < sizeof n)
    throw Error(name + ": the worker process failed");
  std::memcpy(&n, data.data(), sizeof n);
  if (data.size() != sizeof n + n * sizeof(float)) throw Error(name + ": short result from the worker process");
  std::vector<float> h(n);
  if (n) std::memcpy(h.data(), data.data() + sizeof n, n * sizeof(float));
  return h;
}

}  // namespace keyturn
