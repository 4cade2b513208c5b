#include "pbm_image.h"

#include <cctype>
#include <fstream>
#include <iterator>

#include "keyturn/core/error.h"

// By hand, not OpenCV's Netpbm decoder: OpenCV 4.6 prints its own line on stderr for a truncated
// file (imread catches its exception and writes to std::cerr), and a bad mask must be one line.
namespace keyturn::dataset {
namespace {

constexpr std::uint32_t kMaxSide = 1 << 14;

// The next header token (or ascii pixel) after whitespace and # comments; "" at the end.
std::string token(const std::string& s, std::size_t& at, bool single_digit = false) {
  while (at < s.size()) {
    if (s[at] == '#') {
      while (at < s.size() && s[at] != '\n') ++at;
    } else if (std::isspace(static_cast<unsigned char>(s[at]))) {
      ++at;
    } else {
      break;
    }
  }
  const std::size_t from = at;
  while (at < s.size() && !std::isspace(static_cast<unsigned char>(s[at])) && s[at] != '#' &&
         (!single_digit || at == from))
    ++at;
  return s.substr(from, at - from);
}

std::uint32_t side(const std::string& path, const std::string& t) {
  if (t.empty() || t.size() > 6 || t.find_first_not_of("0123456789") != std::string::npos || std::stoul(t) == 0 ||
      std::stoul(t) > kMaxSide)
    throw Error(path + ": not a PBM bitmap (bad width or height '" + t + "')");
  return static_cast<std::uint32_t>(std::stoul(t));
}

}  // namespace

Bitmap readPbm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open");
  const std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t at = 0;
  const std::string magic = token(s, at);
  if (magic != "P4" && magic != "P1") throw Error(path + ": not a PBM bitmap (no P4 or P1 magic)");
  Bitmap b;
  b.width = side(path, token(s, at));
  b.height = side(path, token(s, at));
  b.black.resize(std::size_t(b.width) * b.height);
  if (magic == "P4") {
    ++at;  // the single whitespace before the bits
    const std::size_t row = (b.width + 7) / 8;
    if (s.size() < at + row * b.height) throw Error(path + ": truncated PBM bitmap");
    for (std::uint32_t v = 0; v < b.height; ++v)
      for (std::uint32_t u = 0; u < b.width; ++u)
        b.black[std::size_t(v) * b.width + u] = (static_cast<unsigned char>(s[at + v * row + u / 8]) >> (7 - u % 8)) & 1;
  } else {
    for (auto& px : b.black) {
      const std::string t = token(s, at, true);
      if (t != "0" && t != "1") throw Error(path + ": " + (t.empty() ? "truncated PBM bitmap" : "PBM pixel '" + t + "' is not 0 or 1"));
      px = t == "1";
    }
  }
  return b;
}

}  // namespace keyturn::dataset
