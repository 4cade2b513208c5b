#pragma once
// The error of a file keyturn reads, for core's readers (clouds, PLY, depth images, camera files):
// keyturn::Error "PATH: what", one line of valid UTF-8 whatever bytes of the file it quotes (a
// header line, a token: string_format.h's printableText). Internal to keyturn_core.
#include <string>

namespace keyturn::detail {

[[noreturn]] void fail(const std::string& path, const std::string& what);

}  // namespace keyturn::detail
