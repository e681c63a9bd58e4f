#include "tools/bench/codecs.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "tools/bench/modern_anchors.h"
#include "tools/bench/process.h"
#include "tools/bench/size_search.h"

namespace pupwave::bench {
namespace {

namespace fs = std::filesystem;

std::string format_number(double v, const char* fmt = "%.6g") {
  char buf[48];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

class PupwaveCodec final : public RdCodec {
 public:
  PupwaveCodec(fs::path cli, std::string spec, int effort, std::string entropy, std::string tune)
      : cli_(std::move(cli)),
        spec_(std::move(spec)),
        effort_(effort),
        entropy_(std::move(entropy)),
        tune_(std::move(tune)) {}
  std::string name() const override {
    return spec_ + (entropy_.empty() ? "" : "+" + entropy_) + (tune_ == "psnr" ? "" : "+" + tune_);
  }
  std::string kind() const override { return "pupwave"; }
  std::string extension() const override { return ".pw"; }

  EncodeOutcome encode(const EncodeRequest& q) const override {
    const std::string bpp = format_number(q.target_bpp);
    EncodeOutcome out;
    std::vector<std::string> args{cli_.string(), "compress", q.input.string(), q.output.string(),
                                  "--transform", spec_,      "--bpp",          bpp};
    if (effort_ != 1) args.insert(args.end(), {"--effort", std::to_string(effort_)});
    if (!entropy_.empty()) args.insert(args.end(), {"--entropy", entropy_});
    if (tune_ != "psnr") args.insert(args.end(), {"--tune", tune_});
    out.seconds = run_checked(args, q.log, q.output);
    out.bytes = fs::file_size(q.output);
    out.setting = "--bpp " + bpp + (effort_ != 1 ? " --effort " + std::to_string(effort_) : "") +
                  (entropy_.empty() ? "" : " --entropy " + entropy_) +
                  (tune_ == "psnr" ? "" : " --tune " + tune_);
    return out;
  }

  double decode(const fs::path& compressed, const fs::path& decoded, const fs::path& log) const override {
    return run_checked({cli_.string(), "decompress", compressed.string(), decoded.string()}, log, decoded);
  }

 private:
  fs::path cli_;
  std::string spec_;
  int effort_ = 1;
  std::string entropy_;  // empty: the CLI's default coder
  std::string tune_;     // compress --tune
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
    const auto trial = [&](double d, const fs::path& product) {
      return run_checked({enc_.string(), q.input.string(), product.string(), "-d", format_number(d, "%.4f")},
                         q.log, product);
    };
    // 25 is the largest distance cjxl 0.7 accepts.
    return search_parameter(q, {0.05, 25.0, false, true, true}, trial,
                            [](double d) { return "-d " + format_number(d, "%.4f"); });
  }

  double decode(const fs::path& compressed, const fs::path& decoded, const fs::path& log) const override {
    return run_checked({dec_.string(), compressed.string(), decoded.string()}, log, decoded);
  }

 private:
  fs::path enc_, dec_;
};

}  // namespace

RdCodecPtr make_pupwave_codec(const fs::path& cli, const std::string& spec, int effort,
                              const std::string& entropy, const std::string& tune) {
  return std::make_shared<PupwaveCodec>(cli, spec, effort, entropy, tune);
}

const std::vector<std::string>& anchor_names() {
  static const std::vector<std::string> names = {"openjpeg", "jxl", "avif", "avif-s6", "hevc", "webp"};
  return names;
}

namespace {

// The programs each anchor runs and the Debian package that ships them.
struct AnchorTools {
  std::vector<std::string> programs;
  const char* package;
};

AnchorTools anchor_tools(const std::string& name) {
  if (name == "openjpeg") return {{"opj_compress", "opj_decompress"}, "libopenjp2-tools"};
  if (name == "jxl") return {{"cjxl", "djxl"}, "libjxl-tools"};
  if (name == "avif" || name == "avif-s6")
    return {{"avifenc", "avifdec", "ffmpeg"}, "libavif-bin and ffmpeg"};
  if (name == "hevc") return {{"ffmpeg"}, "ffmpeg"};
  if (name == "webp") return {{"cwebp", "dwebp", "ffmpeg"}, "webp and ffmpeg"};
  throw std::invalid_argument("unknown anchor '" + name +
                              "' (known: openjpeg, jxl, avif, avif-s6, hevc, webp)");
}

}  // namespace

RdCodecPtr make_anchor(const std::string& name, const std::string& search_path, std::string& missing_note) {
  const AnchorTools tools = anchor_tools(name);
  std::vector<fs::path> found;
  for (const std::string& tool : tools.programs) {
    const auto path = find_tool(tool, search_path);
    if (!path) {
      missing_note = "anchor " + name + " skipped: " + tool + " not found in PATH (Debian package " +
                     tools.package + ")";
      return nullptr;
    }
    found.push_back(*path);
  }
  missing_note.clear();
  if (name == "openjpeg") return std::make_shared<OpenJpegAnchor>(found[0], found[1]);
  if (name == "jxl") return std::make_shared<JxlAnchor>(found[0], found[1]);
  if (name == "avif") return make_avif_anchor(found[0], found[1], found[2], 4);
  if (name == "avif-s6") return make_avif_anchor(found[0], found[1], found[2], 6);
  if (name == "hevc") return make_hevc_anchor(found[0]);
  return make_webp_anchor(found[0], found[1], found[2]);
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
  if (const auto avifenc = find_tool("avifenc", search_path))
    parts.push_back("avifenc " + version_line(*avifenc, "--version", "Version: "));
  if (const auto ffmpeg = find_tool("ffmpeg", search_path))
    parts.push_back(version_line(*ffmpeg, "-version", "ffmpeg version"));
  if (const auto cwebp = find_tool("cwebp", search_path))
    parts.push_back("cwebp " + version_line(*cwebp, "-version", ""));
  std::string joined;
  for (const std::string& p : parts) joined += (joined.empty() ? "" : ", ") + p;
  return joined;
}

}  // namespace pupwave::bench
