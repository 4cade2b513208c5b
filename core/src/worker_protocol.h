#pragma once
// The keyturn-worker protocol (worker_process.h), one request and one reply at a time over the
// worker's stdin/stdout (one socket):
//   request: u32 job length, the job's name, u32 n, n floats
//   reply:   u8 status (0 done, 1 failed), u32 n, then n floats (done) or n bytes of message (failed)
// All in this machine's byte order (the worker is the caller's own build). Internal to keyturn_core.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace keyturn::worker {

// Whole reads and writes, resumed after EINTR and short counts. read: false at end of stream
// (or a failure) before `size` bytes; write: false when the other side is gone (no SIGPIPE).
bool readAll(int fd, void* data, std::size_t size);
bool writeAll(int fd, const void* data, std::size_t size);

inline constexpr std::uint8_t kDone = 0;
inline constexpr std::uint8_t kFailed = 1;

}  // namespace keyturn::worker
