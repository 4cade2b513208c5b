#include "keyturn/core/depth_image.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "file_error.h"
#include "png_codec.h"

namespace fs = std::filesystem;

namespace keyturn {
namespace {

using detail::fail;  // "PATH: what", printable

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, fs::exists(path) ? "cannot read" : "no such file");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::uint32_t crc32(const unsigned char* p, std::size_t n) {  // PNG's CRC (ISO 3309), bitwise
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

std::uint32_t bigEndian32(const unsigned char* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}

// The PNG's chunks walked and their checksums checked before it is decoded: libpng prints its own
// complaint about a damaged file on stderr, and our one line already says what is wrong.
void checkPngChunks(const std::string& path, const std::string& bytes) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  std::size_t at = 8;
  while (true) {
    if (at + 12 > bytes.size()) fail(path, "truncated PNG (no end chunk)");
    const std::uint32_t length = bigEndian32(b + at);
    if (length > bytes.size() - at - 12) fail(path, "truncated PNG (a chunk runs past the end of the file)");
    const std::string type = bytes.substr(at + 4, 4);
    for (char c : type)
      if (!std::isalpha(static_cast<unsigned char>(c))) fail(path, "corrupt PNG (a chunk has no valid type)");
    if (crc32(b + at + 4, length + 4) != bigEndian32(b + at + 8 + length))
      fail(path, "corrupt PNG (checksum of chunk " + type + " does not match)");
    at += 12 + length;
    if (type == "IEND") return;
  }
}

// Decodes a PNG whose structure has been checked.
detail::DecodedImage readPng(const std::string& path, const char* what) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(path, "no such file");
  if (fs::is_directory(path, ec)) fail(path, std::string("is a directory, expected a ") + what + " PNG");
  const std::string bytes = readAll(path);
  if (bytes.empty()) fail(path, "empty file (0 bytes)");
  static const char kSignature[] = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 8 || bytes.compare(0, 8, kSignature, 8) != 0) fail(path, "not a PNG file (no PNG signature)");
  checkPngChunks(path, bytes);
  detail::DecodedImage m;
  if (!detail::decodePng(bytes, m) || m.samples.empty()) fail(path, "corrupt PNG (cannot be decoded)");
  return m;
}

// A PNG that is a depth image: 16-bit, one channel.
detail::DecodedImage readDepthPng(const std::string& png) {
  detail::DecodedImage m = readPng(png, "16-bit depth");
  if (m.channels != 1) fail(png, std::to_string(m.channels) + "-channel image; a depth image has one channel");
  if (m.bits != 16)
    fail(png, std::string(m.bits == 8 ? "8-bit" : "non-16-bit") +
                  " image; a depth image is 16-bit (an 8-bit PNG holds no usable depth)");
  return m;
}

std::string withSuffixReplaced(const std::string& path, const std::string& from, const std::string& to) {
  if (path.size() > from.size() && path.compare(path.size() - from.size(), from.size(), from) == 0)
    return path.substr(0, path.size() - from.size()) + to;
  return "";
}

std::vector<std::uint8_t> readMask(const std::string& path, int width, int height, const std::string& depth_png) {
  const detail::DecodedImage m = readPng(path, "mask");
  if (m.channels != 1)
    fail(path, "a mask must be a single-channel 8- or 16-bit image (this one has " + std::to_string(m.channels) +
                   " channels)");
  if (m.width != width || m.height != height)
    fail(path, "mask is " + std::to_string(m.width) + " × " + std::to_string(m.height) + ", its depth image " + depth_png +
                   " is " + std::to_string(width) + " × " + std::to_string(height));
  std::vector<std::uint8_t> out(static_cast<std::size_t>(width) * height);
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u)
      out[static_cast<std::size_t>(v) * width + u] =
          (m.bits == 8 ? m.at8(v, u) != 0 : m.at16(v, u) != 0) ? 1 : 0;
  return out;
}

}  // namespace

std::string companionMask(const std::string& depth_png) {
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"_depthcrop.png", "_maskcrop.png"},
                                 {"_depth.png", "_mask.png"}}) {
    const std::string m = withSuffixReplaced(depth_png, from, to);
    if (!m.empty()) return m;
  }
  return "";
}

std::string companionCropFile(const std::string& depth_png) {
  for (const char* from : {"_depthcrop.png", "_depth.png"}) {
    const std::string l = withSuffixReplaced(depth_png, from, "_loc.txt");
    if (!l.empty()) return l;
  }
  return "";
}

CropOffset readCropFile(const std::string& path) {
  std::string text = readAll(path);
  for (char& c : text)
    if (c == ',') c = ' ';
  std::istringstream in(text);
  long u = 0, v = 0;
  std::string rest;
  if (!(in >> u >> v) || (in >> rest) || u < 1 || v < 1 || u > 100000 || v > 100000)
    fail(path, "expected the crop's top-left pixel as 'u,v' (1-based, as Washington RGB-D's _loc.txt)");
  return {static_cast<int>(u - 1), static_cast<int>(v - 1)};
}

Cloud depthImageToCloud(const std::vector<std::uint16_t>& depth, std::uint32_t width, std::uint32_t height,
                        const DepthIntrinsics& k, double depth_scale, const std::vector<std::uint8_t>& mask,
                        CropOffset crop) {
  Cloud c;
  c.width = width;
  c.height = height;
  c.points.assign(depth.size(), Eigen::Vector3f::Constant(std::nanf("")));
  const bool plain_pinhole = k.distortion.none();  // the pinhole formula as it always was, to the bit
  for (std::uint32_t v = 0; v < height; ++v)
    for (std::uint32_t u = 0; u < width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * width + u;
      if (depth[i] == 0 || (!mask.empty() && !mask[i])) continue;  // no return, or not the object
      const double z = depth[i] * depth_scale;
      if (plain_pinhole) {
        c.points[i] = Eigen::Vector3d((u + crop.u - k.cx) * z / k.fx, (v + crop.v - k.cy) * z / k.fy, z).cast<float>();
        continue;
      }
      const Eigen::Vector2d ray = k.distortion.undistort({(u + crop.u - k.cx) / k.fx, (v + crop.v - k.cy) / k.fy});
      c.points[i] = Eigen::Vector3d(ray.x() * z, ray.y() * z, z).cast<float>();
    }
  return c;
}

bool isDepthImagePath(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png";
}

Cloud loadDepthImage(const std::string& png, const DepthImageOptions& o) {
  const detail::DecodedImage m = readDepthPng(png);
  if (!o.intrinsics)
    throw MissingIntrinsicsError(png + ": a depth image needs the camera's intrinsics (a camera file, or fx, fy, cx and cy)");
  const auto w = static_cast<std::uint32_t>(m.width), h = static_cast<std::uint32_t>(m.height);
  std::vector<std::uint16_t> depth(static_cast<std::size_t>(w) * h);
  for (int v = 0; v < m.height; ++v)
    for (int u = 0; u < m.width; ++u) depth[static_cast<std::size_t>(v) * w + u] = m.at16(v, u);

  std::error_code ec;
  std::string mask_file = o.mask;
  if (mask_file.empty() && !companionMask(png).empty() && fs::exists(companionMask(png), ec)) mask_file = companionMask(png);
  const std::vector<std::uint8_t> mask =
      mask_file.empty() ? std::vector<std::uint8_t>{} : readMask(mask_file, m.width, m.height, png);
  CropOffset crop;
  if (o.crop) crop = *o.crop;
  else if (!companionCropFile(png).empty() && fs::exists(companionCropFile(png), ec)) crop = readCropFile(companionCropFile(png));
  return depthImageToCloud(depth, w, h, *o.intrinsics, o.depth_scale, mask, crop);
}

void checkDepthImage(const std::string& png) { readDepthPng(png); }

std::vector<std::uint16_t> loadPng16(const std::string& path, std::uint32_t width, std::uint32_t height) {
  const detail::DecodedImage m = readPng(path, "16-bit");
  if (m.bits != 16 || m.channels != 1) fail(path, "not a 16-bit grey PNG");
  if (static_cast<std::uint32_t>(m.width) != width || static_cast<std::uint32_t>(m.height) != height)
    fail(path, std::to_string(m.width) + " × " + std::to_string(m.height) + " pixels, expected " + std::to_string(width) +
                   " × " + std::to_string(height));
  std::vector<std::uint16_t> out(static_cast<std::size_t>(width) * height);
  std::copy_n(reinterpret_cast<const std::uint16_t*>(m.samples.data()), out.size(), out.begin());
  return out;
}

void savePng16(const std::string& path, const std::vector<std::uint16_t>& img, std::uint32_t width,
               std::uint32_t height) {
  if (img.size() != static_cast<std::size_t>(width) * height || img.empty())
    fail(path, "image data does not match its size");
  // The encoder is chosen from the extension, which the temporary's name keeps.
  writeFileDurablyWith(path, [&](const std::string& tmp) {
    std::string why;
    if (!detail::writePng16(tmp, img.data(), static_cast<int>(width), static_cast<int>(height), why)) fail(path, why);
  });
}

}  // namespace keyturn
