#include "keyturn/core/string_format.h"

#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "keyturn/core/error.h"
#include "file_error.h"

namespace keyturn {

void appendFormat(std::string& out, const char* format, ...) {
  va_list args;
  va_start(args, format);
  va_list again;
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  if (n > 0) {
    const std::size_t at = out.size();
    out.resize(at + static_cast<std::size_t>(n) + 1);
    std::vsnprintf(&out[at], static_cast<std::size_t>(n) + 1, format, again);
    out.resize(at + static_cast<std::size_t>(n));
  }
  va_end(again);
}

std::string printableText(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  const auto* b = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = b[i];
    const std::size_t len = c < 0x80 ? 1 : (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
    bool ok = len == 1 ? c >= 0x20 && c != 0x7F : len > 0 && i + len <= n;
    if (ok && len > 1) {
      std::uint32_t code = c & (0x7Fu >> len);
      for (std::size_t k = 1; ok && k < len; ++k) {
        ok = (b[i + k] & 0xC0) == 0x80;
        code = code << 6 | (b[i + k] & 0x3Fu);
      }
      static const std::uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};  // shorter forms are overlong
      // Not surrogates, past U+10FFFF or C1 controls (U+0080 … U+009F)
      ok = ok && code >= least[len] && code <= 0x10FFFF && (code < 0xD800 || code > 0xDFFF) && code >= 0xA0;
    }
    if (ok) {
      out.append(text, i, len);
      i += len;
    } else {
      appendFormat(out, "\\x%02x", c);
      ++i;
    }
  }
  return out;
}

void detail::fail(const std::string& path, const std::string& what) { throw Error(printableText(path + ": " + what)); }

std::vector<double> parseNumberList(const std::string& text, const std::string& what) {
  std::vector<double> out;
  std::stringstream ss(text);
  for (std::string tok; std::getline(ss, tok, ',');) {
    try {
      std::size_t used = 0;
      out.push_back(std::stod(tok, &used));
      if (used != tok.size()) throw std::invalid_argument(tok);
    } catch (const std::exception&) {
      throw Error(what + ": '" + tok + "' is not a number");
    }
  }
  if (out.empty()) throw Error(what + ": no number given");
  return out;
}

}  // namespace keyturn
