#include "tools/bench/codecs.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "tools/bench/process.h"

namespace pupwave::bench {
namespace {

namespace fs = std::filesystem;

std::string format_number(double v, const char* fmt = "%.6g") {
  char buf[48];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// Runs a tool and turns a failure (non-zero exit or no output file) into an exception that
// quotes the tool's own message.
double run_checked(const std::vector<std::string>& argv, const fs::path& log, const fs::path& product) {
  const ProcessResult r = run_process(argv, log);
  std::error_code ec;
  if (r.exit_code != 0 || !fs::is_regular_file(product, ec)) {
    const std::string tail = log_tail(log);
    throw std::runtime_error(fs::path(argv[0]).filename().string() + " failed (exit " +
                             std::to_string(r.exit_code) + (tail.empty() ? ")" : "): " + tail));
  }
  return r.seconds;
}

std::uintmax_t target_bytes(const EncodeRequest& q) {
  return static_cast<std::uintmax_t>(
      std::llround(q.target_bpp * static_cast<double>(q.width * q.height) / 8.0));
}

class PupwaveCodec final : public RdCodec {
 public:
  PupwaveCodec(fs::path cli, std::string spec) : cli_(std::move(cli)), spec_(std::move(spec)) {}
  std::string name() const override { return spec_; }
  std::string kind() const override { return "pupwave"; }
  std::string extension() const override { return ".pw"; }

  EncodeOutcome encode(const EncodeRequest& q) const override {
    const std::string bpp = format_number(q.target_bpp);
    EncodeOutcome out;
    out.seconds = run_checked(
        {cli_.string(), "compress", q.input.string(), q.output.string(), "--transform", spec_, "--bpp", bpp},
        q.log, q.output);
    out.bytes = fs::file_size(q.output);
    out.setting = "--bpp " + bpp;
    return out;
  }

  double decode(const fs::path& compressed, const fs::path& decoded, const fs::path& log) const override {
    return run_checked({cli_.string(), "decompress", compressed.string(), decoded.string()}, log, decoded);
  }

 private:
  fs::path cli_;
  std::string spec_;
};

// JPEG 2000 through OpenJPEG: irreversible 9/7 (-I), 6 resolutions (-n 6, fewer for images too
// small for them), rate given as a compression ratio against the 8-bit raw size (-r).
class OpenJpegAnchor final : public RdCodec {
 public:
  OpenJpegAnchor(fs::path encoder, fs::path decoder) : enc_(std::move(encoder)), dec_(std::move(decoder)) {}
  std::string name() const override { return "openjpeg"; }
  std::string kind() const override { return "anchor"; }
  std::string extension() const override { return ".j2k"; }

  EncodeOutcome encode(const EncodeRequest& q) const override {
    int resolutions = 6;
    while (resolutions > 1 && (std::min(q.width, q.height) >> (resolutions - 1)) < 1) --resolutions;
    const std::string ratio = format_number(8.0 * static_cast<double>(q.channels) / q.target_bpp);
    EncodeOutcome out;
    out.seconds = run_checked({enc_.string(), "-i", q.input.string(), "-o", q.output.string(), "-I", "-r",
                               ratio, "-n", std::to_string(resolutions)},
                              q.log, q.output);
    out.bytes = fs::file_size(q.output);
    out.setting = "-I -r " + ratio + " -n " + std::to_string(resolutions);
    return out;
  }

  double decode(const fs::path& compressed, const fs::path& decoded, const fs::path& log) const override {
    return run_checked({dec_.string(), "-i", compressed.string(), "-o", decoded.string()}, log, decoded);
  }

 private:
  fs::path enc_, dec_;
};

// JPEG XL through cjxl: no rate control, so the Butteraugli distance is searched (bisection in
// log distance, the file size falls as the distance grows) until the file is within 1% of the
// target size; the closest trial is kept.
class JxlAnchor final : public RdCodec {
 public:
  JxlAnchor(fs::path encoder, fs::path decoder) : enc_(std::move(encoder)), dec_(std::move(decoder)) {}
  std::string name() const override { return "jxl"; }
  std::string kind() const override { return "anchor"; }
  std::string extension() const override { return ".jxl"; }

  EncodeOutcome encode(const EncodeRequest& q) const override {
    const double target = static_cast<double>(std::max<std::uintmax_t>(1, target_bytes(q)));
    double lo = std::log(kMinDistance), hi = std::log(kMaxDistance);
    EncodeOutcome best;
    double best_miss = INFINITY, best_distance = 0.0;
    int trials = 0;
    while (trials < kMaxTrials && best_miss > 0.01) {
      // Start at the upper end: when even the coarsest setting is too big, stop there.
      const double d = trials == 0 ? kMaxDistance : std::exp(0.5 * (lo + hi));
      const fs::path trial = q.output.string() + ".trial";
      const double seconds = run_checked(
          {enc_.string(), q.input.string(), trial.string(), "-d", format_number(d, "%.4f")}, q.log, trial);
      ++trials;
      const auto bytes = fs::file_size(trial);
      const double miss = std::abs(std::log(static_cast<double>(bytes) / target));
      if (miss < best_miss) {
        best_miss = miss, best_distance = d, best.bytes = bytes, best.seconds = seconds;
        fs::rename(trial, q.output);
      }
      if (trials == 1 && static_cast<double>(bytes) >= target) break;
      (static_cast<double>(bytes) > target ? lo : hi) = std::log(d);
    }
    best.setting = "-d " + format_number(best_distance, "%.4f") + " (" + std::to_string(trials) + " trials)";
    return best;
  }

  double decode(const fs::path& compressed, const fs::path& decoded, const fs::path& log) const override {
    return run_checked({dec_.string(), compressed.string(), decoded.string()}, log, decoded);
  }

 private:
  static constexpr double kMinDistance = 0.05;
  static constexpr double kMaxDistance = 25.0;  // the largest distance cjxl 0.7 accepts
  static constexpr int kMaxTrials = 16;
  fs::path enc_, dec_;
};

}  // namespace

RdCodecPtr make_pupwave_codec(const fs::path& cli, const std::string& spec) {
  return std::make_shared<PupwaveCodec>(cli, spec);
}

const std::vector<std::string>& anchor_names() {
  static const std::vector<std::string> names = {"openjpeg", "jxl"};
  return names;
}

RdCodecPtr make_anchor(const std::string& name, const std::string& search_path, std::string& missing_note) {
  std::vector<std::string> tools;
  if (name == "openjpeg")
    tools = {"opj_compress", "opj_decompress"};
  else if (name == "jxl")
    tools = {"cjxl", "djxl"};
  else
    throw std::invalid_argument("unknown anchor '" + name + "' (known: openjpeg, jxl)");
  std::vector<fs::path> found;
  for (const std::string& tool : tools) {
    const auto path = find_tool(tool, search_path);
    if (!path) {
      missing_note = "anchor " + name + " skipped: " + tool + " not found in PATH (Debian package " +
                     (name == "openjpeg" ? "libopenjp2-tools" : "libjxl-tools") + ")";
      return nullptr;
    }
    found.push_back(*path);
  }
  missing_note.clear();
  if (name == "openjpeg") return std::make_shared<OpenJpegAnchor>(found[0], found[1]);
  return std::make_shared<JxlAnchor>(found[0], found[1]);
}

namespace {

// First line of a tool's output that contains `marker`, from `marker` to the end of the line.
std::string version_line(const fs::path& tool, const std::string& flag, const std::string& marker) {
  const fs::path log =
      fs::temp_directory_path() / ("pupwave-bench-version-" + std::to_string(::getpid()) + ".txt");
  run_process({tool.string(), flag}, log);
  std::ifstream in(log);
  std::string line, found;
  while (found.empty() && std::getline(in, line))
    if (const auto at = line.find(marker); at != std::string::npos) found = line.substr(at);
  fs::remove(log);
  while (!found.empty() && (found.back() == '.' || std::isspace(static_cast<unsigned char>(found.back()))))
    found.pop_back();
  return found;
}

}  // namespace

std::string anchor_versions(const std::string& search_path) {
  std::vector<std::string> parts;
  if (const auto opj = find_tool("opj_compress", search_path))
    parts.push_back("opj_compress (" + version_line(*opj, "-h", "openjp2 library") + ")");
  if (const auto cjxl = find_tool("cjxl", search_path))
    parts.push_back(version_line(*cjxl, "--version", "cjxl v"));
  std::string joined;
  for (const std::string& p : parts) joined += (joined.empty() ? "" : ", ") + p;
  return joined;
}

}  // namespace pupwave::bench
