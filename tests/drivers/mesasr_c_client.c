/* A plain C program written against libMesaSR, linked with -lmesasr: it runs
 * unchanged against libmesasr-sim. Exits 0 when a frame arrives as the SR4000
 * delivers it. */
#include <stdio.h>

#include "keyturn/drivers/mesasr_api.h"

int main(void) {
  SRCAM cam = 0;
  if (SR_OpenUSB(&cam, 0) <= 0) { fprintf(stderr, "open failed\n"); return 1; }
  char dev[256];
  SR_GetDeviceString(cam, dev, sizeof dev);
  int bytes = SR_Acquire(cam);
  ImgEntry* list = 0;
  int n = SR_GetImageList(cam, &list);
  unsigned short* dist = (unsigned short*)SR_GetImage(cam, 0);
  int nonzero = 0;
  for (int i = 0; i < 176 * 144; ++i) nonzero += dist[i] != 0;
  printf("%s: %d bytes, %d images, %ux%u, %d pixels with a distance\n", dev, bytes, n,
         SR_GetCols(cam), SR_GetRows(cam), nonzero);
  SR_Close(cam);
  /* Two images: libMesaSR opens an SR4000 without the confidence map. */
  return bytes == 2 * 176 * 144 * 2 && n == 2 && nonzero > 20000 ? 0 : 1;
}
