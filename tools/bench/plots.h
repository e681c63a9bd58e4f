#pragma once
// PSNR- and MS-SSIM-against-bpp plots drawn by gnuplot (SVG), one per image, from the measured records.

#include <filesystem>
#include <string>
#include <vector>

#include "tools/bench/rd_run.h"

namespace pupwave::bench {

// For each image (in `images` order) writes <dir>/<image>.dat (the points, one gnuplot data
// block per codec), <dir>/<image>.gp (the script) and runs gnuplot to draw <dir>/<image>.svg
// (PSNR against bpp), <dir>/<image>-ms-ssim.svg (MS-SSIM of luma in dB, -10 log10(1 - MS-SSIM),
// against bpp) and, when "openjpeg" is among the codecs, <dir>/<image>-vs-openjpeg.svg
// (PSNR minus OpenJPEG's, interpolated in log rate, against bpp: small gaps become visible).
// Earlier .svg, .dat and .gp files in `dir` are removed first, so `dir` holds this run's
// plots only. Returns the SVG paths per image (empty where drawing failed). When gnuplot is not in
// `search_path`, draws nothing and sets `note`; a failing gnuplot run also sets `note`.
std::vector<std::vector<std::filesystem::path>> draw_rd_plots(const std::vector<RdRecord>& records,
                                                              const std::vector<std::string>& images,
                                                              const std::vector<std::string>& codecs,
                                                              const std::filesystem::path& dir,
                                                              const std::string& search_path,
                                                              std::string& note);

}  // namespace pupwave::bench
