/* The C API from a C program (C99): image and volume round trips, every rate mode, levels,
 * description, and bad input turned into error codes with messages. Exits non-zero on the
 * first failed check, naming it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pupwave/pupwave.h"

static int failures = 0;
#define CHECK(cond)                                                            \
  do {                                                                         \
    if (!(cond)) {                                                             \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                              \
    }                                                                          \
  } while (0)

/* A smooth RGB test pattern with some texture, interleaved. */
static unsigned char* make_rgb(size_t w, size_t h) {
  unsigned char* rgb = malloc(w * h * 3);
  size_t x, y, c;
  for (y = 0; y < h; ++y)
    for (x = 0; x < w; ++x)
      for (c = 0; c < 3; ++c)
        rgb[(y * w + x) * 3 + c] =
            (unsigned char)(128 + 100 * sin(0.05 * (double)(x + 7 * c)) * cos(0.07 * (double)y) +
                            (double)((x * 31 + y * 17) % 13));
  return rgb;
}

static void test_image_lossless(void) {
  const size_t w = 67, h = 45;
  unsigned char* rgb = make_rgb(w, h);
  pupwave_options* o = pupwave_options_create();
  pupwave_stream* s = NULL;
  pupwave_decoded* d = NULL;
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_LOSSLESS, 0) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, rgb, PUPWAVE_U8, w, h, 3, 1, 3, (ptrdiff_t)(3 * w), &s) == PUPWAVE_OK);
  CHECK(s && pupwave_stream_size(s) > 0 && pupwave_stream_size(s) < w * h * 3);
  CHECK(pupwave_decompress_image(pupwave_stream_data(s), pupwave_stream_size(s), 0, 1, &d) == PUPWAVE_OK);
  CHECK(d && pupwave_decoded_type(d) == PUPWAVE_U8 && pupwave_decoded_dim(d, 0) == w &&
        pupwave_decoded_dim(d, 1) == h && pupwave_decoded_channels(d) == 3);
  CHECK(d && pupwave_decoded_size(d) == w * h * 3 && memcmp(pupwave_decoded_data(d), rgb, w * h * 3) == 0);
  pupwave_decoded_destroy(d);
  /* The lossless default codes no wavelet levels: level 1 is refused; with levels it is half
   * size, rounded up. */
  d = NULL;
  CHECK(pupwave_decompress_image(pupwave_stream_data(s), pupwave_stream_size(s), 1, 0, &d) != PUPWAVE_OK);
  pupwave_stream_destroy(s);
  s = NULL;
  CHECK(pupwave_options_set_levels(o, 3) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, rgb, PUPWAVE_U8, w, h, 3, 1, 3, (ptrdiff_t)(3 * w), &s) == PUPWAVE_OK);
  CHECK(pupwave_decompress_image(pupwave_stream_data(s), pupwave_stream_size(s), 0, 1, &d) == PUPWAVE_OK);
  CHECK(d && memcmp(pupwave_decoded_data(d), rgb, w * h * 3) == 0);
  pupwave_decoded_destroy(d);
  CHECK(pupwave_decompress_image(pupwave_stream_data(s), pupwave_stream_size(s), 1, 0, &d) == PUPWAVE_OK);
  CHECK(d && pupwave_decoded_dim(d, 0) == 34 && pupwave_decoded_dim(d, 1) == 23);
  pupwave_decoded_destroy(d);
  pupwave_stream_destroy(s);
  pupwave_options_destroy(o);
  free(rgb);
}

static void test_image_rates(void) {
  const size_t w = 128, h = 96;
  unsigned char* rgb = make_rgb(w, h);
  pupwave_options* o = pupwave_options_create();
  pupwave_stream* s = NULL;
  size_t small, large;
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_BPP, 1.0) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, rgb, PUPWAVE_U8, w, h, 3, 1, 3, 0, &s) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(strlen(pupwave_last_error()) > 0); /* zero row stride with height > 1 is not readable */
  CHECK(pupwave_compress_image(o, rgb, PUPWAVE_U8, w, h, 3, 1, 3, (ptrdiff_t)(3 * w), &s) == PUPWAVE_OK);
  small = pupwave_stream_size(s);
  CHECK(small * 8 <= w * h + 64);
  CHECK(pupwave_stream_data(s)[5 + 8 + 15] == 4); /* the default coder for a small image: pc */
  pupwave_stream_destroy(s);
  CHECK(pupwave_options_set_effort(o, 3) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(pupwave_options_set_effort(o, 2) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, rgb, PUPWAVE_U8, w, h, 3, 1, 3, (ptrdiff_t)(3 * w), &s) ==
        PUPWAVE_ERROR_ARGUMENT);
  CHECK(strstr(pupwave_last_error(), "ebcot") != NULL); /* effort 2 is the bit-plane coder's */
  CHECK(pupwave_options_set_coder(o, PUPWAVE_CODER_EBCOT) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, rgb, PUPWAVE_U8, w, h, 3, 1, 3, (ptrdiff_t)(3 * w), &s) == PUPWAVE_OK);
  CHECK(pupwave_stream_size(s) * 8 <= w * h + 64); /* effort 2 keeps the budget too */
  CHECK(pupwave_stream_data(s)[5 + 8 + 15] == 0);  /* the bit-plane coder */
  pupwave_stream_destroy(s);
  CHECK(pupwave_options_set_coder(o, PUPWAVE_CODER_AUTO) == PUPWAVE_OK);
  CHECK(pupwave_options_set_effort(o, 1) == PUPWAVE_OK);
  /* Visual tuning keeps the budget and gives a stream the decoder reads. */
  CHECK(pupwave_options_set_tune(o, (pupwave_tune)2) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(pupwave_options_set_tune(o, PUPWAVE_TUNE_VISUAL) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, rgb, PUPWAVE_U8, w, h, 3, 1, 3, (ptrdiff_t)(3 * w), &s) == PUPWAVE_OK);
  CHECK(pupwave_stream_size(s) * 8 <= w * h + 64);
  {
    pupwave_decoded* d = NULL;
    CHECK(pupwave_decompress_image(pupwave_stream_data(s), pupwave_stream_size(s), 0, 1, &d) == PUPWAVE_OK);
    CHECK(d && pupwave_decoded_dim(d, 0) == w && pupwave_decoded_channels(d) == 3);
    pupwave_decoded_destroy(d);
  }
  pupwave_stream_destroy(s);
  CHECK(pupwave_options_set_tune(o, PUPWAVE_TUNE_PSNR) == PUPWAVE_OK);
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_STEP, 1.0) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, rgb, PUPWAVE_U8, w, h, 3, 1, 3, (ptrdiff_t)(3 * w), &s) == PUPWAVE_OK);
  large = pupwave_stream_size(s);
  CHECK(large > small);
  pupwave_stream_destroy(s);
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_PSNR, 45) == PUPWAVE_OK);
  /* Each coder by its enumerator; the stream's coder byte says which wrote it (docs/bitstream.md). */
  {
    const pupwave_coder coders[] = {PUPWAVE_CODER_HT, PUPWAVE_CODER_PC};
    const uint8_t stored[] = {2, 4};
    for (int i = 0; i < 2; ++i) {
      CHECK(pupwave_options_set_coder(o, coders[i]) == PUPWAVE_OK);
      CHECK(pupwave_compress_image(o, rgb, PUPWAVE_U8, w, h, 3, 1, 3, (ptrdiff_t)(3 * w), &s) == PUPWAVE_OK);
      CHECK(s && pupwave_stream_size(s) > 15 && pupwave_stream_data(s)[5 + 8 + 15] == stored[i]);
      pupwave_stream_destroy(s);
    }
  }
  CHECK(pupwave_options_set_coder(o, PUPWAVE_CODER_LC) == PUPWAVE_OK); /* lossless only */
  CHECK(pupwave_compress_image(o, rgb, PUPWAVE_U8, w, h, 3, 1, 3, (ptrdiff_t)(3 * w), &s) != PUPWAVE_OK);
  CHECK(strstr(pupwave_last_error(), "lossless") != NULL);
  CHECK(pupwave_options_set_coder(o, (pupwave_coder)5) == PUPWAVE_ERROR_ARGUMENT); /* past HT */
  /* The names: the same as the CLI's --entropy and Python's entropy=. */
  {
    pupwave_coder c = PUPWAVE_CODER_AUTO;
    CHECK(pupwave_coder_from_name("PC", &c) == PUPWAVE_OK && c == PUPWAVE_CODER_PC);
    CHECK(pupwave_coder_from_name("auto", &c) == PUPWAVE_OK && c == PUPWAVE_CODER_AUTO);
    CHECK(pupwave_coder_from_name("jpeg", &c) == PUPWAVE_ERROR_ARGUMENT);
    CHECK(strstr(pupwave_last_error(), "auto, ebcot, pc, lc, ht") != NULL);
    CHECK(strcmp(pupwave_coder_name(PUPWAVE_CODER_LC), "lc") == 0);
    CHECK(strcmp(pupwave_coder_name(PUPWAVE_CODER_EBCOT), "ebcot") == 0);
    CHECK(pupwave_coder_name((pupwave_coder)5) == NULL);
  }
  pupwave_options_destroy(o);
  free(rgb);
}

/* testimages/wmag91.float (91^3 float32): the max-error bound holds on every voxel. */
static void test_volume_max_error(void) {
  const size_t n = 91, count = 91 * 91 * 91;
  const double bound = 2.65; /* 1e-2 of the value range */
  float* v = malloc(count * sizeof(float));
  float* back = malloc(count * sizeof(float));
  FILE* f = fopen(PUPWAVE_TESTIMAGES_DIR "/wmag91.float", "rb");
  pupwave_options* o = pupwave_options_create();
  pupwave_stream* s = NULL;
  size_t i, dims[3] = {0, 0, 0};
  double worst = 0;
  int kind = -1, levels = -1;
  pupwave_type type = PUPWAVE_U8;
  char text[512];
  size_t length = 0;
  CHECK(f != NULL);
  if (!f) return;
  CHECK(fread(v, sizeof(float), count, f) == count);
  fclose(f);
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_MAX_ERROR, bound) == PUPWAVE_OK);
  CHECK(pupwave_compress_volume(o, v, PUPWAVE_F32, n, n, n, &s) == PUPWAVE_OK);
  CHECK(s && pupwave_stream_size(s) < count * sizeof(float) / 8);
  CHECK(pupwave_describe_dims(pupwave_stream_data(s), pupwave_stream_size(s), &kind, dims, &type, &levels) ==
        PUPWAVE_OK);
  CHECK(kind == 1 && dims[0] == n && dims[1] == n && dims[2] == n && type == PUPWAVE_F32 && levels > 0);
  CHECK(pupwave_describe(pupwave_stream_data(s), pupwave_stream_size(s), text, sizeof text, &length) ==
        PUPWAVE_OK);
  CHECK(length > 0 && strstr(text, "volume") != NULL);
  CHECK(pupwave_decompress_volume_into(pupwave_stream_data(s), pupwave_stream_size(s), 0, 0, back,
                                       count * sizeof(float)) == PUPWAVE_OK);
  for (i = 0; i < count; ++i)
    if (fabs((double)back[i] - (double)v[i]) > worst) worst = fabs((double)back[i] - (double)v[i]);
  CHECK(worst <= bound);
  CHECK(worst > 0.0);
  /* A wrong buffer size is refused, nothing written past it. */
  CHECK(pupwave_decompress_volume_into(pupwave_stream_data(s), pupwave_stream_size(s), 0, 0, back, 100) ==
        PUPWAVE_ERROR_ARGUMENT);
  pupwave_stream_destroy(s);
  pupwave_options_destroy(o);
  free(v);
  free(back);
}

/* Whether the target was met, and what was reached: crops of testimages/wmag91.float (a real
 * field) too small for their budget miss it; the whole field meets the same budgets. */
static void test_target_outcome(void) {
  const size_t n = 91, count = 91 * 91 * 91;
  const float* slice; /* plane z = 45 as a 91x91 float image */
  float* v = malloc(count * sizeof(float));
  float cube[8];
  FILE* f = fopen(PUPWAVE_TESTIMAGES_DIR "/wmag91.float", "rb");
  pupwave_options* o = pupwave_options_create();
  pupwave_stream* s = NULL;
  size_t i;
  CHECK(f != NULL);
  if (!f) return;
  CHECK(fread(v, sizeof(float), count, f) == count);
  fclose(f);
  slice = v + 45 * n * n;
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_BPP, 2.0) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, slice, PUPWAVE_F32, n, n, 1, 1, 1, (ptrdiff_t)n, &s) == PUPWAVE_OK);
  CHECK(pupwave_stream_target_met(s) == 1 && strcmp(pupwave_stream_target_miss(s), "") == 0);
  CHECK(fabs(pupwave_stream_achieved(s) - 8.0 * (double)pupwave_stream_size(s) / (double)(n * n)) < 1e-9);
  CHECK(pupwave_stream_achieved(s) <= 2.0);
  pupwave_stream_destroy(s);
  /* A 2x2 crop: the stream's header alone exceeds 1 bit per pixel; the stream still comes back. */
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_BPP, 1.0) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, slice + 40 * n + 40, PUPWAVE_F32, 2, 2, 1, 1, 1, (ptrdiff_t)n, &s) ==
        PUPWAVE_OK);
  CHECK(s && pupwave_stream_size(s) > 0 && pupwave_stream_target_met(s) == 0);
  CHECK(fabs(pupwave_stream_achieved(s) - 8.0 * (double)pupwave_stream_size(s) / 4.0) < 1e-9);
  /* The text of the CLI's `warning:` line for it. */
  CHECK(strncmp(pupwave_stream_target_miss(s), "--bpp 1 not met: the stream is ", 31) == 0);
  CHECK(strstr(pupwave_stream_target_miss(s),
               " bpp) for this 2x2 image; its header and chunk framing alone take ") != NULL);
  pupwave_stream_destroy(s);
  /* A step sets no target to miss. */
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_STEP, 0.5) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, slice, PUPWAVE_F32, n, n, 1, 1, 1, (ptrdiff_t)n, &s) == PUPWAVE_OK);
  CHECK(pupwave_stream_target_met(s) == 1 && isnan(pupwave_stream_achieved(s)));
  pupwave_stream_destroy(s);
  /* Volumes: the field at 2 bits per voxel, a 2^3 crop of it that cannot meet 1. */
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_BPV, 2.0) == PUPWAVE_OK);
  CHECK(pupwave_compress_volume(o, v, PUPWAVE_F32, n, n, n, &s) == PUPWAVE_OK);
  CHECK(pupwave_stream_target_met(s) == 1 && pupwave_stream_achieved(s) <= 2.0);
  pupwave_stream_destroy(s);
  for (i = 0; i < 8; ++i) cube[i] = v[40 + (i & 1) + n * (40 + ((i >> 1) & 1) + n * (40 + (i >> 2)))];
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_BPV, 1.0) == PUPWAVE_OK);
  CHECK(pupwave_compress_volume(o, cube, PUPWAVE_F32, 2, 2, 2, &s) == PUPWAVE_OK);
  CHECK(s && pupwave_stream_target_met(s) == 0);
  CHECK(fabs(pupwave_stream_achieved(s) - 8.0 * (double)pupwave_stream_size(s) / 8.0) < 1e-9);
  CHECK(strncmp(pupwave_stream_target_miss(s), "--bpv 1 not met: the stream is ", 31) == 0);
  pupwave_stream_destroy(s);
  /* An error bound is guaranteed: met, and the error reached is within it. */
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_MAX_ERROR_REL, 1e-2) == PUPWAVE_OK);
  CHECK(pupwave_compress_volume(o, v, PUPWAVE_F32, n, n, n, &s) == PUPWAVE_OK);
  CHECK(pupwave_stream_target_met(s) == 1);
  CHECK(pupwave_stream_achieved(s) > 0.0 && pupwave_stream_achieved(s) <= 1e-2);
  pupwave_stream_destroy(s);
  CHECK(pupwave_stream_target_met(NULL) == 0 && isnan(pupwave_stream_achieved(NULL)));
  CHECK(strcmp(pupwave_stream_target_miss(NULL), "") == 0);
  pupwave_options_destroy(o);
  free(v);
}

static void test_volume_double_levels(void) {
  const size_t nx = 20, ny = 17, nz = 9, count = 20 * 17 * 9;
  double* v = malloc(count * sizeof(double));
  pupwave_stream* s = NULL;
  pupwave_decoded* d = NULL;
  size_t i;
  for (i = 0; i < count; ++i) v[i] = sin(0.1 * (double)i) * 1000.0;
  CHECK(pupwave_compress_volume(NULL, v, PUPWAVE_F64, nx, ny, nz, &s) == PUPWAVE_OK);
  CHECK(pupwave_decompress_volume(pupwave_stream_data(s), pupwave_stream_size(s), 1, 0, &d) == PUPWAVE_OK);
  CHECK(d && pupwave_decoded_type(d) == PUPWAVE_F64 && pupwave_decoded_dim(d, 0) == 10 &&
        pupwave_decoded_dim(d, 1) == 9 && pupwave_decoded_dim(d, 2) == 5);
  pupwave_decoded_destroy(d);
  pupwave_stream_destroy(s);
  free(v);
}

/* A sparse grid from two bricks (one with a mask): inactive voxels come back exactly. */
static void test_sparse_bricks(void) {
  float a[4 * 4 * 4], b[2 * 2 * 2];
  uint8_t mask[8] = {1, 1, 1, 0, 1, 1, 1, 1};
  pupwave_brick bricks[2] = {{{10, 0, 0}, {4, 4, 4}, NULL, NULL}, {{20, 2, 2}, {2, 2, 2}, NULL, NULL}};
  pupwave_options* o = pupwave_options_create();
  pupwave_stream* s = NULL;
  pupwave_decoded* d = NULL;
  const float* v;
  const uint8_t* active;
  size_t i, nx;
  for (i = 0; i < 64; ++i) a[i] = (float)sin(0.3 * (double)i);
  for (i = 0; i < 8; ++i) b[i] = 5.0f + (float)i;
  bricks[0].data = a;
  bricks[1].data = b;
  bricks[1].active = mask;
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_MAX_ERROR, 1e-3) == PUPWAVE_OK);
  CHECK(pupwave_compress_sparse_volume(o, bricks, 2, PUPWAVE_F32, -1.0, &s) == PUPWAVE_OK);
  CHECK(pupwave_decompress_volume(pupwave_stream_data(s), pupwave_stream_size(s), 0, 0, &d) == PUPWAVE_OK);
  if (!d) return;
  nx = pupwave_decoded_dim(d, 0);
  CHECK(nx == 12 && pupwave_decoded_dim(d, 1) == 4 && pupwave_decoded_dim(d, 2) == 4);
  CHECK(pupwave_decoded_origin(d, 0) == 10 && pupwave_decoded_origin(d, 1) == 0);
  v = pupwave_decoded_data(d);
  active = pupwave_decoded_active(d);
  CHECK(active != NULL);
  if (active) {
    CHECK(active[0] == 1 && fabs(v[0] - a[0]) <= 1e-3);
    CHECK(active[5] == 0 && v[5] == -1.0f);                                         /* between the bricks */
    CHECK(active[10 + nx * (2 + 4 * 2)] == 1);                                      /* b's voxel (0, 0, 0) */
    CHECK(active[11 + nx * (3 + 4 * 2)] == 0 && v[11 + nx * (3 + 4 * 2)] == -1.0f); /* mask[3] */
  }
  pupwave_decoded_destroy(d);
  pupwave_stream_destroy(s);
  CHECK(pupwave_compress_sparse_volume(o, bricks, 0, PUPWAVE_F32, 0.0, &s) == PUPWAVE_ERROR_ARGUMENT);
  bricks[1].origin[0] = 12; /* overlaps the first brick */
  CHECK(pupwave_compress_sparse_volume(o, bricks, 2, PUPWAVE_F32, 0.0, &s) == PUPWAVE_ERROR_ARGUMENT);
  pupwave_options_destroy(o);
}

static void test_bad_input(void) {
  unsigned char junk[64];
  float one = 1.0f;
  pupwave_stream* s = NULL;
  pupwave_decoded* d = NULL;
  pupwave_options* o = pupwave_options_create();
  size_t i;
  for (i = 0; i < sizeof junk; ++i) junk[i] = (unsigned char)(i * 37);
  memcpy(junk, "PUPW", 4);
  CHECK(pupwave_decompress_image(junk, sizeof junk, 0, 0, &d) == PUPWAVE_ERROR_CORRUPT && d == NULL);
  CHECK(strlen(pupwave_last_error()) > 0);
  CHECK(pupwave_decompress_volume(junk, sizeof junk, 0, 0, &d) == PUPWAVE_ERROR_CORRUPT);
  CHECK(pupwave_decompress_image(NULL, 0, 0, 0, &d) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_BPP, -1.0) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(pupwave_options_set_rate(o, (pupwave_rate)99, 1.0) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(pupwave_options_set_levels(o, 1000) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(pupwave_compress_image(o, &one, PUPWAVE_F64, 1, 1, 1, 1, 1, 1, &s) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(pupwave_compress_image(o, NULL, PUPWAVE_U8, 4, 4, 1, 16, 1, 4, &s) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(pupwave_compress_image(o, &one, PUPWAVE_U8, 0, 0, 1, 1, 1, 1, &s) != PUPWAVE_OK && s == NULL);
  CHECK(pupwave_compress_volume(o, &one, PUPWAVE_F32, 0, 1, 1, &s) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(pupwave_compress_volume(o, &one, PUPWAVE_F16, 1, 1, 1, &s) == PUPWAVE_ERROR_ARGUMENT);
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_LOSSLESS, 0) == PUPWAVE_OK);
  CHECK(pupwave_compress_volume(o, &one, PUPWAVE_F32, 1, 1, 1, &s) != PUPWAVE_OK);
  CHECK(strlen(pupwave_last_error()) > 0);
  CHECK(pupwave_options_set_transform(o, "no-such-transform") == PUPWAVE_OK);
  CHECK(pupwave_options_set_rate(o, PUPWAVE_RATE_PSNR, 30) == PUPWAVE_OK);
  CHECK(pupwave_compress_image(o, &one, PUPWAVE_F32, 1, 1, 1, 1, 1, 1, &s) != PUPWAVE_OK && s == NULL);
  pupwave_options_destroy(o);
  pupwave_options_destroy(NULL);
  pupwave_stream_destroy(NULL);
  pupwave_decoded_destroy(NULL);
}

int main(void) {
  printf("%s\n", pupwave_version());
  test_image_lossless();
  test_image_rates();
  test_volume_max_error();
  test_target_outcome();
  test_volume_double_levels();
  test_sparse_bricks();
  test_bad_input();
  if (failures)
    fprintf(stderr, "%d check(s) failed\n", failures);
  else
    printf("all C API checks passed\n");
  return failures ? 1 : 0;
}
