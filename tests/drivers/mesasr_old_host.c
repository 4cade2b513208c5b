/* An old single-threaded program, as MESA's libMesaSRTester is: it defines
 * do-nothing pthread mutex functions of its own (and exports them, as that
 * binary does), which then come first for every library in the process.
 * Before libmesasr-sim loaded its simulator apart, the first SR_Acquire spun
 * for ever in Embree's scene commit. Acquires at three turntable angles (a
 * new scene each) must return the full frame, each a different view.
 * Usage: mesasr_old_host WORK_DIR (created, holds the config and world file). */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "keyturn/drivers/mesasr_api.h"

int pthread_mutex_init(pthread_mutex_t* m, const pthread_mutexattr_t* a) { (void)m, (void)a; return 0; }
int pthread_mutex_lock(pthread_mutex_t* m) { (void)m; return 0; }
int pthread_mutex_unlock(pthread_mutex_t* m) { (void)m; return 0; }

enum { PIXELS = 176 * 144 };

static int writeFile(const char* path, const char* text) {
  FILE* f = fopen(path, "w");
  if (!f || fputs(text, f) < 0 || fclose(f) != 0) {
    fprintf(stderr, "mesasr_old_host: cannot write %s\n", path);
    return 0;
  }
  return 1;
}

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s WORK_DIR\n", argv[0]);
    return 2;
  }
  char config[4096], world[4096], text[4200];
  mkdir(argv[1], 0755);
  snprintf(config, sizeof config, "%s/sim.json", argv[1]);
  snprintf(world, sizeof world, "%s/world.json", argv[1]);
  snprintf(text, sizeof text, "{\"world\": \"%s\"}\n", world);
  if (!writeFile(config, text) || !writeFile(world, "{\"turntable_deg\": 0}\n")) return 1;
  setenv("MESASR_SIM_CONFIG", config, 1);

  SRCAM cam = NULL;
  if (SR_OpenUSB(&cam, 0) != 1 || !cam) {
    printf("FAILED: SR_OpenUSB\n");
    return 1;
  }
  static unsigned short views[3][PIXELS];
  const int angles[3] = {0, 90, 180};
  int failures = 0;
  for (int k = 0; k < 3; ++k) {
    snprintf(text, sizeof text, "{\"turntable_deg\": %d}\n", angles[k]);
    if (!writeFile(world, text)) return 1;
    const int bytes = SR_Acquire(cam);
    const unsigned short* dist = (const unsigned short*)SR_GetImage(cam, 0);
    if (bytes != 2 * PIXELS * 2 || !dist) {
      printf("FAILED: SR_Acquire at %d degrees returned %d\n", angles[k], bytes);
      ++failures;
      continue;
    }
    memcpy(views[k], dist, sizeof views[k]);
    if (k > 0) {
      int changed = 0;
      /* more than noise: 1000 counts are 7.6 cm at 30 MHz */
      for (int i = 0; i < PIXELS; ++i) changed += abs(views[k][i] - views[k - 1][i]) > 1000;
      printf("%d degrees: %d pixels moved from the view at %d degrees\n", angles[k], changed, angles[k - 1]);
      if (changed < 100) ++failures;  /* the object turned: its outline moved */
    }
  }
  if (SR_Close(cam) != 0) ++failures;
  printf("%s\n", failures ? "FAILED" : "three views acquired");
  return failures ? 1 : 0;
}
