#include "sim_stream.h"

#include <cmath>
#include <cstring>

#include <PS1080.h>  // XN_STREAM_PROPERTY_EMITTER_DCMOS_DISTANCE

#include "sim_device.h"

namespace keyturn::sim::openni2 {

SimStream::SimStream(SimDevice& device, OniSensorType type) : device_(device), type_(type) {
  mode_ = device.sensor(type)->pSupportedVideoModes[0];
}

OniStatus SimStream::start() {
  device_.streamStarted(this);
  return ONI_STATUS_OK;
}

void SimStream::stop() { device_.streamStopped(this); }

int SimStream::bytesPerPixel() const { return type_ == ONI_SENSOR_COLOR ? 3 : 2; }

int SimStream::getRequiredFrameSize() {
  std::lock_guard<std::mutex> lock(mutex_);
  return mode_.resolutionX * mode_.resolutionY * bytesPerPixel();
}

OniBool SimStream::isPropertySupported(int id) {
  switch (id) {
    case ONI_STREAM_PROPERTY_VIDEO_MODE:
    case ONI_STREAM_PROPERTY_HORIZONTAL_FOV:
    case ONI_STREAM_PROPERTY_VERTICAL_FOV:
    case ONI_STREAM_PROPERTY_MIRRORING:
    case ONI_STREAM_PROPERTY_CROPPING:
    case ONI_STREAM_PROPERTY_STRIDE:
      return TRUE;
    case ONI_STREAM_PROPERTY_MAX_VALUE:
    case ONI_STREAM_PROPERTY_MIN_VALUE:
    case XN_STREAM_PROPERTY_EMITTER_DCMOS_DISTANCE:
      return type_ == ONI_SENSOR_DEPTH;
    default:
      return FALSE;
  }
}

namespace {
template <typename T>
OniStatus putValue(void* data, int* size, const T& value) {
  if (!data || !size || *size < static_cast<int>(sizeof(T))) return ONI_STATUS_BAD_PARAMETER;
  std::memcpy(data, &value, sizeof(T));
  *size = sizeof(T);
  return ONI_STATUS_OK;
}
}  // namespace

OniStatus SimStream::getProperty(int id, void* data, int* size) {
  const Intrinsics& k = device_.intrinsics();
  std::lock_guard<std::mutex> lock(mutex_);
  switch (id) {
    case ONI_STREAM_PROPERTY_VIDEO_MODE:
      return putValue(data, size, mode_);
    case ONI_STREAM_PROPERTY_HORIZONTAL_FOV:  // radians; fx = width / (2 tan(hfov/2)) recovers the focal length
      return putValue(data, size, static_cast<float>(2.0 * std::atan(0.5 * k.width / k.fx)));
    case ONI_STREAM_PROPERTY_VERTICAL_FOV:
      return putValue(data, size, static_cast<float>(2.0 * std::atan(0.5 * k.height / k.fy)));
    case ONI_STREAM_PROPERTY_MIRRORING:
      return putValue(data, size, OniBool{FALSE});
    case ONI_STREAM_PROPERTY_CROPPING:
      return putValue(data, size, OniCropping{FALSE, 0, 0, mode_.resolutionX, mode_.resolutionY});
    case ONI_STREAM_PROPERTY_STRIDE:
      return putValue(data, size, mode_.resolutionX * bytesPerPixel());
    case ONI_STREAM_PROPERTY_MAX_VALUE:
      if (type_ != ONI_SENSOR_DEPTH) break;
      return putValue(data, size, static_cast<int>(std::lround(device_.maxDepth() *
                                                               (mode_.pixelFormat == ONI_PIXEL_FORMAT_DEPTH_100_UM ? 1e4 : 1e3))));
    case ONI_STREAM_PROPERTY_MIN_VALUE:
      if (type_ != ONI_SENSOR_DEPTH) break;
      return putValue(data, size, 0);
    case XN_STREAM_PROPERTY_EMITTER_DCMOS_DISTANCE:  // the PS1080's projector-to-camera baseline, cm
      if (type_ != ONI_SENSOR_DEPTH) break;
      return putValue(data, size, device_.baseline() * 100.0);
    default:
      break;
  }
  return ONI_STATUS_NOT_SUPPORTED;
}

OniStatus SimStream::setProperty(int id, const void* data, int size) {
  if (!data) return ONI_STATUS_BAD_PARAMETER;
  switch (id) {
    case ONI_STREAM_PROPERTY_VIDEO_MODE: {
      if (size != sizeof(OniVideoMode)) return ONI_STATUS_BAD_PARAMETER;
      OniVideoMode want;
      std::memcpy(&want, data, sizeof want);
      const OniSensorInfo* info = device_.sensor(type_);
      for (int i = 0; i < info->numSupportedVideoModes; ++i) {
        const OniVideoMode& m = info->pSupportedVideoModes[i];
        if (m.pixelFormat == want.pixelFormat && m.resolutionX == want.resolutionX &&
            m.resolutionY == want.resolutionY && m.fps == want.fps) {
          std::lock_guard<std::mutex> lock(mutex_);
          mode_ = m;
          return ONI_STATUS_OK;
        }
      }
      return ONI_STATUS_NOT_SUPPORTED;
    }
    case ONI_STREAM_PROPERTY_MIRRORING: {  // the simulator never mirrors; turning it off is fine
      if (size != sizeof(OniBool)) return ONI_STATUS_BAD_PARAMETER;
      OniBool on;
      std::memcpy(&on, data, sizeof on);
      return on ? ONI_STATUS_NOT_SUPPORTED : ONI_STATUS_OK;
    }
    case ONI_STREAM_PROPERTY_CROPPING: {
      if (size != sizeof(OniCropping)) return ONI_STATUS_BAD_PARAMETER;
      OniCropping c;
      std::memcpy(&c, data, sizeof c);
      return c.enabled ? ONI_STATUS_NOT_SUPPORTED : ONI_STATUS_OK;
    }
    default:
      return ONI_STATUS_NOT_SUPPORTED;
  }
}

OniStatus SimStream::convertDepthToColorCoordinates(StreamBase*, int depthX, int depthY, OniDepthPixel,
                                                    int* colorX, int* colorY) {
  if (!colorX || !colorY) return ONI_STATUS_BAD_PARAMETER;
  *colorX = depthX;
  *colorY = depthY;
  return ONI_STATUS_OK;
}

void SimStream::deliver(const StructuredLightFrame& f, int index, std::uint64_t timestamp_us) {
  OniVideoMode mode;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    mode = mode_;
  }
  OniFrame* frame = getServices().acquireFrame();
  if (!frame) return;
  const std::size_t n = static_cast<std::size_t>(f.width) * f.height;
  if (type_ == ONI_SENSOR_DEPTH) {
    const double per_metre = mode.pixelFormat == ONI_PIXEL_FORMAT_DEPTH_100_UM ? 1e4 : 1e3;
    auto* out = static_cast<OniDepthPixel*>(frame->data);
    for (std::size_t i = 0; i < n; ++i)
      out[i] = static_cast<OniDepthPixel>(std::min(65535.0, std::round(f.depth[i] * per_metre)));
  } else if (type_ == ONI_SENSOR_COLOR) {
    std::memcpy(frame->data, f.rgb.data(), n * 3);
  } else {
    std::memcpy(frame->data, f.ir.data(), n * 2);
  }
  frame->dataSize = static_cast<int>(n) * bytesPerPixel();
  frame->sensorType = type_;
  frame->timestamp = timestamp_us;
  frame->frameIndex = index;
  frame->width = f.width;
  frame->height = f.height;
  frame->videoMode = mode;
  frame->croppingEnabled = FALSE;
  frame->cropOriginX = 0;
  frame->cropOriginY = 0;
  frame->stride = f.width * bytesPerPixel();
  raiseNewFrame(frame);
  getServices().releaseFrame(frame);
}

}  // namespace keyturn::sim::openni2
