#include "keyturn/core/ply_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "keyturn/core/checked_integer.h"
#include "keyturn/core/error.h"
#include "file_error.h"

namespace keyturn {

namespace {

constexpr int kMaxHeaderLines = 4096;
constexpr std::size_t kMaxListLength = 1 << 20;

using detail::fail;  // "PATH: what", printable

// Byte size of a PLY scalar type (both the old and the sized names); 0 if unknown.
std::size_t typeSize(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

double decode(const unsigned char* p, const std::string& t, bool swap) {
  unsigned char b[8];
  const std::size_t n = typeSize(t);
  std::memcpy(b, p, n);
  if (swap) std::reverse(b, b + n);
  auto as = [&](auto v) {
    std::memcpy(&v, b, sizeof v);
    return static_cast<double>(v);
  };
  if (t == "char" || t == "int8") return as(std::int8_t{});
  if (t == "uchar" || t == "uint8") return as(std::uint8_t{});
  if (t == "short" || t == "int16") return as(std::int16_t{});
  if (t == "ushort" || t == "uint16") return as(std::uint16_t{});
  if (t == "int" || t == "int32") return as(std::int32_t{});
  if (t == "uint" || t == "uint32") return as(std::uint32_t{});
  if (t == "float" || t == "float32") return as(float{});
  return as(double{});
}

bool isIntegerType(const std::string& t) {
  return typeSize(t) != 0 && t != "float" && t != "float32" && t != "double" && t != "float64";
}

// Reads the payload: a cursor over the bytes after end_header.
class Payload {
 public:
  Payload(const std::string& path, const std::string& bytes, std::size_t start, const std::string& format)
      : path_(path), bytes_(bytes), pos_(start), ascii_(format == "ascii"),
        swap_(format == "binary_big_endian") {}

  double next(const std::string& type, const std::string& what) {
    if (ascii_) return nextText(type, what);
    const std::size_t n = typeSize(type);
    if (bytes_.size() - pos_ < n) fail(path_, "truncated PLY: the data ends inside " + what);
    const double v = decode(reinterpret_cast<const unsigned char*>(bytes_.data()) + pos_, type, swap_);
    pos_ += n;
    return v;
  }

 private:
  double nextText(const std::string& type, const std::string& what) {
    while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
    if (pos_ == bytes_.size()) fail(path_, "truncated PLY: the data ends before " + what);
    const std::size_t end = std::min(bytes_.size(), pos_ + 64);
    std::size_t stop = pos_;
    while (stop < end && !std::isspace(static_cast<unsigned char>(bytes_[stop]))) ++stop;
    const std::string token = bytes_.substr(pos_, stop - pos_);
    if (stop == end && end < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[end])))
      fail(path_, "a number longer than 64 characters ('" + token.substr(0, 20) + "...') in " + what);
    pos_ = stop;
    char* tail = nullptr;
    const double v = std::strtod(token.c_str(), &tail);
    // The whole token must be the number: a NUL byte would end it early for strtod.
    if (token.empty() || tail != token.c_str() + token.size())
      fail(path_, "bad number '" + token.substr(0, 20) + "' in " + what);
    if (isIntegerType(type) && v != std::floor(v)) fail(path_, "non-integer '" + token.substr(0, 20) + "' in " + what);
    return v;
  }

  const std::string& path_;
  const std::string& bytes_;
  std::size_t pos_;
  bool ascii_;
  bool swap_;
};

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open file");
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Parses the header; returns the offset of the first payload byte.
std::size_t parseHeader(const std::string& path, const std::string& bytes, PlyData& ply) {
  std::size_t pos = 0;
  auto nextLine = [&](std::string& line) {
    if (pos >= bytes.size()) return false;
    std::size_t nl = bytes.find('\n', pos);
    if (nl == std::string::npos) nl = bytes.size();
    line = bytes.substr(pos, std::min<std::size_t>(nl - pos, 1024));
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = nl + 1;
    return true;
  };
  std::string line;
  if (!nextLine(line) || line != "ply") fail(path, "not a PLY file (it must start with 'ply')");
  for (int n = 1; n < kMaxHeaderLines && nextLine(line); ++n) {
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    const std::string where = "header line " + std::to_string(n + 1) + ": ";
    if (key == "format") {
      std::string version;
      ls >> ply.format >> version;
      if (ply.format != "ascii" && ply.format != "binary_little_endian" && ply.format != "binary_big_endian")
        fail(path, where + "unknown format '" + ply.format.substr(0, 30) + "'");
    } else if (key == "element") {
      PlyElement e;
      long long count = -1;
      if (!(ls >> e.name >> count) || count < 0) fail(path, where + "an element needs a name and a count >= 0");
      if (static_cast<unsigned long long>(count) > bytes.size())  // every item takes at least one byte
        fail(path, where + "element '" + e.name.substr(0, 30) + "' promises " + std::to_string(count) +
                       " items but the file has only " + std::to_string(bytes.size()) + " bytes");
      e.count = static_cast<std::size_t>(count);
      ply.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (ply.elements.empty()) fail(path, where + "a property before any element");
      PlyProperty p;
      std::string type;
      ls >> type;
      if (type == "list") {
        p.is_list = true;
        ls >> p.count_type >> p.value_type;
        if (!isIntegerType(p.count_type)) fail(path, where + "a list count must be an integer type");
      } else {
        p.value_type = type;
      }
      if (typeSize(p.value_type) == 0) fail(path, where + "unknown property type '" + p.value_type.substr(0, 30) + "'");
      if (!(ls >> p.name)) fail(path, where + "a property needs a name");
      ply.elements.back().properties.push_back(std::move(p));
    } else if (key == "obj_info") {
      std::string rest;
      std::getline(ls >> std::ws, rest);
      ply.obj_info.push_back(rest);
    } else if (key == "comment" || key.empty()) {
    } else if (key == "end_header") {
      if (ply.format.empty()) fail(path, "PLY header has no format line");
      return pos;
    } else {
      fail(path, where + "unknown keyword '" + key.substr(0, 30) + "'");
    }
  }
  fail(path, "not a valid PLY file (no end_header)");
}

}  // namespace

const PlyProperty* PlyElement::find(const std::string& n) const {
  for (const auto& p : properties)
    if (p.name == n) return &p;
  return nullptr;
}

const PlyElement* PlyData::find(const std::string& n) const {
  for (const auto& e : elements)
    if (e.name == n) return &e;
  return nullptr;
}

PlyData readPly(const std::string& path) {
  const std::string bytes = readAll(path);
  PlyData ply;
  const std::size_t start = parseHeader(path, bytes, ply);
  // A binary item is at least the sum of its scalar sizes (lists: their count);
  // check the whole promise before allocating anything.
  const bool ascii = ply.format == "ascii";
  std::uint64_t min_bytes = 0;
  for (const auto& e : ply.elements) {
    std::uint64_t per_item = 0;
    for (const auto& p : e.properties) per_item += ascii ? 2 : typeSize(p.is_list ? p.count_type : p.value_type);
    if (per_item != 0 && e.count > (bytes.size() - start) / per_item + 1)
      fail(path, "truncated PLY: element '" + e.name.substr(0, 30) + "' needs at least " +
                     std::to_string(e.count * per_item) + " bytes but the data has " +
                     std::to_string(bytes.size() - start));
    min_bytes += e.count * per_item;
  }
  if (min_bytes > bytes.size() - start + 1)
    fail(path, "truncated PLY: the header needs at least " + std::to_string(min_bytes) +
                   " bytes of data but the file has " + std::to_string(bytes.size() - start));

  Payload in(path, bytes, start, ply.format);
  for (auto& e : ply.elements) {
    for (auto& p : e.properties) {
      if (p.is_list) p.offsets.reserve(e.count + 1), p.offsets.push_back(0);
      else p.values.reserve(e.count);
    }
    for (std::size_t i = 0; i < e.count; ++i) {
      for (auto& p : e.properties) {
        const std::string what = "element '" + e.name.substr(0, 30) + "' item " + std::to_string(i);
        if (!p.is_list) {
          p.values.push_back(in.next(p.value_type, what));
          continue;
        }
        const double n = in.next(p.count_type, what);
        const auto len = integerIn<std::size_t>(n, 0, kMaxListLength);
        if (!len) fail(path, "bad list length " + numberText(n) + " in " + what);
        for (std::size_t k = 0; k < *len; ++k) p.values.push_back(in.next(p.value_type, what));
        p.offsets.push_back(p.values.size());
      }
    }
  }
  return ply;
}

}  // namespace keyturn
