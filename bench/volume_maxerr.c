/* Largest |a - b| over two raw float32 files of the same size, and how many voxels exceed a
 * bound: the benchmark's own check of every voxel, independent of either codec.
 * Usage: volume_maxerr A.raw B.raw BOUND  ->  prints "max_error exceeding_voxels"
 *        volume_maxerr A.raw              ->  prints "min max" of A */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int range(const char* path) {
  FILE* a = fopen(path, "rb");
  if (!a) {
    fprintf(stderr, "volume_maxerr: cannot open input\n");
    return 2;
  }
  enum { kChunk = 1 << 16 };
  static float x[kChunk];
  float lo = INFINITY, hi = -INFINITY;
  size_t n;
  while ((n = fread(x, sizeof(float), kChunk, a)) > 0)
    for (size_t i = 0; i < n; ++i) {
      if (x[i] < lo) lo = x[i];
      if (x[i] > hi) hi = x[i];
    }
  printf("%.9g %.9g\n", (double)lo, (double)hi);
  return lo <= hi ? 0 : 2;
}

int main(int argc, char** argv) {
  if (argc == 2) return range(argv[1]);
  if (argc != 4) {
    fprintf(stderr, "usage: volume_maxerr A.raw [B.raw BOUND]\n");
    return 2;
  }
  FILE* a = fopen(argv[1], "rb");
  FILE* b = fopen(argv[2], "rb");
  if (!a || !b) {
    fprintf(stderr, "volume_maxerr: cannot open input\n");
    return 2;
  }
  const double bound = atof(argv[3]);
  enum { kChunk = 1 << 16 };
  static float x[kChunk], y[kChunk];
  double worst = 0.0;
  unsigned long long over = 0, total = 0;
  for (;;) {
    const size_t n = fread(x, sizeof(float), kChunk, a);
    if (fread(y, sizeof(float), kChunk, b) != n) {
      fprintf(stderr, "volume_maxerr: files differ in size\n");
      return 2;
    }
    for (size_t i = 0; i < n; ++i) {
      const double e = fabs((double)x[i] - (double)y[i]);
      if (!(e <= worst)) worst = e; /* NaN propagates as a failure */
      if (!(e <= bound)) ++over;
    }
    total += n;
    if (n < kChunk) break;
  }
  printf("%.9g %llu\n", worst, over);
  return total > 0 ? 0 : 2;
}
