// The plugin "png": OpenCV's imgcodecs behind the two calls of src/png_codec.h.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstring>

#include "../src/png_codec.h"
#include "keyturn/core/plugin.h"

using keyturn::detail::DecodedImage;

KEYTURN_PLUGIN_EXPORT bool keyturn_png_decode(const std::string& bytes, DecodedImage& image) {
  cv::Mat m;
  try {
    m = cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data())),
                     cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {
    return false;
  }
  if (m.empty() || (m.depth() != CV_8U && m.depth() != CV_16U)) return false;
  if (!m.isContinuous()) m = m.clone();
  image.width = m.cols;
  image.height = m.rows;
  image.channels = m.channels();
  image.bits = m.depth() == CV_8U ? 8 : 16;
  image.samples.resize(m.total() * m.elemSize());
  std::memcpy(image.samples.data(), m.data, image.samples.size());
  return true;
}

KEYTURN_PLUGIN_EXPORT bool keyturn_png_write16(const std::string& path, const std::uint16_t* samples, int width,
                                               int height, std::string& error) {
  const cv::Mat m(height, width, CV_16UC1, const_cast<std::uint16_t*>(samples));
  try {
    if (cv::imwrite(path, m)) return true;
    error = "could not write PNG";
  } catch (const cv::Exception& e) {
    error = std::string("PNG encoder failed: ") + e.what();
  }
  return false;
}
