/* The pattern of ROS-style SwissRanger drivers, in plain C: a callback of the
 * driver's own set before opening, the camera opened on one thread, frames
 * acquired on a polling thread, closed from a third. Threads hand over with
 * pthread_join, as a node's start/poll/stop calls are ordered.
 * Usage: mesasr_threaded_client usb | eth ADDRESS. Exits 1 if a check failed. */
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "keyturn/drivers/mesasr_api.h"

enum { COLS = 176, ROWS = 144, PIXELS = COLS * ROWS, FRAMES = 8 };
/* The ROS driver's SR4000 mode: confidence map and grey-converted amplitude. */
#define DRIVER_MODE (AM_CONF_MAP | AM_CONV_GRAY)

static SRCAM g_cam;
static const char* g_addr;  /* NULL: USB */
static int g_failures;
static SR_FuncCB* g_default;
static int g_progress, g_changing, g_changed, g_foreign;

static void fail(const char* what) {
  printf("FAILED: %s\n", what);
  ++g_failures;
}

/* Counts what it handles, forwards the rest to the library's default, as documented. */
static int driverCallback(SRCAM cam, unsigned int msg, unsigned int param, void* data) {
  switch (msg) {
    case CM_PROGRESS: ++g_progress; return 0;
    case CM_CHANGING: ++g_changing; g_foreign += cam != g_cam; return 0;
    case CM_CHANGED: ++g_changed; g_foreign += cam != g_cam; return 0;
    default: return g_default ? g_default(cam, msg, param, data) : 0;
  }
}

static void* openCamera(void* arg) {
  (void)arg;
  g_default = SR_GetDefaultCallback();
  SR_SetCallback(driverCallback);
  const int n = g_addr ? SR_OpenETH(&g_cam, g_addr) : SR_OpenUSB(&g_cam, 0);
  if (n <= 0 || !g_cam) {
    fail("open");
    return NULL;
  }
  if (SR_GetRows(g_cam) != ROWS || SR_GetCols(g_cam) != COLS) fail("rows/cols");
  if (SR_SetMode(g_cam, DRIVER_MODE) != 0) fail("SR_SetMode");
  ImgEntry* list = NULL;
  if (SR_GetImageList(g_cam, &list) < 3 || !list) fail("image list has no confidence map");
  if (SR_SetAutoExposure(g_cam, 1, 150, 5, 70) != 0) fail("SR_SetAutoExposure");
  return NULL;
}

static float xp[PIXELS], yp[PIXELS], zp[PIXELS];

static void* pollFrames(void* arg) {
  int* frames = arg;
  for (int k = 0; k < FRAMES; ++k) {
    const int bytes = SR_Acquire(g_cam);
    if (bytes != 2 * PIXELS * 2) {
      printf("FAILED: SR_Acquire returned %d\n", bytes);
      ++g_failures;
      continue;
    }
    /* Images fetched after every acquire, as the driver does. */
    const unsigned short* dist = SR_GetImage(g_cam, 0);
    const unsigned short* amp = SR_GetImage(g_cam, 1);
    const unsigned short* conf = SR_GetImage(g_cam, 2);
    if (!dist || !amp || !conf) {
      fail("SR_GetImage");
      continue;
    }
    if (SR_CoordTrfFlt(g_cam, xp, yp, zp, sizeof(float), sizeof(float), sizeof(float)) != 0) {
      fail("SR_CoordTrfFlt");
      continue;
    }
    int points = 0;
    for (int i = 0; i < PIXELS; ++i) points += dist[i] != 0 && zp[i] > 0.1f && conf[i] > 0;
    if (points < PIXELS / 2) {
      printf("FAILED: frame %d has %d confident points\n", k, points);
      ++g_failures;
    }
    ++*frames;
  }
  return NULL;
}

static void* closeCamera(void* arg) {
  int* result = arg;
  *result = SR_Close(g_cam);
  return NULL;
}

int main(int argc, char** argv) {
  if (argc == 3 && strcmp(argv[1], "eth") == 0) g_addr = argv[2];
  else if (!(argc == 2 && strcmp(argv[1], "usb") == 0)) {
    fprintf(stderr, "usage: %s usb | eth ADDRESS\n", argv[0]);
    return 2;
  }
  pthread_t t;
  int frames = 0, closed = -1;
  if (pthread_create(&t, NULL, openCamera, NULL) != 0 || pthread_join(t, NULL) != 0) return 1;
  if (!g_cam) return 1;
  if (pthread_create(&t, NULL, pollFrames, &frames) != 0 || pthread_join(t, NULL) != 0) return 1;
  if (pthread_create(&t, NULL, closeCamera, &closed) != 0 || pthread_join(t, NULL) != 0) return 1;
  if (frames != FRAMES) fail("not every frame arrived");
  if (closed != 0) fail("SR_Close");
  if (g_progress < 1) fail("no CM_PROGRESS while opening");
  if (g_changing != 1 || g_changed != 1) fail("SR_SetMode not announced once by CM_CHANGING/CM_CHANGED");
  if (g_foreign) fail("callback got a handle other than the camera's");
  if (SR_SetCallback(g_default) != driverCallback) fail("SR_SetCallback did not return the driver's callback");
  printf("%d frames on the polling thread, %d progress, %d/%d mode messages: %s\n", frames, g_progress,
         g_changing, g_changed, g_failures ? "FAILED" : "all checks passed");
  return g_failures ? 1 : 0;
}
