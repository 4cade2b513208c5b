// libKeyturnOniFile.so.0: Debian's .oni recording driver (libOniFile, OpenNI2 2.2), loaded from the
// system's drivers folder and passed every call, except that a stream is never taken out of a
// playback device while the device's player thread runs.
//
// Why: libOniFile's player thread (PlayerDevice::MainLoop) walks the device's list of streams
// without a lock, continuously once a started stream has reached the end of the recording, while
// PlayerDevice::destroyStream unlinks the stream from that list and frees it from the application's
// thread. The player thread then follows a freed list node and crashes (issue 52: one run in ~150 of
// openni2.OpenNI2Sim.AnOniRecordingPlaysBackTheSameFrames; every run of
// OniPlayback.AStreamDestroyedAfterTheRecordingEnded without this guard, tests/openni2). Nothing in OpenNI2's API orders
// a stream's end after the player thread's: the device joins that thread only when it closes, and
// OpenNI destroys a device's streams before it closes the device.
//
// So a destroyed stream is stopped, its last frame in flight delivered (as libOniFile's own
// unregistration waits for it), and from then on it is cut off from OpenNI: its frame and property
// callbacks go nowhere. It stays in the player's list, stopped, which the player skips. It is never
// freed: once its device is closed, libOniFile's stream destructor would reach into that closed
// device and its sources. What stays is a few kilobytes per stream of a playback device.
#include <dlfcn.h>

#include <condition_variable>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>

#include "oni_driver_api.h"

#ifndef KEYTURN_SYSTEM_ONI_FILE_DRIVER
#error "KEYTURN_SYSTEM_ONI_FILE_DRIVER: the path of the system's libOniFile.so.0"
#endif

namespace {

using oni::driver::DeviceBase;
using oni::driver::StreamBase;
using NewFrame = oni::driver::NewFrameCallback;
using PropertyChanged = oni::driver::PropertyChangedCallback;

// The real driver's entry points (OniDriverAPI.h's ONI_EXPORT_DRIVER), looked up by name.
struct Real {
  void* (*create)(OniDriverServices*);
  void (*destroy)();
  OniStatus (*initialize)(oni::driver::DeviceConnectedCallback, oni::driver::DeviceDisconnectedCallback,
                          oni::driver::DeviceStateChangedCallback, void*);
  OniStatus (*tryDevice)(const char*);
  DeviceBase* (*deviceOpen)(const char*, const char*);
  void (*deviceClose)(DeviceBase*);
  OniStatus (*deviceGetSensorInfoList)(DeviceBase*, OniSensorInfo**, int*);
  StreamBase* (*deviceCreateStream)(DeviceBase*, OniSensorType);
  void (*deviceDestroyStream)(DeviceBase*, StreamBase*);
  OniStatus (*deviceSetProperty)(DeviceBase*, int, const void*, int);
  OniStatus (*deviceGetProperty)(DeviceBase*, int, void*, int*);
  OniBool (*deviceIsPropertySupported)(DeviceBase*, int);
  void (*deviceSetPropertyChangedCallback)(DeviceBase*, PropertyChanged, void*);
  void (*deviceNotifyAllProperties)(DeviceBase*);
  OniStatus (*deviceInvoke)(DeviceBase*, int, void*, int);
  OniBool (*deviceIsCommandSupported)(DeviceBase*, int);
  OniStatus (*deviceTryManualTrigger)(DeviceBase*);
  OniBool (*deviceIsImageRegistrationModeSupported)(DeviceBase*, OniImageRegistrationMode);
  void (*streamSetServices)(StreamBase*, OniStreamServices*);
  OniStatus (*streamSetProperty)(StreamBase*, int, const void*, int);
  OniStatus (*streamGetProperty)(StreamBase*, int, void*, int*);
  OniBool (*streamIsPropertySupported)(StreamBase*, int);
  void (*streamSetPropertyChangedCallback)(StreamBase*, PropertyChanged, void*);
  void (*streamNotifyAllProperties)(StreamBase*);
  OniStatus (*streamInvoke)(StreamBase*, int, void*, int);
  OniBool (*streamIsCommandSupported)(StreamBase*, int);
  OniStatus (*streamStart)(StreamBase*);
  void (*streamStop)(StreamBase*);
  int (*streamGetRequiredFrameSize)(StreamBase*);
  void (*streamSetNewFrameCallback)(StreamBase*, NewFrame, void*);
  OniStatus (*streamConvertDepthToColorCoordinates)(StreamBase*, StreamBase*, int, int, OniDepthPixel, int*, int*);
  void* (*enableFrameSync)(StreamBase**, int);
  void (*disableFrameSync)(void*);
};

Real g_real{};
bool g_loaded = false;

template <typename F>
bool lookUp(void* lib, const char* name, F& f) {
  f = reinterpret_cast<F>(::dlsym(lib, name));
  return f != nullptr;
}

// Loads the system's libOniFile once; it stays loaded (its frames stay named in leak reports, and
// nothing of it runs once its devices are closed).
bool load() {
  if (g_loaded) return true;
  void* lib = ::dlopen(KEYTURN_SYSTEM_ONI_FILE_DRIVER, RTLD_NOW | RTLD_LOCAL);
  if (!lib) return false;
  Real r{};
  const bool all =
      lookUp(lib, "oniDriverCreate", r.create) && lookUp(lib, "oniDriverDestroy", r.destroy) &&
      lookUp(lib, "oniDriverInitialize", r.initialize) && lookUp(lib, "oniDriverTryDevice", r.tryDevice) &&
      lookUp(lib, "oniDriverDeviceOpen", r.deviceOpen) && lookUp(lib, "oniDriverDeviceClose", r.deviceClose) &&
      lookUp(lib, "oniDriverDeviceGetSensorInfoList", r.deviceGetSensorInfoList) &&
      lookUp(lib, "oniDriverDeviceCreateStream", r.deviceCreateStream) &&
      lookUp(lib, "oniDriverDeviceDestroyStream", r.deviceDestroyStream) &&
      lookUp(lib, "oniDriverDeviceSetProperty", r.deviceSetProperty) &&
      lookUp(lib, "oniDriverDeviceGetProperty", r.deviceGetProperty) &&
      lookUp(lib, "oniDriverDeviceIsPropertySupported", r.deviceIsPropertySupported) &&
      lookUp(lib, "oniDriverDeviceSetPropertyChangedCallback", r.deviceSetPropertyChangedCallback) &&
      lookUp(lib, "oniDriverDeviceNotifyAllProperties", r.deviceNotifyAllProperties) &&
      lookUp(lib, "oniDriverDeviceInvoke", r.deviceInvoke) &&
      lookUp(lib, "oniDriverDeviceIsCommandSupported", r.deviceIsCommandSupported) &&
      lookUp(lib, "oniDriverDeviceTryManualTrigger", r.deviceTryManualTrigger) &&
      lookUp(lib, "oniDriverDeviceIsImageRegistrationModeSupported", r.deviceIsImageRegistrationModeSupported) &&
      lookUp(lib, "oniDriverStreamSetServices", r.streamSetServices) &&
      lookUp(lib, "oniDriverStreamSetProperty", r.streamSetProperty) &&
      lookUp(lib, "oniDriverStreamGetProperty", r.streamGetProperty) &&
      lookUp(lib, "oniDriverStreamIsPropertySupported", r.streamIsPropertySupported) &&
      lookUp(lib, "oniDriverStreamSetPropertyChangedCallback", r.streamSetPropertyChangedCallback) &&
      lookUp(lib, "oniDriverStreamNotifyAllProperties", r.streamNotifyAllProperties) &&
      lookUp(lib, "oniDriverStreamInvoke", r.streamInvoke) &&
      lookUp(lib, "oniDriverStreamIsCommandSupported", r.streamIsCommandSupported) &&
      lookUp(lib, "oniDriverStreamStart", r.streamStart) && lookUp(lib, "oniDriverStreamStop", r.streamStop) &&
      lookUp(lib, "oniDriverStreamGetRequiredFrameSize", r.streamGetRequiredFrameSize) &&
      lookUp(lib, "oniDriverStreamSetNewFrameCallback", r.streamSetNewFrameCallback) &&
      lookUp(lib, "oniDriverStreamConvertDepthToColorCoordinates", r.streamConvertDepthToColorCoordinates) &&
      lookUp(lib, "oniDriverEnableFrameSync", r.enableFrameSync) &&
      lookUp(lib, "oniDriverDisableFrameSync", r.disableFrameSync);
  if (!all) return false;
  g_real = r;
  g_loaded = true;
  return true;
}

// One stream of a playback device as OpenNI sees it. The real stream gets this stream's services
// and callbacks, which pass through to OpenNI's until the stream is destroyed.
struct Stream {
  DeviceBase* device = nullptr;
  OniStreamServices* services = nullptr;  // OpenNI's
  OniStreamServices own{};                // given to the real stream
  NewFrame new_frame = nullptr;
  void* new_frame_cookie = nullptr;
  PropertyChanged property_changed = nullptr;
  void* property_changed_cookie = nullptr;

  std::mutex mutex;  // guards what follows
  std::condition_variable idle;
  int busy = 0;        // calls into OpenNI in progress (a frame: acquired until released)
  bool gone = false;   // destroyed by OpenNI: nothing reaches OpenNI any more
};

std::mutex g_mutex;  // guards g_streams
std::map<StreamBase*, std::unique_ptr<Stream>> g_streams;

Stream* find(StreamBase* s) {
  std::lock_guard<std::mutex> lock(g_mutex);
  const auto it = g_streams.find(s);
  return it == g_streams.end() ? nullptr : it->second.get();
}

// A call into OpenNI for this stream may begin: false once it is destroyed.
bool enter(Stream* s) {
  std::lock_guard<std::mutex> lock(s->mutex);
  if (s->gone) return false;
  ++s->busy;
  return true;
}

void leave(Stream* s) {
  std::lock_guard<std::mutex> lock(s->mutex);
  if (s->busy > 0 && --s->busy == 0) s->idle.notify_all();
}

int ONI_CALLBACK_TYPE defaultRequiredFrameSize(void* cookie) {
  auto* s = static_cast<Stream*>(cookie);
  if (!enter(s)) return 0;
  const int size = s->services->getDefaultRequiredFrameSize(s->services->streamServices);
  leave(s);
  return size;
}

// libOniFile delivers a frame as acquire → fill → new-frame callback → release, on its player
// thread: the stream counts as busy from the acquisition to the release.
OniFrame* ONI_CALLBACK_TYPE acquireFrame(void* cookie) {
  auto* s = static_cast<Stream*>(cookie);
  if (!enter(s)) return nullptr;
  OniFrame* frame = s->services->acquireFrame(s->services->streamServices);
  if (!frame) leave(s);
  return frame;
}

void ONI_CALLBACK_TYPE addFrameRef(void* cookie, OniFrame* frame) {
  auto* s = static_cast<Stream*>(cookie);
  s->services->addFrameRef(s->services->streamServices, frame);
}

void ONI_CALLBACK_TYPE releaseFrame(void* cookie, OniFrame* frame) {
  auto* s = static_cast<Stream*>(cookie);
  s->services->releaseFrame(s->services->streamServices, frame);
  leave(s);
}

// Within an acquired frame (busy), so never after the stream's destruction returned.
void ONI_CALLBACK_TYPE newFrame(StreamBase* stream, OniFrame* frame, void* cookie) {
  auto* s = static_cast<Stream*>(cookie);
  NewFrame handler;
  void* handler_cookie;
  {
    std::lock_guard<std::mutex> lock(s->mutex);
    handler = s->new_frame;
    handler_cookie = s->new_frame_cookie;
  }
  if (handler) handler(stream, frame, handler_cookie);
}

void ONI_CALLBACK_TYPE propertyChanged(void* sender, int id, const void* data, int size, void* cookie) {
  auto* s = static_cast<Stream*>(cookie);
  PropertyChanged handler;
  void* handler_cookie;
  {
    std::lock_guard<std::mutex> lock(s->mutex);
    if (s->gone) return;
    ++s->busy;
    handler = s->property_changed;
    handler_cookie = s->property_changed_cookie;
  }
  if (handler) handler(sender, id, data, size, handler_cookie);
  leave(s);
}

}  // namespace

#define KEYTURN_ONI_EXPORT extern "C" __attribute__((visibility("default")))

KEYTURN_ONI_EXPORT void oniDriverCreate(OniDriverServices* services) {
  if (load()) g_real.create(services);
}

KEYTURN_ONI_EXPORT void oniDriverDestroy() {
  if (g_loaded) g_real.destroy();
}

KEYTURN_ONI_EXPORT OniStatus oniDriverInitialize(oni::driver::DeviceConnectedCallback connected,
                                                 oni::driver::DeviceDisconnectedCallback disconnected,
                                                 oni::driver::DeviceStateChangedCallback state_changed, void* cookie) {
  if (!g_loaded) return ONI_STATUS_ERROR;  // no libOniFile on this system: OpenNI leaves this driver out
  return g_real.initialize(connected, disconnected, state_changed, cookie);
}

KEYTURN_ONI_EXPORT OniStatus oniDriverTryDevice(const char* uri) { return g_real.tryDevice(uri); }

KEYTURN_ONI_EXPORT DeviceBase* oniDriverDeviceOpen(const char* uri, const char* mode) {
  return g_real.deviceOpen(uri, mode);
}

// Closing the device joins its player thread; then its streams, destroyed or not, are forgotten
// (the real ones are not freed: see the top of this file).
KEYTURN_ONI_EXPORT void oniDriverDeviceClose(DeviceBase* device) {
  g_real.deviceClose(device);
  std::lock_guard<std::mutex> lock(g_mutex);
  for (auto it = g_streams.begin(); it != g_streams.end();)
    it = it->second->device == device ? g_streams.erase(it) : std::next(it);
}

KEYTURN_ONI_EXPORT OniStatus oniDriverDeviceGetSensorInfoList(DeviceBase* device, OniSensorInfo** infos, int* count) {
  return g_real.deviceGetSensorInfoList(device, infos, count);
}

KEYTURN_ONI_EXPORT StreamBase* oniDriverDeviceCreateStream(DeviceBase* device, OniSensorType type) {
  StreamBase* real = g_real.deviceCreateStream(device, type);
  if (!real) return nullptr;
  auto s = std::make_unique<Stream>();
  s->device = device;
  s->own = {s.get(), defaultRequiredFrameSize, acquireFrame, addFrameRef, releaseFrame};
  std::lock_guard<std::mutex> lock(g_mutex);
  g_streams[real] = std::move(s);
  return real;
}

// Stopped, its frame in flight delivered, then cut off from OpenNI; left in the player's list.
KEYTURN_ONI_EXPORT void oniDriverDeviceDestroyStream(DeviceBase*, StreamBase* stream) {
  Stream* s = find(stream);
  if (!s) return;
  g_real.streamStop(stream);
  std::unique_lock<std::mutex> lock(s->mutex);
  s->gone = true;
  s->idle.wait(lock, [s] { return s->busy == 0; });
}

KEYTURN_ONI_EXPORT OniStatus oniDriverDeviceSetProperty(DeviceBase* device, int id, const void* data, int size) {
  return g_real.deviceSetProperty(device, id, data, size);
}

KEYTURN_ONI_EXPORT OniStatus oniDriverDeviceGetProperty(DeviceBase* device, int id, void* data, int* size) {
  return g_real.deviceGetProperty(device, id, data, size);
}

KEYTURN_ONI_EXPORT OniBool oniDriverDeviceIsPropertySupported(DeviceBase* device, int id) {
  return g_real.deviceIsPropertySupported(device, id);
}

KEYTURN_ONI_EXPORT void oniDriverDeviceSetPropertyChangedCallback(DeviceBase* device, PropertyChanged handler,
                                                                 void* cookie) {
  g_real.deviceSetPropertyChangedCallback(device, handler, cookie);
}

KEYTURN_ONI_EXPORT void oniDriverDeviceNotifyAllProperties(DeviceBase* device) {
  g_real.deviceNotifyAllProperties(device);
}

KEYTURN_ONI_EXPORT OniStatus oniDriverDeviceInvoke(DeviceBase* device, int id, void* data, int size) {
  return g_real.deviceInvoke(device, id, data, size);
}

KEYTURN_ONI_EXPORT OniBool oniDriverDeviceIsCommandSupported(DeviceBase* device, int id) {
  return g_real.deviceIsCommandSupported(device, id);
}

KEYTURN_ONI_EXPORT OniStatus oniDriverDeviceTryManualTrigger(DeviceBase* device) {
  return g_real.deviceTryManualTrigger(device);
}

KEYTURN_ONI_EXPORT OniBool oniDriverDeviceIsImageRegistrationModeSupported(DeviceBase* device,
                                                                           OniImageRegistrationMode mode) {
  return g_real.deviceIsImageRegistrationModeSupported(device, mode);
}

KEYTURN_ONI_EXPORT void oniDriverStreamSetServices(StreamBase* stream, OniStreamServices* services) {
  Stream* s = find(stream);
  if (!s) return g_real.streamSetServices(stream, services);
  s->services = services;
  g_real.streamSetServices(stream, &s->own);
}

KEYTURN_ONI_EXPORT OniStatus oniDriverStreamSetProperty(StreamBase* stream, int id, const void* data, int size) {
  return g_real.streamSetProperty(stream, id, data, size);
}

KEYTURN_ONI_EXPORT OniStatus oniDriverStreamGetProperty(StreamBase* stream, int id, void* data, int* size) {
  return g_real.streamGetProperty(stream, id, data, size);
}

KEYTURN_ONI_EXPORT OniBool oniDriverStreamIsPropertySupported(StreamBase* stream, int id) {
  return g_real.streamIsPropertySupported(stream, id);
}

KEYTURN_ONI_EXPORT void oniDriverStreamSetPropertyChangedCallback(StreamBase* stream, PropertyChanged handler,
                                                                 void* cookie) {
  Stream* s = find(stream);
  if (!s) return g_real.streamSetPropertyChangedCallback(stream, handler, cookie);
  {
    std::lock_guard<std::mutex> lock(s->mutex);
    s->property_changed = handler;
    s->property_changed_cookie = cookie;
  }
  g_real.streamSetPropertyChangedCallback(stream, propertyChanged, s);
}

KEYTURN_ONI_EXPORT void oniDriverStreamNotifyAllProperties(StreamBase* stream) {
  g_real.streamNotifyAllProperties(stream);
}

KEYTURN_ONI_EXPORT OniStatus oniDriverStreamInvoke(StreamBase* stream, int id, void* data, int size) {
  return g_real.streamInvoke(stream, id, data, size);
}

KEYTURN_ONI_EXPORT OniBool oniDriverStreamIsCommandSupported(StreamBase* stream, int id) {
  return g_real.streamIsCommandSupported(stream, id);
}

KEYTURN_ONI_EXPORT OniStatus oniDriverStreamStart(StreamBase* stream) { return g_real.streamStart(stream); }

KEYTURN_ONI_EXPORT void oniDriverStreamStop(StreamBase* stream) { g_real.streamStop(stream); }

KEYTURN_ONI_EXPORT int oniDriverStreamGetRequiredFrameSize(StreamBase* stream) {
  return g_real.streamGetRequiredFrameSize(stream);
}

KEYTURN_ONI_EXPORT void oniDriverStreamSetNewFrameCallback(StreamBase* stream, NewFrame handler, void* cookie) {
  Stream* s = find(stream);
  if (!s) return g_real.streamSetNewFrameCallback(stream, handler, cookie);
  {
    std::lock_guard<std::mutex> lock(s->mutex);
    s->new_frame = handler;
    s->new_frame_cookie = cookie;
  }
  g_real.streamSetNewFrameCallback(stream, newFrame, s);
}

KEYTURN_ONI_EXPORT OniStatus oniDriverStreamConvertDepthToColorCoordinates(StreamBase* depth, StreamBase* colour, int x,
                                                                           int y, OniDepthPixel z, int* colour_x,
                                                                           int* colour_y) {
  return g_real.streamConvertDepthToColorCoordinates(depth, colour, x, y, z, colour_x, colour_y);
}

KEYTURN_ONI_EXPORT void* oniDriverEnableFrameSync(StreamBase** streams, int count) {
  return g_real.enableFrameSync(streams, count);
}

KEYTURN_ONI_EXPORT void oniDriverDisableFrameSync(void* group) { g_real.disableFrameSync(group); }
