#pragma once
// PNG decoding and 16-bit PNG writing through OpenCV's imgcodecs, which lives in the plugin
// "png" (plugins/png_codec_opencv.cpp): imgcodecs brings GDAL and ~140 shared libraries, whose
// loading took 0.10-0.15 s of every process's start, PNG or not. Internal to keyturn_core.
#include <cstdint>
#include <string>
#include <vector>

namespace keyturn::detail {

struct DecodedImage {
  int width = 0, height = 0;
  int channels = 0;  // 1 grey, 3 colour, 4 with alpha
  int bits = 0;      // 8 or 16 bits a sample
  std::vector<std::uint8_t> samples;  // row-major, channels interleaved; 16-bit samples in host order

  std::uint16_t at16(int row, int column) const {
    return reinterpret_cast<const std::uint16_t*>(samples.data())[(static_cast<std::size_t>(row) * width + column) * channels];
  }
  std::uint8_t at8(int row, int column) const {
    return samples[(static_cast<std::size_t>(row) * width + column) * channels];
  }
};

// False when the bytes do not decode. Throws keyturn::Error when the plugin cannot be loaded.
bool decodePng(const std::string& bytes, DecodedImage& image);

// Writes a 16-bit grey PNG at `path` (which ends in .png); false with the reason in `error`.
bool writePng16(const std::string& path, const std::uint16_t* samples, int width, int height, std::string& error);

// The plugin's entry points.
using DecodePngFunction = bool(const std::string& bytes, DecodedImage& image);
using WritePng16Function = bool(const std::string& path, const std::uint16_t* samples, int width, int height,
                                std::string& error);

}  // namespace keyturn::detail
