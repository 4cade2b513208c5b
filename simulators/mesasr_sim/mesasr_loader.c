/* libmesasr.so of libmesasr-sim: the SR_* entry points, forwarded to the
 * simulator (libmesasr-sim-core.so, C++ and Embree), loaded on first use.
 *
 * Why a loader: old single-threaded programs, MESA's own libMesaSRTester among
 * them, define do-nothing pthread_mutex_init/lock/unlock of their own. An
 * executable's definitions come first in the process's symbol scope, so every
 * library loaded with it would get those, and Embree's scene commit, which
 * mixes them with the C library's pthread_mutex_trylock on a mutex that was
 * never initialised, spins for ever. When the host replaces them, the core is
 * loaded with RTLD_DEEPBIND, so that it and the libraries it brings (Embree,
 * TBB) bind to the C library first. Other hosts load it as any library. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "keyturn/drivers/mesasr_api.h"

#define SIM_EXPORT __attribute__((visibility("default")))

#define CORE_NAME "libmesasr-sim-core.so"

/* AddressSanitizer refuses RTLD_DEEPBIND: under it the core is always loaded plainly. */
#if defined(__SANITIZE_ADDRESS__)
#define LOADER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LOADER_ASAN 1
#endif
#endif

static pthread_once_t g_once = PTHREAD_ONCE_INIT;
static void* g_core;

/* Does the host define the mutex calls that the C library should provide? */
static int hostReplacesMutexes(void) {
#ifdef LOADER_ASAN
  return 0;
#else
  static const char* const names[] = {"pthread_mutex_init", "pthread_mutex_lock", "pthread_mutex_unlock",
                                      "pthread_mutex_trylock", "pthread_mutex_destroy"};
  void* libc = dlopen("libc.so.6", RTLD_LAZY | RTLD_NOLOAD);
  if (!libc) return 0;
  int replaced = 0;
  for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
    if (dlsym(RTLD_DEFAULT, names[i]) != dlsym(libc, names[i])) replaced = 1;
  dlclose(libc);
  return replaced;
#endif
}

static void loadCore(void) {
  const int flags = RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE | (hostReplacesMutexes() ? RTLD_DEEPBIND : 0);
  char beside[PATH_MAX + sizeof CORE_NAME] = "";
  char real[PATH_MAX];
  Dl_info self;
  if (dladdr((void*)&loadCore, &self) && self.dli_fname && realpath(self.dli_fname, real)) {
    char* slash = strrchr(real, '/');
    if (slash) {
      slash[1] = '\0';
      snprintf(beside, sizeof beside, "%s%s", real, CORE_NAME);
    }
  }
  /* The core beside this file, symbolic links followed (built and installed side by side). */
  const char* path = beside[0] ? beside : CORE_NAME;
  g_core = dlopen(path, flags);
  if (!g_core) fprintf(stderr, "libmesasr-sim: cannot load the simulator %s: %s\n", path, dlerror());
}

static void* coreSymbol(const char* name) {
  pthread_once(&g_once, loadCore);
  if (!g_core) return NULL;
  void* f = dlsym(g_core, name);
  if (!f) fprintf(stderr, "libmesasr-sim: %s lacks %s\n", CORE_NAME, name);
  return f;
}

/* One forwarder per function: its pointer is looked up once; without the core
 * each returns the value libMesaSR returns on failure. */
#define FORWARD(ret, name, params, args, failed)                     \
  SIM_EXPORT ret name params {                                       \
    typedef ret(*Fn) params;                                         \
    static Fn fn;                                                    \
    Fn impl = __atomic_load_n(&fn, __ATOMIC_ACQUIRE);                \
    if (!impl) {                                                     \
      impl = (Fn)coreSymbol(#name);                                  \
      if (!impl) return failed;                                      \
      __atomic_store_n(&fn, impl, __ATOMIC_RELEASE);                 \
    }                                                                \
    return impl args;                                                \
  }

typedef const unsigned char* CU8;
typedef const unsigned short* CU16;

FORWARD(int, SR_OpenUSB, (SRCAM* c, unsigned int serial), (c, serial), -1)
FORWARD(int, SR_OpenETH, (SRCAM* c, const char* addr), (c, addr), -1)
FORWARD(int, SR_OpenDlg, (SRCAM* c, int mode, int parent), (c, mode, parent), -1)
FORWARD(int, SR_Close, (SRCAM c), (c), -1)
FORWARD(int, SR_Acquire, (SRCAM c), (c), -1)
FORWARD(void*, SR_GetImage, (SRCAM c, unsigned char idx), (c, idx), NULL)
FORWARD(int, SR_GetImageList, (SRCAM c, ImgEntry** list), (c, list), -1)
FORWARD(unsigned int, SR_GetRows, (SRCAM c), (c), 0)
FORWARD(unsigned int, SR_GetCols, (SRCAM c), (c), 0)
FORWARD(int, SR_SetMode, (SRCAM c, int mode), (c, mode), -1)
FORWARD(int, SR_GetMode, (SRCAM c), (c), -1)
FORWARD(int, SR_SetIntegrationTime, (SRCAM c, unsigned char t), (c, t), -1)
FORWARD(unsigned char, SR_GetIntegrationTime, (SRCAM c), (c), 0)
FORWARD(int, SR_SetModulationFrequency, (SRCAM c, enum ModulationFrq f), (c, f), -1)
FORWARD(enum ModulationFrq, SR_GetModulationFrequency, (SRCAM c), (c), MF_30MHz)
FORWARD(int, SR_SetAmplitudeThreshold, (SRCAM c, unsigned short v), (c, v), -1)
FORWARD(unsigned short, SR_GetAmplitudeThreshold, (SRCAM c), (c), 0)
FORWARD(int, SR_SetAutoExposure,
        (SRCAM c, unsigned char mn, unsigned char mx, unsigned char pct, unsigned char pos),
        (c, mn, mx, pct, pos), -1)
FORWARD(int, SR_SetDistanceOffset, (SRCAM c, unsigned short ofs), (c, ofs), -1)
FORWARD(unsigned short, SR_GetDistanceOffset, (SRCAM c), (c), 0)
FORWARD(int, SR_GetDeviceString, (SRCAM c, char* buf, int len), (c, buf, len), -1)
FORWARD(unsigned int, SR_ReadSerial, (SRCAM c), (c), 0)
FORWARD(int, SR_GetVersion, (unsigned short version[4]), (version), -1)
FORWARD(unsigned char, SR_GetReg, (SRCAM c, unsigned char reg), (c, reg), 0)
FORWARD(int, SR_SetReg, (SRCAM c, unsigned char reg, unsigned char val), (c, reg, val), -1)
FORWARD(SR_FuncCB*, SR_SetCallback, (SR_FuncCB * cb), (cb), NULL)
FORWARD(SR_FuncCB*, SR_GetDefaultCallback, (void), (), NULL)
FORWARD(int, SR_CoordTrfFlt, (SRCAM c, float* x, float* y, float* z, int px, int py, int pz),
        (c, x, y, z, px, py, pz), -1)
FORWARD(int, SR_CoordTrfDbl, (SRCAM c, double* x, double* y, double* z, int px, int py, int pz),
        (c, x, y, z, px, py, pz), -1)
FORWARD(int, SR_CoordTrfUint16,
        (SRCAM c, short* x, short* y, unsigned short* z, int px, int py, int pz),
        (c, x, y, z, px, py, pz), -1)
FORWARD(int, SR_CoordTrfPntFlt, (SRCAM c, CU8 ix, CU8 iy, CU16 d, float* x, float* y, float* z, int n),
        (c, ix, iy, d, x, y, z, n), -1)
FORWARD(int, SR_CoordTrfPntDbl, (SRCAM c, CU8 ix, CU8 iy, CU16 d, double* x, double* y, double* z, int n),
        (c, ix, iy, d, x, y, z, n), -1)
FORWARD(int, SR_CoordTrfPntUint16,
        (SRCAM c, CU8 ix, CU8 iy, CU16 d, short* x, short* y, unsigned short* z, int n),
        (c, ix, iy, d, x, y, z, n), -1)
FORWARD(int, SR_TCPSend, (SRCAM c, void* buf, int len, int flags), (c, buf, len, flags), -1)
/* keyturn's extension (mesasr_api.h): a camera opened with its own configuration file. */
FORWARD(int, KTSIM_OpenWithConfig, (SRCAM* c, const char* config), (c, config), -1)
FORWARD(int, SR_TCPRecv, (SRCAM c, void* buf, int len, int flags), (c, buf, len, flags), -1)

SIM_EXPORT void SR_SetTimeout(SRCAM c, int ms) {  /* the one without a result */
  typedef void (*Fn)(SRCAM, int);
  static Fn fn;
  Fn impl = __atomic_load_n(&fn, __ATOMIC_ACQUIRE);
  if (!impl) {
    impl = (Fn)coreSymbol("SR_SetTimeout");
    if (!impl) return;
    __atomic_store_n(&fn, impl, __ATOMIC_RELEASE);
  }
  impl(c, ms);
}
