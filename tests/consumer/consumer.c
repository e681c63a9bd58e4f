/* Downstream use of the installed C API (built with pkg-config): `consumer_c VOLUME.f32 NX NY NZ`
 * compresses the volume with a max-error bound and checks the decoded voxels. */
#include <math.h>
#include <pupwave/pupwave.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char** argv) {
  size_t nx, ny, nz, count, i;
  float *v, *back;
  double worst = 0;
  FILE* f;
  pupwave_options* o;
  pupwave_stream* s = NULL;
  if (argc != 5) return fprintf(stderr, "usage: consumer_c VOLUME.f32 NX NY NZ\n"), 2;
  nx = strtoul(argv[2], NULL, 10), ny = strtoul(argv[3], NULL, 10), nz = strtoul(argv[4], NULL, 10);
  count = nx * ny * nz;
  v = malloc(count * sizeof(float)), back = malloc(count * sizeof(float));
  f = fopen(argv[1], "rb");
  if (!f || fread(v, sizeof(float), count, f) != count)
    return fprintf(stderr, "cannot read %s\n", argv[1]), 1;
  fclose(f);
  o = pupwave_options_create();
  if (pupwave_options_set_rate(o, PUPWAVE_RATE_MAX_ERROR, 0.1) != PUPWAVE_OK ||
      pupwave_compress_volume(o, v, PUPWAVE_F32, nx, ny, nz, &s) != PUPWAVE_OK ||
      pupwave_decompress_volume_into(pupwave_stream_data(s), pupwave_stream_size(s), 0, 0, back,
                                     count * sizeof(float)) != PUPWAVE_OK)
    return fprintf(stderr, "pupwave: error: %s\n", pupwave_last_error()), 1;
  for (i = 0; i < count; ++i)
    if (fabs((double)back[i] - v[i]) > worst) worst = fabs((double)back[i] - v[i]);
  printf("%s: volume %zu bytes, max error %.4g (bound 0.1)\n", pupwave_version(), pupwave_stream_size(s),
         worst);
  pupwave_stream_destroy(s);
  pupwave_options_destroy(o);
  free(v), free(back);
  return worst <= 0.1 ? 0 : 1;
}
