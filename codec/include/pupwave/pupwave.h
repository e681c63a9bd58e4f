/* Pupwave's public C API (C99, usable from any FFI): images and dense volumes in, .pw bytes
 * out; bytes in, samples out at any resolution level; stream description. The C++ API is
 * pupwave/pupwave.hpp; docs/api.md has examples.
 *
 * Conventions: every function that can fail returns a pupwave_status (PUPWAVE_OK = 0); on
 * failure pupwave_last_error() gives the library's message for the calling thread (valid until
 * that thread's next call). No exception crosses this interface. Objects are opaque handles
 * created by *_create or returned through an out-parameter and released with their *_destroy
 * function (which accepts NULL).
 *
 * Thread safety: independent calls on different threads are safe; one handle must not be used
 * by two threads at once. Output never depends on the thread count. */
#ifndef PUPWAVE_PUPWAVE_H
#define PUPWAVE_PUPWAVE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum pupwave_status {
  PUPWAVE_OK = 0,
  PUPWAVE_ERROR_ARGUMENT = 1,    /* bad parameter, view or handle */
  PUPWAVE_ERROR_UNSUPPORTED = 2, /* input the format cannot hold (size, channels, NaN, ...) */
  PUPWAVE_ERROR_CORRUPT = 3,     /* truncated, corrupted or not a Pupwave stream */
  PUPWAVE_ERROR_MEMORY = 4,      /* out of memory */
  PUPWAVE_ERROR_INTERNAL = 5     /* anything else (a bug: please report it) */
} pupwave_status;

/* The message of the calling thread's last failure ("" if none). */
const char* pupwave_last_error(void);
/* "pupwave X.Y.Z" */
const char* pupwave_version(void);

/* Sample types: images use U8, U16, F16 (IEEE binary16 bits in a uint16_t), F32;
 * volumes use U8, U16, F32, F64. */
typedef enum pupwave_type {
  PUPWAVE_U8 = 0,
  PUPWAVE_U16 = 1,
  PUPWAVE_F16 = 2,
  PUPWAVE_F32 = 3,
  PUPWAVE_F64 = 4
} pupwave_type;

/* Rate modes, as the CLI's flags. Images: PSNR, BPP, STEP, LOSSLESS. Volumes: MAX_ERROR,
 * MAX_ERROR_REL, BPV, PSNR, STEP, LOSSLESS. */
typedef enum pupwave_rate {
  PUPWAVE_RATE_PSNR = 0,          /* target: dB */
  PUPWAVE_RATE_BPP = 1,           /* target: bits per pixel (whole stream) */
  PUPWAVE_RATE_STEP = 2,          /* target: quantizer base step (sample units) */
  PUPWAVE_RATE_LOSSLESS = 3,      /* bit exact; integer samples only */
  PUPWAVE_RATE_MAX_ERROR = 4,     /* volumes: |x - x'| <= target on every voxel, guaranteed */
  PUPWAVE_RATE_MAX_ERROR_REL = 5, /* volumes: bound target * (max - min) */
  PUPWAVE_RATE_BPV = 6            /* volumes: target bits per voxel */
} pupwave_rate;

/* Encoding parameters. Defaults: images PSNR 40 dB, volumes LOSSLESS for U8/U16 data and
 * MAX_ERROR_REL 1e-3 for float data, as the CLI (the mode is checked against the data kind when
 * compressing); transform "" (cdf97, cdf53 for lossless,
 * pups:cinpact-interp-vm4 for volumes in a max-error mode);
 * levels -1 (from the size); 64^3 bricks; coder AUTO; all cores. */
typedef struct pupwave_options pupwave_options;
pupwave_options* pupwave_options_create(void); /* NULL when out of memory */
void pupwave_options_destroy(pupwave_options* options);
/* Sets the mode and its target (ignored for LOSSLESS; otherwise positive and finite). */
pupwave_status pupwave_options_set_rate(pupwave_options* options, pupwave_rate rate, double target);
/* Transform spec (cdf97, cdf53, pups:..., kobbelt:...); NULL or "" for the default. */
pupwave_status pupwave_options_set_transform(pupwave_options* options, const char* spec);
/* Decomposition levels (-1: default, else 0..32). */
pupwave_status pupwave_options_set_levels(pupwave_options* options, int levels);
/* Most worker threads (0: all cores, 1: the calling thread only). */
pupwave_status pupwave_options_set_threads(pupwave_options* options, unsigned threads);
/* Volumes: brick edge (power of two, 8..256). */
pupwave_status pupwave_options_set_brick(pupwave_options* options, size_t brick);
/* Dense volumes: voxels equal to fill_value (finite) are missing values, as NaN and infinities
 * always are: restored bit for bit, outside the error bound, the value range and statistics. */
pupwave_status pupwave_options_set_fill_value(pupwave_options* options, double fill_value);
/* Images: the entropy coder, with the names of the CLI's --entropy and Python's entropy=
 * (pupwave_coder_name): AUTO (the default: LC for lossless; for rate targets PC on images of up
 * to 4 Mpixel, EBCOT on larger ones), EBCOT (bit-plane coder: embedded, bounded
 * memory from 8-bit PGM/PPM files), PC (parent-context coder: the smallest lossy files; lossy
 * only), LC (lossless context coder; lossless only), HT (high-throughput block coder: no
 * arithmetic coding, faster, larger files). */
typedef enum pupwave_coder {
  PUPWAVE_CODER_AUTO = 0,
  PUPWAVE_CODER_EBCOT = 1,
  PUPWAVE_CODER_PC = 2,
  PUPWAVE_CODER_LC = 3,
  PUPWAVE_CODER_HT = 4
} pupwave_coder;
pupwave_status pupwave_options_set_coder(pupwave_options* options, pupwave_coder coder);
/* The coder named NAME ("auto", "ebcot", "pc", "lc", "ht"; any case) into *coder;
 * PUPWAVE_ERROR_ARGUMENT for another name. */
pupwave_status pupwave_coder_from_name(const char* name, pupwave_coder* coder);
/* CODER's name, or NULL when CODER is not a pupwave_coder value. */
const char* pupwave_coder_name(pupwave_coder coder);
/* Images, BPP targets with PUPWAVE_CODER_EBCOT: encoder effort 1 (default, fastest) or 2 (three
 * base steps per band and RDOQ: about 1 % less rate at equal PSNR for up to 1.9x the encode time). */
pupwave_status pupwave_options_set_effort(pupwave_options* options, int effort);
/* Images, lossy: what the coding minimises (pupwave.hpp's Tune): PUPWAVE_TUNE_PSNR (default, the
 * squared error) or PUPWAVE_TUNE_VISUAL (a contrast-sensitivity-weighted squared error, less
 * weight on chroma: better perceptual scores at a size, lower PSNR). Rate targets keep their
 * meaning in both. */
typedef enum pupwave_tune { PUPWAVE_TUNE_PSNR = 0, PUPWAVE_TUNE_VISUAL = 1 } pupwave_tune;
pupwave_status pupwave_options_set_tune(pupwave_options* options, pupwave_tune tune);

/* Compressed bytes. */
typedef struct pupwave_stream pupwave_stream;
const uint8_t* pupwave_stream_data(const pupwave_stream* stream);
size_t pupwave_stream_size(const pupwave_stream* stream);
/* 1 when the stream meets the rate target it was compressed for, 0 when it misses it (over a
 * BPP or BPV budget: a tiny input's header alone can exceed one; under a PSNR target; over an
 * error bound) or stream is NULL. The stream is complete either way. STEP and LOSSLESS set no
 * target to miss: 1. */
int pupwave_stream_target_met(const pupwave_stream* stream);
/* The stream's value in the target's unit: bits per pixel or voxel, PSNR in dB (log-PSNR for
 * F16/F32 images), the largest error (for MAX_ERROR_REL as a fraction of the value range); NaN
 * for STEP, LOSSLESS and a NULL stream. */
double pupwave_stream_achieved(const pupwave_stream* stream);
/* How the stream misses its target, in the words of the CLI's `warning:` line with "the stream"
 * as its subject ("--bpp 1 not met: the stream is 110 bytes (220 bpp) for this 2x2 image; ...");
 * "" when it meets it or stream is NULL. Valid until the stream is destroyed. */
const char* pupwave_stream_target_miss(const pupwave_stream* stream);
void pupwave_stream_destroy(pupwave_stream* stream);

/* Compresses an image: sample (c, x, y) is the element at
 *   data + c * channel_stride + x * pixel_stride + y * row_stride   (strides in ELEMENTS),
 * so interleaved RGB is (1, 3, 3 * width) and planar is (width * height, 1, width).
 * channels 1..64. options NULL: defaults. */
pupwave_status pupwave_compress_image(const pupwave_options* options, const void* data, pupwave_type type,
                                      size_t width, size_t height, size_t channels, ptrdiff_t channel_stride,
                                      ptrdiff_t pixel_stride, ptrdiff_t row_stride, pupwave_stream** out);

/* A decoded image or volume: interleaved image samples (channels adjacent) or volume voxels
 * (x fastest) of pupwave_decoded_type, dims[0..2] = width, height, 1 (images) or x, y, z. */
typedef struct pupwave_decoded pupwave_decoded;
pupwave_type pupwave_decoded_type(const pupwave_decoded* decoded);
size_t pupwave_decoded_dim(const pupwave_decoded* decoded, int axis);
size_t pupwave_decoded_channels(const pupwave_decoded* decoded); /* 1 for volumes */
const void* pupwave_decoded_data(const pupwave_decoded* decoded);
size_t pupwave_decoded_size(const pupwave_decoded* decoded); /* bytes */
/* Volumes: index-space position of voxel (0, 0, 0) along axis; 0 for images. */
int64_t pupwave_decoded_origin(const pupwave_decoded* decoded, int axis);
/* Sparse volumes: one byte per voxel (1 active, 0 inactive); NULL for dense data and images. */
const uint8_t* pupwave_decoded_active(const pupwave_decoded* decoded);
void pupwave_decoded_destroy(pupwave_decoded* decoded);

/* Decodes an image stream at level (0 full size, k: 1/2^k). threads as above. */
pupwave_status pupwave_decompress_image(const void* stream, size_t size, int level, unsigned threads,
                                        pupwave_decoded** out);

/* Compresses a dense volume of nx * ny * nz voxels (x fastest). */
pupwave_status pupwave_compress_volume(const pupwave_options* options, const void* data, pupwave_type type,
                                       size_t nx, size_t ny, size_t nz, pupwave_stream** out);
/* One brick of a sparse grid: dims[0] * dims[1] * dims[2] voxels (x fastest) at integer
 * position origin, optionally with an activity mask (one byte per voxel, nonzero = active;
 * NULL: all active). */
typedef struct pupwave_brick {
  int64_t origin[3];
  size_t dims[3];
  const void* data;
  const uint8_t* active;
} pupwave_brick;
/* Compresses a sparse grid given as `count` non-overlapping bricks of one voxel type: only
 * active voxels are coded; inactive voxels and the box around the bricks (value `background`)
 * are restored exactly. Decode with pupwave_decompress_volume: the decoded box starts at
 * pupwave_decoded_origin and pupwave_decoded_active gives its mask. */
pupwave_status pupwave_compress_sparse_volume(const pupwave_options* options, const pupwave_brick* bricks,
                                              size_t count, pupwave_type type, double background,
                                              pupwave_stream** out);

/* Decodes the (single) grid of a volume stream at level; streams with several grids (from a
 * .vdb) are refused with PUPWAVE_ERROR_UNSUPPORTED (use the C++ API or the CLI). Inactive
 * voxels of a sparse grid hold their stored values. */
pupwave_status pupwave_decompress_volume(const void* stream, size_t size, int level, unsigned threads,
                                         pupwave_decoded** out);
/* The same, into the caller's buffer of `capacity` bytes, which must hold the decoded grid
 * exactly (dims from pupwave_describe_dims, type as stored); for filters (HDF5). */
pupwave_status pupwave_decompress_volume_into(const void* stream, size_t size, int level, unsigned threads,
                                              void* buffer, size_t capacity);
/* Decodes the voxels of the box [lo[a], hi[a]) (full-resolution x, y, z; half-open) of the
 * (single) grid of a volume stream at level, decoding only the bricks the box touches: the
 * level voxels whose full-resolution footprint meets the box (their counts are
 * pupwave_decoded_dim, the first one's position pupwave_decoded_origin), equal to that box
 * cropped out of pupwave_decompress_volume. A box that is empty, inverted or outside the grid
 * is PUPWAVE_ERROR_ARGUMENT, the message naming the box and the grid's dims. */
pupwave_status pupwave_decompress_volume_box(const void* stream, size_t size, const size_t lo[3],
                                             const size_t hi[3], int level, unsigned threads,
                                             pupwave_decoded** out);

/* Stream header: kind (0 image, 1 volume), dims (width, height, 1 or x, y, z of the first
 * grid), sample type and levels; every checksum verified. Any out pointer may be NULL. */
pupwave_status pupwave_describe_dims(const void* stream, size_t size, int* kind, size_t dims[3],
                                     pupwave_type* type, int* levels);
/* The `pupwave info` text of a stream, NUL-terminated, into buffer (truncated to capacity);
 * *length (if not NULL) receives the full length without the NUL. */
pupwave_status pupwave_describe(const void* stream, size_t size, char* buffer, size_t capacity,
                                size_t* length);

#ifdef __cplusplus
}
#endif

#endif /* PUPWAVE_PUPWAVE_H */
