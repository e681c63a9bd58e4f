#pragma once
// The coarse-band experiment of Fig. 16 of "PUPs subdivision and multiresolution": transform
// an image L levels, zero every detail band, transform back, and measure luma PSNR. It shows
// how much of the image each filter bank's coarse band alone keeps.

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "tools/bench/rd_run.h"

namespace pupwave::bench {

struct CoarseRecord {
  std::string image;
  std::string transform;  // spec
  int levels = 0;
  double psnr_luma = 0.0;  // dB; Rec. 601 luma for RGB, the grey channel for grey images
  bool ok = false;
  std::string error;
};

// Reconstruction of `image` from its coarse band after `levels` levels of `spec` (every detail
// band zeroed), channel by channel in RGB, rounded and clamped to 8 bits like a decoded file.
Image coarse_reconstruction(const Image& image, const std::string& spec, int levels);

// Every image x transform x level; failures (e.g. an unknown spec) become records with
// ok = false. Progress goes to `log`.
std::vector<CoarseRecord> run_coarse(const std::vector<BenchImage>& images,
                                     const std::vector<std::string>& specs, const std::vector<int>& levels,
                                     unsigned jobs, bool terminal, std::ostream& log);

// Writes coarse.csv and summary.md (a table per image and the mean) into `dir`.
void write_coarse_report(const std::vector<CoarseRecord>& records, const std::vector<int>& levels,
                         const std::string& command, const std::string& machine,
                         const std::filesystem::path& dir);

// Parses "1..5" or "1,2,4" into ascending level counts in [1, 16]; std::invalid_argument
// otherwise.
std::vector<int> parse_levels(const std::string& text);

}  // namespace pupwave::bench
