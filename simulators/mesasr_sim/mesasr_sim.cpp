// libmesasr-sim: the libMesaSR C interface over a simulated SR4000. Built as
// libmesasr.so so that keyturn's driver, and any program written against
// libMesaSR, loads it exactly as it would load MESA's library.
#include <arpa/inet.h>
#include <sys/stat.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <thread>
#include <chrono>
#include <atomic>
#include <string>
#include <vector>

#include "keyturn/core/error.h"
#include "keyturn/drivers/mesasr_api.h"
#include "keyturn/drivers/tof_camera.h"
#include "keyturn/sim/mesasr_sim_config.h"
#include "keyturn/sim/tof_view.h"

#define SIM_EXPORT extern "C" __attribute__((visibility("default")))

using keyturn::Cloud;
using keyturn::sim::MesaSrSimConfig;

// The mode libMesaSR sets on an SR4000 it opens: fix-pattern correction, grey
// amplitude and the hardware filter, no confidence map (so two images).
constexpr int kPowerOnMode = AM_COR_FIX_PTRN | AM_CONV_GRAY | AM_DENOISE_ANF;

struct CMesaDevice {
  MesaSrSimConfig config;
  std::unique_ptr<keyturn::sim::TofViewRenderer> renderer;
  double distance = 0.0;
  bool ethernet = false;
  std::string address;
  // Image buffers; SR_SetMode reallocates them, as libMesaSR does.
  std::unique_ptr<std::uint16_t[]> distance_img, amplitude_img, confidence_img;
  ImgEntry entries[3] = {};
  int mode = kPowerOnMode;
  unsigned char int_time = 30;
  unsigned char ae[4] = {1, 150, 5, 70};
  ModulationFrq mf = MF_30MHz;
  unsigned short amp_threshold = 0;
  unsigned short dist_offset = 0;
  int timeout_ms = 3000;
  unsigned char regs[256] = {};
  std::uint64_t frames = 0, acquires = 0;
  bool unplugged = false;
  std::mt19937_64 fault_rng{0};
  std::chrono::steady_clock::time_point next_frame{};  // with a frame rate: when the next frame is due
};

namespace {

constexpr int kCols = 176, kRows = 144;
constexpr int kPixels = kCols * kRows;
std::atomic<SR_FuncCB*> g_callback{nullptr};  // process-wide, as in libMesaSR

int defaultCallback(SRCAM, unsigned int, unsigned int, void*) { return 0; }

void notify(SRCAM cam, unsigned msg, unsigned param) {
  if (SR_FuncCB* cb = g_callback.load()) cb(cam, msg, param, nullptr);
}

void allocateImages(CMesaDevice& d) {
  d.distance_img.reset(new std::uint16_t[kPixels]());
  d.amplitude_img.reset(new std::uint16_t[kPixels]());
  d.confidence_img.reset(new std::uint16_t[kPixels]());
  d.entries[0] = {IT_DISTANCE, DT_USHORT, d.distance_img.get(), kCols, kRows};
  d.entries[1] = {IT_AMPLITUDE, DT_USHORT, d.amplitude_img.get(), kCols, kRows};
  d.entries[2] = {IT_CONF_MAP, DT_USHORT, d.confidence_img.get(), kCols, kRows};
}

// The cable is "pulled" while the config's unplug file exists (tests, the studio's unplug button).
bool unplugged(const MesaSrSimConfig& c) {
  struct stat st;
  return !c.unplug_file.empty() && ::stat(c.unplug_file.c_str(), &st) == 0;
}

// config_path: null for $MESASR_SIM_CONFIG (libMesaSR's own entry points), else the file keyturn
// passed to KTSIM_OpenWithConfig ("" for the defaults).
int openCamera(SRCAM* out, bool ethernet, const std::string& address, unsigned serial, const char* config_path) {
  if (!out) return -1;
  *out = nullptr;
  try {
    auto d = std::make_unique<CMesaDevice>();
    if (!config_path) d->config = MesaSrSimConfig::fromEnvironment();
    else if (*config_path) d->config = MesaSrSimConfig::fromFile(config_path);
    if (d->config.faults.open_fail || unplugged(d->config)) return -1;
    if (!ethernet && serial != 0 && serial != d->config.serial) return 0;  // no such camera
    const auto mesh = keyturn::sim::scaledMesh(keyturn::sim::loadMeshOrBuiltin(d->config.mesh), d->config.scale);
    d->renderer = std::make_unique<keyturn::sim::TofViewRenderer>(mesh);
    d->distance = d->config.distance > 0 ? d->config.distance : keyturn::sim::operatorDistance(mesh);
    d->ethernet = ethernet;
    d->address = address;
    d->regs[SR4000_REG_FIRMWARE] = 0x57;
    d->fault_rng.seed(d->config.seed * 7919 + static_cast<std::uint64_t>(std::random_device{}()));
    allocateImages(*d);
    *out = d.release();
    for (unsigned p = 0; p <= 100; p += 50) notify(*out, CM_PROGRESS, p);
    return 1;
  } catch (const std::exception&) {
    return -1;  // a bad configuration or mesh: like a camera that does not answer
  }
}

// Renders one frame into the raw images following the SR4000's conventions.
void renderFrame(CMesaDevice& d) {
  keyturn::sim::SceneView v;
  v.distance = d.distance;
  v.elevation_deg = d.config.elevation;
  v.roll_deg = d.config.roll;
  v.turntable_deg = d.config.world.empty()
                        ? d.config.turntable_deg
                        : keyturn::sim::readWorldTurntable(d.config.world, d.config.turntable_deg);
  v.seed = d.config.noise_per_pose ? d.config.poseNoiseSeed(v.turntable_deg) : d.config.seed + d.frames;
  // Shorter integration collects less light: noise grows as 1/sqrt(time).
  const double t_ms = 0.3 + 0.1 * d.int_time, t_ref = 0.3 + 0.1 * 30;
  v.noise_at_1m *= std::sqrt(t_ref / t_ms);
  v.amplitude_threshold = 0.0;  // the camera's own threshold is applied below, in counts
  const Cloud c = d.renderer->render(v);

  const double range = keyturn::drivers::nonAmbiguousRange(d.mf);
  // Counts: a 50% target head-on at 1 m gives 5000 at the reference integration
  // time, so the operator's 0.45 m placement stays below saturation (65535).
  const double counts_per_unit = 5000.0 / 0.5 * (t_ms / t_ref);
  for (int i = 0; i < kPixels; ++i) {
    const double amp = c.amplitude[i] * counts_per_unit;
    const bool saturated = amp > 65535.0;
    d.amplitude_img[i] = static_cast<std::uint16_t>(std::min(amp, 65535.0));
    const auto& p = c.points[i];
    if (!Cloud::isValid(p) || d.amplitude_img[i] < d.amp_threshold) {
      d.distance_img[i] = 0;  // no return, or under the amplitude threshold
      d.confidence_img[i] = 0;
      continue;
    }
    const double wrapped = std::fmod(static_cast<double>(p.norm()), range);  // phase wrap
    const double raw = std::round(wrapped / range * 65535.0) + d.dist_offset;
    d.distance_img[i] = static_cast<std::uint16_t>(std::clamp(raw, 1.0, 65535.0));
    d.confidence_img[i] = saturated ? 0 : static_cast<std::uint16_t>(c.confidence[i] * 65535.0f);
  }
}

// Unit ray of pixel (u, v) in libMesaSR's frame (x left, y up, z forward).
void pixelRay(const keyturn::sim::Intrinsics& k, double u, double v, double r[3]) {
  const double x = (u + 0.5 - k.cx) / k.fx, y = (v + 0.5 - k.cy) / k.fy;
  const double n = std::sqrt(x * x + y * y + 1.0);
  r[0] = -x / n;
  r[1] = -y / n;
  r[2] = 1.0 / n;
}

double rawToMetres(const CMesaDevice& d, unsigned short raw) {
  const double range = keyturn::drivers::nonAmbiguousRange(d.mf);
  return (static_cast<double>(raw) - d.dist_offset) / 65535.0 * range;
}

// A null output is skipped, as in libMesaSR (a caller may want z alone).
template <typename T>
void put(void* base, int pitch, int i, T value) {
  if (base) std::memcpy(static_cast<char*>(base) + static_cast<std::ptrdiff_t>(pitch) * i, &value, sizeof(T));
}

template <typename T, typename Z>
int coordTrf(SRCAM cam, T* x, T* y, Z* z, int px, int py, int pz, double scale) {
  if (!cam || cam->unplugged) return -1;
  const auto& k = cam->renderer->intrinsics();
  for (int i = 0; i < kPixels; ++i) {
    double r[3];
    pixelRay(k, i % kCols, i / kCols, r);
    const unsigned short raw = cam->distance_img[i];
    const double m = raw == 0 ? 0.0 : rawToMetres(*cam, raw) * scale;
    put<T>(x, px, i, static_cast<T>(m * r[0]));
    put<T>(y, py, i, static_cast<T>(m * r[1]));
    put<Z>(z, pz, i, static_cast<Z>(m * r[2]));
  }
  return 0;
}

template <typename T, typename Z>
int coordTrfPnt(SRCAM cam, const unsigned char* ix, const unsigned char* iy, const unsigned short* idst,
                T* ox, T* oy, Z* oz, int num, double scale) {
  if (!cam || cam->unplugged || !ix || !iy || !idst || num < 0) return -1;
  const auto& k = cam->renderer->intrinsics();
  for (int i = 0; i < num; ++i) {
    double r[3];
    pixelRay(k, ix[i], iy[i], r);
    const double m = idst[i] == 0 ? 0.0 : rawToMetres(*cam, idst[i]) * scale;
    if (ox) ox[i] = static_cast<T>(m * r[0]);
    if (oy) oy[i] = static_cast<T>(m * r[1]);
    if (oz) oz[i] = static_cast<Z>(m * r[2]);
  }
  return 0;
}

bool alive(SRCAM cam) { return cam && !cam->unplugged; }

}  // namespace

SIM_EXPORT int SR_OpenUSB(SRCAM* srCam, unsigned int serialNumber) {
  return openCamera(srCam, false, "", serialNumber, nullptr);
}

// keyturn's extension (mesasr_api.h): the configuration passed, not read from the environment.
SIM_EXPORT int KTSIM_OpenWithConfig(SRCAM* srCam, const char* configPath) {
  return openCamera(srCam, false, "", 0, configPath ? configPath : "");
}

SIM_EXPORT int SR_OpenETH(SRCAM* srCam, const char* addr) {
  in_addr a{};
  if (!addr || ::inet_pton(AF_INET, addr, &a) != 1) {
    if (srCam) *srCam = nullptr;
    return -1;
  }
  return openCamera(srCam, true, addr, 0, nullptr);
}

SIM_EXPORT int SR_OpenDlg(SRCAM* srCam, int, int) { return SR_OpenUSB(srCam, 0); }

SIM_EXPORT int SR_Close(SRCAM srCam) {
  delete srCam;
  return 0;
}

SIM_EXPORT int SR_Acquire(SRCAM cam) {
  if (!alive(cam)) return -1;
  const auto& f = cam->config.faults;
  ++cam->acquires;
  if (unplugged(cam->config)) {
    cam->unplugged = true;
    return -1;
  }
  if (f.disconnect_after > 0 && cam->frames >= static_cast<std::uint64_t>(f.disconnect_after)) {
    cam->unplugged = true;  // stays silent until closed and opened again
    return -1;
  }
  if (f.timeout_every > 0 && cam->acquires % f.timeout_every == 0) return -1;
  int random_fault = -1;  // 0 timeout, 1 short frame, 2 disconnect
  if (f.random_rate > 0 && std::uniform_real_distribution<double>(0, 1)(cam->fault_rng) < f.random_rate)
    random_fault = static_cast<int>(cam->fault_rng() % 3);
  if (random_fault == 0) return -1;
  if (random_fault == 2) {
    cam->unplugged = true;
    return -1;
  }
  try {
    renderFrame(*cam);
  } catch (const std::exception&) {
    return -1;
  }
  if (cam->config.frame_rate > 0) {
    // A real camera delivers at its frame rate: wait for the frame's slot.
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / cam->config.frame_rate));
    const auto now = std::chrono::steady_clock::now();
    if (cam->next_frame > now) std::this_thread::sleep_until(cam->next_frame);
    cam->next_frame = std::max(cam->next_frame, now) + period;
  }
  ++cam->frames;
  const int full = 2 * kPixels * static_cast<int>(sizeof(std::uint16_t));
  if ((f.corrupt_every > 0 && cam->acquires % f.corrupt_every == 0) || random_fault == 1) return full / 3;  // short transfer
  return full;
}

SIM_EXPORT void* SR_GetImage(SRCAM cam, unsigned char idx) {
  if (!alive(cam) || idx > 2) return nullptr;
  if (idx == 2 && !(cam->mode & AM_CONF_MAP)) return nullptr;
  return cam->entries[idx].data;
}

SIM_EXPORT int SR_GetImageList(SRCAM cam, ImgEntry** list) {
  if (!alive(cam) || !list) return -1;
  *list = cam->entries;
  return cam->mode & AM_CONF_MAP ? 3 : 2;
}

SIM_EXPORT unsigned int SR_GetRows(SRCAM cam) { return cam ? kRows : 0; }
SIM_EXPORT unsigned int SR_GetCols(SRCAM cam) { return cam ? kCols : 0; }

SIM_EXPORT int SR_SetMode(SRCAM cam, int mode) {
  if (!alive(cam)) return -1;
  if (mode == cam->mode) return 0;  // nothing changes: the buffers stay, no messages
  notify(cam, CM_CHANGING, static_cast<unsigned>(mode));
  cam->mode = mode;
  allocateImages(*cam);  // old pointers are now invalid: drivers must fetch the list again
  notify(cam, CM_CHANGED, static_cast<unsigned>(mode));
  return 0;
}
SIM_EXPORT int SR_GetMode(SRCAM cam) { return alive(cam) ? cam->mode : -1; }

SIM_EXPORT int SR_SetIntegrationTime(SRCAM cam, unsigned char t) {
  if (!alive(cam)) return -1;
  cam->int_time = t;
  return 2;  // like the Set* below, libMesaSR's count of bytes written to the camera's registers
}
SIM_EXPORT unsigned char SR_GetIntegrationTime(SRCAM cam) { return cam ? cam->int_time : 0; }

SIM_EXPORT int SR_SetModulationFrequency(SRCAM cam, ModulationFrq f) {
  if (!alive(cam) || keyturn::drivers::modulationMHz(f) <= 0) return -1;
  cam->mf = f;
  return 0;
}
SIM_EXPORT ModulationFrq SR_GetModulationFrequency(SRCAM cam) { return cam ? cam->mf : MF_30MHz; }

SIM_EXPORT int SR_SetAmplitudeThreshold(SRCAM cam, unsigned short v) {
  if (!alive(cam)) return -1;
  cam->amp_threshold = v;
  return 4;  // a 16-bit value: two registers
}
SIM_EXPORT unsigned short SR_GetAmplitudeThreshold(SRCAM cam) { return cam ? cam->amp_threshold : 0; }

SIM_EXPORT int SR_SetAutoExposure(SRCAM cam, unsigned char mn, unsigned char mx, unsigned char pct,
                                  unsigned char pos) {
  if (!alive(cam)) return -1;
  cam->ae[0] = mn;
  cam->ae[1] = mx;
  cam->ae[2] = pct;
  cam->ae[3] = pos;
  return 0;
}

SIM_EXPORT int SR_SetDistanceOffset(SRCAM cam, unsigned short ofs) {
  if (!alive(cam)) return -1;
  cam->dist_offset = ofs;
  return 4;
}
SIM_EXPORT unsigned short SR_GetDistanceOffset(SRCAM cam) { return cam ? cam->dist_offset : 0; }

SIM_EXPORT void SR_SetTimeout(SRCAM cam, int ms) {
  if (cam) cam->timeout_ms = ms;
}

SIM_EXPORT int SR_GetDeviceString(SRCAM cam, char* buf, int buflen) {
  if (!cam || !buf || buflen <= 0) return -1;
  const int n = std::snprintf(buf, static_cast<std::size_t>(buflen),
                              "VendorID:0x%04x, ProductID:0x%04x, Manufacturer:'%s', Product:'%s'", 0x1ad2,
                              0x0075, "MESA Imaging (keyturn libmesasr-sim)",
                              cam->ethernet ? "SR4000-ETH" : "SR4000");
  return std::min(n, buflen - 1);
}

SIM_EXPORT unsigned int SR_ReadSerial(SRCAM cam) { return cam ? cam->config.serial : 0; }

// The release whose interface (and soname, libmesasr.so.1.0.14) the simulator
// implements, stored as MESA's library stores "1.0.14.706": version[3] is the
// major number, version[0] the build.
SIM_EXPORT int SR_GetVersion(unsigned short version[4]) {
  if (!version) return -1;
  version[3] = 1;
  version[2] = 0;
  version[1] = 14;
  version[0] = 706;
  return 0;
}

SIM_EXPORT unsigned char SR_GetReg(SRCAM cam, unsigned char reg) { return cam ? cam->regs[reg] : 0; }
SIM_EXPORT int SR_SetReg(SRCAM cam, unsigned char reg, unsigned char val) {
  if (!alive(cam)) return -1;
  cam->regs[reg] = val;
  return 2;  // register and value
}

SIM_EXPORT SR_FuncCB* SR_SetCallback(SR_FuncCB* cb) {
  SR_FuncCB* old = g_callback.exchange(cb);
  return old ? old : &defaultCallback;
}
SIM_EXPORT SR_FuncCB* SR_GetDefaultCallback(void) { return &defaultCallback; }

SIM_EXPORT int SR_CoordTrfFlt(SRCAM cam, float* x, float* y, float* z, int px, int py, int pz) {
  return coordTrf<float, float>(cam, x, y, z, px, py, pz, 1.0);
}
SIM_EXPORT int SR_CoordTrfDbl(SRCAM cam, double* x, double* y, double* z, int px, int py, int pz) {
  return coordTrf<double, double>(cam, x, y, z, px, py, pz, 1.0);
}
SIM_EXPORT int SR_CoordTrfUint16(SRCAM cam, short* x, short* y, unsigned short* z, int px, int py, int pz) {
  return coordTrf<short, unsigned short>(cam, x, y, z, px, py, pz, 1000.0);  // millimetres
}
SIM_EXPORT int SR_CoordTrfPntFlt(SRCAM cam, const unsigned char* ix, const unsigned char* iy,
                                 const unsigned short* idst, float* ox, float* oy, float* oz, int num) {
  return coordTrfPnt<float, float>(cam, ix, iy, idst, ox, oy, oz, num, 1.0);
}
SIM_EXPORT int SR_CoordTrfPntDbl(SRCAM cam, const unsigned char* ix, const unsigned char* iy,
                                 const unsigned short* idst, double* ox, double* oy, double* oz, int num) {
  return coordTrfPnt<double, double>(cam, ix, iy, idst, ox, oy, oz, num, 1.0);
}
SIM_EXPORT int SR_CoordTrfPntUint16(SRCAM cam, const unsigned char* ix, const unsigned char* iy,
                                    const unsigned short* idst, short* ox, short* oy, unsigned short* oz,
                                    int num) {
  return coordTrfPnt<short, unsigned short>(cam, ix, iy, idst, ox, oy, oz, num, 1000.0);
}

// Raw TCP access to the camera has no meaning in the simulator.
SIM_EXPORT int SR_TCPSend(SRCAM, void*, int, int) { return -1; }
SIM_EXPORT int SR_TCPRecv(SRCAM, void*, int, int) { return -1; }
