#pragma once
// Writers for the rate-distortion outputs: results.csv (one row per measurement), summary.md
// (PSNR per rate, BD-PSNR and BD-rate against OpenJPEG, MS-SSIM BD-rate, SSIM / MS-SSIM /
// butteraugli per rate, per image and mean) and the plots.

#include <filesystem>
#include <string>
#include <vector>

#include "tools/bench/rd_run.h"

namespace pupwave::bench {

// Column names of results.csv, in order.
const std::vector<std::string>& results_csv_columns();

// Writes results.csv (atomically); numbers with enough digits to recompute the summary.
void write_results_csv(const std::vector<RdRecord>& records, const std::filesystem::path& path);

// What summary.md says about how it was made.
struct ReportContext {
  std::string command;                          // the command line that produced the run
  std::string machine;                          // machine and tool versions, one markdown paragraph
  std::vector<std::string> notes;               // e.g. anchors skipped because their tools are missing
  std::vector<double> bpps;                     // target rates, ascending
  std::vector<std::string> codecs;              // codec names in report order
  std::vector<std::vector<std::string>> plots;  // per image: plot files relative to summary.md
};

// Writes summary.md (atomically). The BD reference is the "openjpeg" codec when present.
void write_rd_summary(const std::vector<RdRecord>& records, const ReportContext& context,
                      const std::filesystem::path& path);

// Machine description (CPU model, cores, OS) for the reports.
std::string describe_machine();

// Writes `text` to `path` atomically (temporary name, then rename).
void write_text_file(const std::filesystem::path& path, const std::string& text);

// "%.*f" formatting; "n/a" for NaN, "inf" for infinity.
std::string fixed(double value, int decimals);

}  // namespace pupwave::bench
