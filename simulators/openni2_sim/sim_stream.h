#pragma once
// One stream (depth, colour or IR) of the simulated OpenNI2 device: its video
// mode and properties, and the copy of each rendered frame into an OpenNI frame.
#include <mutex>

#include "keyturn/sim/structured_light_view.h"
#include "oni_driver_api.h"

namespace keyturn::sim::openni2 {

class SimDevice;

class SimStream : public oni::driver::StreamBase {
 public:
  SimStream(SimDevice& device, OniSensorType type);

  OniStatus start() override;
  void stop() override;
  OniStatus setProperty(int id, const void* data, int size) override;
  OniStatus getProperty(int id, void* data, int* size) override;
  OniBool isPropertySupported(int id) override;
  int getRequiredFrameSize() override;
  // Colour is rendered from the depth camera's viewpoint: a depth pixel is the same colour pixel.
  OniStatus convertDepthToColorCoordinates(StreamBase* color, int depthX, int depthY, OniDepthPixel depthZ,
                                           int* colorX, int* colorY) override;

  OniSensorType type() const { return type_; }
  // Called from the device's frame thread.
  void deliver(const StructuredLightFrame& frame, int index, std::uint64_t timestamp_us);

 private:
  int bytesPerPixel() const;
  SimDevice& device_;
  OniSensorType type_;
  std::mutex mutex_;  // guards mode_ between the application and the frame thread
  OniVideoMode mode_;
};

}  // namespace keyturn::sim::openni2
