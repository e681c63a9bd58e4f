#pragma once
// The codecs the rate-distortion harness compares, all driven as external programs: pupwave
// itself (one per transform spec) and the anchors OpenJPEG (JPEG 2000) and JPEG XL, plus the
// modern anchors of modern_anchors.h (AVIF, HEVC intra, WebP).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace pupwave::bench {

// One compression request: a PPM/PGM source, where to write, the target rate, and a log file
// collecting the tools' output.
struct EncodeRequest {
  std::filesystem::path input;   // 8-bit PPM (RGB) or PGM (grey)
  std::filesystem::path output;  // compressed file to create
  std::filesystem::path log;
  double target_bpp = 0.0;  // bits per pixel (all channels together)
  std::size_t width = 0, height = 0, channels = 0;
};

struct EncodeOutcome {
  std::uintmax_t bytes = 0;  // size of the compressed file
  double seconds = 0.0;      // wall time of the (final) encoder run
  std::string setting;       // encoder parameter used, e.g. "-r 48" or "-d 1.83 (9 trials)"
};

class RdCodec {
 public:
  virtual ~RdCodec() = default;
  // Name in tables and plots: the transform spec for pupwave, "openjpeg" or "jxl" for anchors.
  virtual std::string name() const = 0;
  // "pupwave" or "anchor".
  virtual std::string kind() const = 0;
  // Extension (with dot) of the compressed files.
  virtual std::string extension() const = 0;
  // Compresses toward the target rate; throws std::runtime_error when the tool fails.
  virtual EncodeOutcome encode(const EncodeRequest& request) const = 0;
  // Decodes to a PPM/PGM; returns the wall time; throws std::runtime_error on failure.
  virtual double decode(const std::filesystem::path& compressed, const std::filesystem::path& decoded,
                        const std::filesystem::path& log) const = 0;
};

using RdCodecPtr = std::shared_ptr<const RdCodec>;

// pupwave compress/decompress run through the binary `cli` with `--transform spec --bpp X`
// (and `--effort N` when effort is not 1, `--entropy E` when entropy is not empty, `--tune T` when
// tune is not psnr; the codec is then named SPEC+E, SPEC+T or SPEC+E+T).
RdCodecPtr make_pupwave_codec(const std::filesystem::path& cli, const std::string& spec, int effort = 1,
                              const std::string& entropy = "", const std::string& tune = "psnr");

// Names of the anchors the harness knows, in report order.
const std::vector<std::string>& anchor_names();

// The anchor called `name` ("openjpeg" or "jxl") when its Debian tools are found in
// `search_path` (PATH style); otherwise nullptr and `missing_note` says what is missing.
// Throws std::invalid_argument for an unknown name.
RdCodecPtr make_anchor(const std::string& name, const std::string& search_path, std::string& missing_note);

// Versions of the anchor tools found in `search_path`, e.g. "opj_compress (openjp2 v2.5.0),
// cjxl v0.7.0", for the reports; tools that are missing are left out.
std::string anchor_versions(const std::string& search_path);

}  // namespace pupwave::bench
