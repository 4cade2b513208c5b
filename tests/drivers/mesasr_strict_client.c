/* A plain C program (no C++ runtime, no threads) making the calls of MESA's
 * libMesaSRTester "TestBasic", in its order, and checking every result as a
 * careful caller would. Usage: mesasr_strict_client usb | eth ADDRESS.
 * Prints one line per failed check and exits 1 if any failed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "keyturn/drivers/mesasr_api.h"

enum { COLS = 176, ROWS = 144, PIXELS = COLS * ROWS };
/* The simulated SR4000's pinhole intrinsics (docs/simulated-views.md). */
static const double kFx = 219.9, kFy = 219.9, kCx = 88.0, kCy = 72.0;
/* Non-ambiguous range at 30 MHz, the SR4000's default: c / (2 f). */
static const double kRange30 = 299.792458 / 60.0;

static int failures;

static void check(int ok, const char* what, const char* detail) {
  if (!ok) {
    printf("FAILED: %s: %s\n", what, detail);
    ++failures;
  }
}

static int changing, changed;
static int countingCallback(SRCAM cam, unsigned int msg, unsigned int param, void* data) {
  (void)cam, (void)param, (void)data;
  if (msg == CM_CHANGING) ++changing;
  if (msg == CM_CHANGED) ++changed;
  return 0;
}

/* The image list as a caller re-reads it after SR_SetMode. */
static void checkImageList(SRCAM cam, int with_conf) {
  ImgEntry* list = NULL;
  const int n = SR_GetImageList(cam, &list);
  check(n == (with_conf ? 3 : 2) && list != NULL, "GetImageList", "image count for the mode");
  if (n < 2 || !list) return;
  const enum ImgType types[3] = {IT_DISTANCE, IT_AMPLITUDE, IT_CONF_MAP};
  for (int i = 0; i < n && i < 3; ++i) {
    check(list[i].imgType == types[i], "GetImageList", "image type");
    check(list[i].dataType == DT_USHORT, "GetImageList", "data type is not unsigned short");
    check(list[i].width == COLS && list[i].height == ROWS, "GetImageList", "image size is not 176 x 144");
    check(list[i].data != NULL, "GetImageList", "image without data");
    check(SR_GetImage(cam, (unsigned char)i) == list[i].data, "GetImage", "pointer differs from the list");
  }
  check(list[0].data != list[1].data, "GetImageList", "distance and amplitude share a buffer");
  if (!with_conf) check(SR_GetImage(cam, 2) == NULL, "GetImage", "a confidence map without AM_CONF_MAP");
}

/* Cartesian coordinates against the raw distance and the intrinsics. */
static void checkPoint(const char* what, double x, double y, double z, int px, unsigned short raw,
                       double tol) {
  char msg[160];
  const int u = px % COLS, v = px / COLS;
  if (raw == 0) {
    snprintf(msg, sizeof msg, "pixel %d has no distance but (%g, %g, %g)", px, x, y, z);
    check(x == 0 && y == 0 && z == 0, what, msg);
    return;
  }
  const double d = raw / 65535.0 * kRange30;
  const double r = sqrt(x * x + y * y + z * z);
  snprintf(msg, sizeof msg, "pixel %d: |p| %.4f m, distance %.4f m", px, r, d);
  check(fabs(r - d) < tol, what, msg);
  /* x left, y up, z forward: the ray through the pixel centre. */
  const double ex = -(u + 0.5 - kCx) / kFx, ey = -(v + 0.5 - kCy) / kFy;
  snprintf(msg, sizeof msg, "pixel %d: x/z %.5f y/z %.5f, ray %.5f %.5f", px, x / z, y / z, ex, ey);
  check(z > 0 && fabs(x / z - ex) < tol / d + 1e-4 && fabs(y / z - ey) < tol / d + 1e-4, what, msg);
}

int main(int argc, char** argv) {
  const int eth = argc == 3 && strcmp(argv[1], "eth") == 0;
  if (!(argc == 2 && strcmp(argv[1], "usb") == 0) && !eth) {
    fprintf(stderr, "usage: %s usb | eth ADDRESS\n", argv[0]);
    return 2;
  }
  char msg[200];

  /* 1 SR_GetVersion: printed major.minor.patch.build from version[3] down. */
  unsigned short ver[4] = {0, 0, 0, 0};
  check(SR_GetVersion(ver) == 0, "SR_GetVersion", "did not return 0");
  snprintf(msg, sizeof msg, "%u.%u.%u.%u, not 1.0.14.706", ver[3], ver[2], ver[1], ver[0]);
  check(ver[3] == 1 && ver[2] == 0 && ver[1] == 14 && ver[0] == 706, "SR_GetVersion", msg);

  SR_FuncCB* previous = SR_SetCallback(countingCallback);
  check(previous == SR_GetDefaultCallback(), "SR_SetCallback", "the first call did not return the default");

  /* 2 open */
  SRCAM cam = NULL;
  const int opened = eth ? SR_OpenETH(&cam, argv[2]) : SR_OpenUSB(&cam, 0);
  snprintf(msg, sizeof msg, "returned %d, handle %p", opened, (void*)cam);
  check(opened == 1 && cam != NULL, eth ? "SR_OpenETH" : "SR_OpenUSB", msg);
  if (opened <= 0 || !cam) return 1;

  /* 3 SR_GetDeviceString: the documented format, the length returned. */
  char dev[256];
  memset(dev, 'x', sizeof dev);
  const int len = SR_GetDeviceString(cam, dev, (int)sizeof dev);
  check(len > 0 && len < (int)sizeof dev && (size_t)len == strlen(dev), "SR_GetDeviceString", "length");
  check(strncmp(dev, "VendorID:0x", 11) == 0 && strstr(dev, ", Product:'") != NULL, "SR_GetDeviceString", dev);
  char small[16];
  const int cut = SR_GetDeviceString(cam, small, (int)sizeof small);
  check(cut == (int)strlen(small) && cut < (int)sizeof small, "SR_GetDeviceString", "not cut to the buffer");

  /* 4 SR_SetTimeout (nothing to check: it returns nothing) */
  SR_SetTimeout(cam, 3000);

  /* 5, 6 rows and columns, twice */
  for (int k = 0; k < 2; ++k) {
    check(SR_GetRows(cam) == ROWS, "SR_GetRows", "not 144");
    check(SR_GetCols(cam) == COLS, "SR_GetCols", "not 176");
  }

  /* 7-10 the image list and the images of the mode libMesaSR opens an SR4000 in */
  const int mode0 = SR_GetMode(cam);
  snprintf(msg, sizeof msg, "0x%x, not 0x%x", mode0, AM_COR_FIX_PTRN | AM_CONV_GRAY | AM_DENOISE_ANF);
  check(mode0 == (AM_COR_FIX_PTRN | AM_CONV_GRAY | AM_DENOISE_ANF), "SR_GetMode", msg);
  checkImageList(cam, 0);

  /* 11 SR_SetMode: CM_CHANGING / CM_CHANGED around it, a new image list */
  changing = changed = 0;
  check(SR_SetMode(cam, AM_COR_FIX_PTRN | AM_DENOISE_ANF) == 0, "SR_SetMode", "without AM_CONF_MAP");
  check(SR_GetMode(cam) == (AM_COR_FIX_PTRN | AM_DENOISE_ANF), "SR_GetMode", "not the mode set");
  check(changing == 1 && changed == 1, "SR_SetMode", "callback not told of the buffer change");
  checkImageList(cam, 0);
  changing = 0;
  check(SR_SetMode(cam, AM_COR_FIX_PTRN | AM_DENOISE_ANF) == 0 && changing == 0, "SR_SetMode",
        "the same mode again announced a buffer change");
  const int mode = AM_COR_FIX_PTRN | AM_CONV_GRAY | AM_DENOISE_ANF | AM_CONF_MAP;
  check(SR_SetMode(cam, mode) == 0, "SR_SetMode", "with AM_CONF_MAP");
  checkImageList(cam, 1);

  /* 12 SR_Acquire: distance, amplitude and confidence of the same scene */
  const int bytes = SR_Acquire(cam);
  snprintf(msg, sizeof msg, "returned %d, not %d", bytes, 2 * PIXELS * 2);
  check(bytes == 2 * PIXELS * 2, "SR_Acquire", msg);
  ImgEntry* list = NULL;
  if (SR_GetImageList(cam, &list) < 3 || !list) return 1;
  const unsigned short* dist = (const unsigned short*)list[0].data;
  const unsigned short* amp = (const unsigned short*)list[1].data;
  const unsigned short* conf = (const unsigned short*)list[2].data;
  int with_distance = 0, bad_amp = 0, bad_conf = 0;
  for (int i = 0; i < PIXELS; ++i) {
    with_distance += dist[i] != 0;
    bad_amp += dist[i] != 0 && amp[i] == 0;
    bad_conf += dist[i] == 0 && conf[i] != 0;
  }
  snprintf(msg, sizeof msg, "%d pixels with a distance, %d without amplitude, %d zero ones confident",
           with_distance, bad_amp, bad_conf);
  check(with_distance > PIXELS / 2 && bad_amp == 0 && bad_conf == 0, "SR_Acquire", msg);

  /* 13-15 the whole image: millimetres, then metres in float and double.
   * Float goes into one interleaved buffer (pitch 12), as point clouds are kept. */
  static short xs[PIXELS], ys[PIXELS];
  static unsigned short zs[PIXELS];
  static float xyz[PIXELS][3];
  static double xd[PIXELS], yd[PIXELS], zd[PIXELS];
  check(SR_CoordTrfUint16(cam, xs, ys, zs, 2, 2, 2) == 0, "SR_CoordTrfUint16", "did not return 0");
  check(SR_CoordTrfFlt(cam, &xyz[0][0], &xyz[0][1], &xyz[0][2], 12, 12, 12) == 0, "SR_CoordTrfFlt",
        "did not return 0");
  check(SR_CoordTrfDbl(cam, xd, yd, zd, 8, 8, 8) == 0, "SR_CoordTrfDbl", "did not return 0");
  /* Null outputs are skipped: z alone, as TestBasic asks for it. */
  static unsigned short z_only[PIXELS];
  check(SR_CoordTrfUint16(cam, NULL, NULL, z_only, 2, 2, 2) == 0, "SR_CoordTrfUint16", "z alone refused");
  check(memcmp(z_only, zs, sizeof zs) == 0, "SR_CoordTrfUint16", "z alone differs");
  for (int i = 0; i < PIXELS && failures < 20; ++i) {
    checkPoint("SR_CoordTrfUint16", xs[i] / 1000.0, ys[i] / 1000.0, zs[i] / 1000.0, i, dist[i], 2e-3);
    checkPoint("SR_CoordTrfFlt", xyz[i][0], xyz[i][1], xyz[i][2], i, dist[i], 1e-5);
    checkPoint("SR_CoordTrfDbl", xd[i], yd[i], zd[i], i, dist[i], 1e-9);
  }

  /* 16-18 the per-point variants on a sample of pixels agree with the images */
  enum { N = 97 };
  unsigned char iu[N], iv[N];
  unsigned short id[N];
  for (int k = 0; k < N; ++k) {
    const int px = (k * 2713 + 41) % PIXELS;
    iu[k] = (unsigned char)(px % COLS);
    iv[k] = (unsigned char)(px / COLS);
    id[k] = dist[px];
  }
  short pxs[N], pys[N];
  unsigned short pzs[N];
  float pxf[N], pyf[N], pzf[N];
  double pxd[N], pyd[N], pzd[N];
  check(SR_CoordTrfPntUint16(cam, iu, iv, id, pxs, pys, pzs, N) == 0, "SR_CoordTrfPntUint16", "did not return 0");
  check(SR_CoordTrfPntFlt(cam, iu, iv, id, pxf, pyf, pzf, N) == 0, "SR_CoordTrfPntFlt", "did not return 0");
  check(SR_CoordTrfPntDbl(cam, iu, iv, id, pxd, pyd, pzd, N) == 0, "SR_CoordTrfPntDbl", "did not return 0");
  float z_pnt[N];
  check(SR_CoordTrfPntFlt(cam, iu, iv, id, NULL, NULL, z_pnt, N) == 0, "SR_CoordTrfPntFlt", "z alone refused");
  for (int k = 0; k < N; ++k) {
    const int px = iv[k] * COLS + iu[k];
    check(z_pnt[k] == pzf[k], "SR_CoordTrfPntFlt", "z alone differs");
    check(pxs[k] == xs[px] && pys[k] == ys[px] && pzs[k] == zs[px], "SR_CoordTrfPntUint16", "differs from the image");
    check(pxf[k] == xyz[px][0] && pyf[k] == xyz[px][1] && pzf[k] == xyz[px][2], "SR_CoordTrfPntFlt",
          "differs from the image");
    check(pxd[k] == xd[px] && pyd[k] == yd[px] && pzd[k] == zd[px], "SR_CoordTrfPntDbl", "differs from the image");
  }

  /* 19 registers: a write is read back, the firmware register is kept */
  const unsigned char firmware = SR_GetReg(cam, SR4000_REG_FIRMWARE);
  check(firmware != 0, "SR_GetReg", "no firmware version in register 46");
  const int sent = SR_SetReg(cam, 0x20, 0xA5);
  snprintf(msg, sizeof msg, "returned %d, not the 2 bytes sent", sent);
  check(sent == 2, "SR_SetReg", msg);
  check(SR_GetReg(cam, 0x20) == 0xA5, "SR_GetReg", "not the value written");
  check(SR_GetReg(cam, SR4000_REG_FIRMWARE) == firmware, "SR_GetReg", "firmware register changed");

  /* 20-22 integration time, amplitude threshold, distance offset round trips.
   * The setters return the bytes written to the camera's registers, as
   * libMesaSR's do: one register for the time, two for 16-bit values. */
  const unsigned char t0 = SR_GetIntegrationTime(cam);
  check(SR_SetIntegrationTime(cam, 77) == 2 && SR_GetIntegrationTime(cam) == 77, "IntegrationTime", "77");
  check(SR_SetIntegrationTime(cam, t0) == 2 && SR_GetIntegrationTime(cam) == t0, "IntegrationTime", "restore");
  check(SR_GetAmplitudeThreshold(cam) == 0, "AmplitudeThreshold", "default is not 0");
  check(SR_SetAmplitudeThreshold(cam, 1234) == 4 && SR_GetAmplitudeThreshold(cam) == 1234,
        "AmplitudeThreshold", "1234");
  check(SR_SetAmplitudeThreshold(cam, 0) == 4 && SR_GetAmplitudeThreshold(cam) == 0, "AmplitudeThreshold", "0");
  const unsigned short ofs0 = SR_GetDistanceOffset(cam);
  check(SR_SetDistanceOffset(cam, 321) == 4 && SR_GetDistanceOffset(cam) == 321, "DistanceOffset", "321");
  check(SR_SetDistanceOffset(cam, ofs0) == 4 && SR_GetDistanceOffset(cam) == ofs0, "DistanceOffset", "restore");

  /* 23 auto exposure: MESA's SR4000 values, then off (minIntTime 0xff) */
  check(SR_SetAutoExposure(cam, 1, 150, 5, 70) == 0, "SR_SetAutoExposure", "on");
  check(SR_SetAutoExposure(cam, 0xff, 0, 0, 0) == 0, "SR_SetAutoExposure", "off");

  /* 24 close */
  check(SR_Close(cam) == 0, "SR_Close", "did not return 0");
  SR_SetCallback(previous);

  printf("%s: %s\n", eth ? "eth" : "usb", failures ? "FAILED" : "all checks passed");
  return failures ? 1 : 0;
}
