#include "png_codec.h"

#include "keyturn/core/plugin.h"

namespace keyturn::detail {

bool decodePng(const std::string& bytes, DecodedImage& image) {
  static auto* decode = pluginFunction<DecodePngFunction>("png", "keyturn_png_decode");
  return decode(bytes, image);
}

bool writePng16(const std::string& path, const std::uint16_t* samples, int width, int height, std::string& error) {
  static auto* write = pluginFunction<WritePng16Function>("png", "keyturn_png_write16");
  return write(path, samples, width, height, error);
}

}  // namespace keyturn::detail
