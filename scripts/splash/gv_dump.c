/* globalvis measurement hook for SPLASH-3 RADIOSITY (not part of SPLASH; written for globalvis).
 * Linked into the RADIOSITY binary by build.sh. After a batch run, when the environment variable
 * GV_SPLASH_DUMP names a file, writes one line per patch (SPLASH's input triangles):
 *   x1 y1 z1 x2 y2 z2 x3 y3 z3  reflectance r g b  emittance r g b  radiosity r g b
 * The radiosity is the root element's: the area average of the patch's elements (B, with Ke).
 * to_obj.py turns the file into an OBJ + MTL scene for globalvis and a radiosity.txt that
 * `globalvis photons --compare` reads. */
#include <stdio.h>
#include <stdlib.h>

#include "radiosity.h"

static FILE* gv_out;

static void gv_dump_patch(Patch* p, long unused_arg, long unused_process) {
  (void)unused_arg;
  (void)unused_process;
  const Rgb b = p->el_root->rad;
  fprintf(gv_out, "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g  %.9g %.9g %.9g  %.9g %.9g %.9g  %.9g %.9g %.9g\n",
          p->p1.x, p->p1.y, p->p1.z, p->p2.x, p->p2.y, p->p2.z, p->p3.x, p->p3.y, p->p3.z,
          p->color.r, p->color.g, p->color.b, p->emittance.r, p->emittance.g, p->emittance.b,
          b.r, b.g, b.b);
}

void gv_dump_patches(void) {
  const char* path = getenv("GV_SPLASH_DUMP");
  if (!path) return;
  gv_out = fopen(path, "w");
  if (!gv_out) {
    perror(path);
    exit(2);
  }
  foreach_patch_in_bsp(gv_dump_patch, 0, 0);
  fclose(gv_out);
}
