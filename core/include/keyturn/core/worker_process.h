#pragma once
// Running code that may crash the process (a third-party routine with a known
// abort no input check predicts) in a forked child: its result comes back
// through a pipe, and a crash becomes a keyturn::Error instead of taking the
// caller down. The child's stderr goes to /dev/null (the parent reports).
#include <functional>
#include <string>
#include <vector>

namespace keyturn {

// name: in the messages of a failed pipe, fork or worker ("NAME: cannot fork").
// crashed: the message of a crash, completed with " (signal N, where)".
std::vector<float> inWorkerProcess(const std::function<std::vector<float>()>& work, const std::string& name,
                                   const std::string& crashed, const std::string& where);

}  // namespace keyturn
