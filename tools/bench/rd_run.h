#pragma once
// The rate-distortion run: every image x codec x target rate is compressed, decompressed and
// measured (achieved bpp, PSNR, max error, SSIM, MS-SSIM, butteraugli distance, times),
// independent jobs on a thread pool.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "codec/image/image.h"
#include "tools/bench/codecs.h"

namespace pupwave::bench {

// An input image of the harness, as 8-bit grey or RGB samples.
struct BenchImage {
  std::string name;  // file stem, used in tables and file names
  std::filesystem::path source;
  Image pixels;
};

// One measurement (a row of results.csv).
struct RdRecord {
  std::string image;
  std::size_t width = 0, height = 0, channels = 0;
  std::string codec;  // transform spec, or anchor name
  std::string kind;   // "pupwave" or "anchor"
  double target_bpp = 0.0;
  std::uintmax_t bytes = 0;
  double bpp = 0.0;        // achieved: 8 * bytes / (width * height)
  double psnr = 0.0;       // dB over all channels (RGB for colour), peak 255
  double psnr_luma = 0.0;  // dB of Rec. 601 luma; the grey channel itself for grey images
  double max_error = 0.0;  // largest absolute sample error
  double ssim = 0.0;       // SSIM of luma (tools/bench/ssim.h)
  double ms_ssim = 0.0;    // MS-SSIM of luma (tools/bench/ssim.h)
  double butteraugli = std::numeric_limits<double>::quiet_NaN();  // distance; NaN when not measured
  double encode_s = 0.0, decode_s = 0.0;
  std::string setting;  // encoder parameter used
  bool ok = false;
  std::string error;  // why the job failed when !ok
};

struct RdRun {
  std::vector<BenchImage> images;
  std::vector<RdCodecPtr> codecs;     // pupwave transforms first, then anchors
  std::vector<double> bpps;           // target rates, ascending
  unsigned jobs = 1;                  // worker threads (>= 1)
  bool terminal = false;              // progress as a redrawn bar rather than lines
  std::filesystem::path butteraugli;  // the butteraugli command; empty: distances not measured
};

// Expands --images arguments: a directory gives its image files (png, ppm, pgm, pnm, tif,
// tiff, bmp) sorted by name; files are taken as given. Throws std::invalid_argument when an
// argument does not exist or nothing is found.
std::vector<std::filesystem::path> expand_image_args(const std::vector<std::string>& args);

// Reads an image for the harness; colour images must be 8-bit grey or RGB (alpha and 16-bit
// samples are rejected with std::invalid_argument: the anchors are fed 8-bit PPM/PGM).
BenchImage load_bench_image(const std::filesystem::path& path);

// Runs every job; a failed job becomes a record with ok = false and its error, it does not
// stop the others. Records come back ordered by image, codec, rate. Progress goes to `log`.
// Temporary files live in a fresh directory under `work_root`, removed afterwards.
std::vector<RdRecord> run_rd(const RdRun& run, const std::filesystem::path& work_root, std::ostream& log);

}  // namespace pupwave::bench
