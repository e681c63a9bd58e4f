// `pupwave compress IN OUT.pw`: read an image (or a volume: a .vdb file, or a raw file given
// --dims and --dtype), encode it, write the stream atomically and report size, rate, quality
// against the input and time.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "codec/api/api_image_options.h"
#include "codec/api/api_volume_options.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "codec/volume/volume_codec.h"
#include "pupwave/pupwave.hpp"
#include "tools/atomic_file.h"
#include "tools/cli_numbers.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/image_io.h"
#include "tools/pnm_io.h"
#include "tools/rate_warnings.h"
#include "tools/volume_io.h"
#include "tools/volume_raw.h"
#include "transforms/separable.h"

namespace pupwave::cli {
namespace {

struct CompressOptions {
  std::string input;
  std::string output;
  std::string transform;
  int levels = -1;
  double bpp = 0.0, psnr = 0.0, step = 0.0;
  bool lossless = false;
  std::string entropy = "auto";  // --entropy: a coder name of pupwave::api::coder_from_name
  int effort = 0;                // 0: not given (1)
  std::string tune = "psnr";     // --tune: psnr or visual (pupwave::api::tune_from_name)
  unsigned threads = 0;
  bool report_psnr = false;
  bool keep_nonfinite = false;
  std::string transfer = "log";  // --transfer: log, adaptive or linear
  // volumes
  std::string dims, dtype, grid;
  double bpv = 0.0, max_error = 0.0, max_error_rel = 0.0;
  std::optional<double> fill_value;  // --fill-value: voxels equal to it are missing, kept exactly
  std::size_t brick = 64;
  bool strict = false;  // a missed rate target is an error and nothing is written
  Verbosity verbosity;
};

// --entropy's value, already checked and spelled as the library names it (coder_option).
pupwave::api::Coder coder_of(const CompressOptions& opt) {
  return *pupwave::api::coder_from_name(opt.entropy);
}

// Checks an --entropy name against the library's table and spells it the library's way.
CLI::Validator coder_option() {
  return CLI::Validator(
      [](std::string& name) -> std::string {
        const auto coder = pupwave::api::coder_from_name(name);
        if (!coder) return "unknown entropy coder " + name + " (one of " + pupwave::api::coder_names() + ")";
        name = std::string(pupwave::api::coder_name(*coder));
        return "";
      },
      "CODER");
}

bool is_volume_input(const CompressOptions& opt) { return !opt.dims.empty() || is_vdb_path(opt.input); }

// The grids to encode and, for a raw file, the file mapped in its own type: `grids` then holds
// only the description and `views` the voxels, read in place by the encoder.
struct VolumeInput {
  std::vector<VolumeGrid> grids;
  std::unique_ptr<MappedRawVolume> raw;
  std::vector<VolumeView> views;  // empty, or one per grid (null data: the grid's own values)
};

VolumeInput read_volume_input(const CompressOptions& opt) {
  VolumeInput in;
  if (is_vdb_path(opt.input)) {
    if (!opt.dims.empty() || !opt.dtype.empty())
      throw std::invalid_argument("--dims/--dtype apply to raw input only");
    in.grids = read_vdb(opt.input, opt.grid);
    if (in.grids.empty()) throw std::runtime_error(opt.input + " holds no float or double grid");
    return in;
  }
  if (opt.dtype.empty())
    throw std::invalid_argument("raw volume input needs --dtype u8|u16|f32|f64 with --dims");
  if (!opt.grid.empty()) throw std::invalid_argument("--grid applies to .vdb input only");
  in.raw = std::make_unique<MappedRawVolume>(opt.input, parse_dims(opt.dims), parse_voxel_type(opt.dtype),
                                             kMaxRawVoxels);
  in.grids.push_back(describe_view(in.raw->view(), std::filesystem::path(opt.input).stem().string()));
  in.views.push_back(in.raw->view());
  return in;
}

// The flags that decide what is coded (rate, transform, levels, brick) as the library's volume
// options, whose resolve_volume_options supplies the defaults (no rate flag: automatic): the CLI
// codes what the APIs code for the same settings.
pupwave::api::VolumeOptions volume_options(const CompressOptions& opt) {
  using pupwave::api::VolumeRate;
  if (opt.bpp > 0.0) throw std::invalid_argument("use --bpv (bits per voxel) for volumes, not --bpp");
  pupwave::api::VolumeOptions o;
  if (opt.lossless)
    o.rate = VolumeRate::lossless;
  else if (opt.bpv > 0.0)
    o.rate = VolumeRate::bpv, o.target = opt.bpv;
  else if (opt.psnr > 0.0)
    o.rate = VolumeRate::psnr, o.target = opt.psnr;
  else if (opt.step > 0.0)
    o.rate = VolumeRate::step, o.target = opt.step;
  else if (opt.max_error > 0.0)
    o.rate = VolumeRate::max_error, o.target = opt.max_error;
  else if (opt.max_error_rel > 0.0)
    o.rate = VolumeRate::max_error_rel, o.target = opt.max_error_rel;
  o.transform = opt.transform;
  o.levels = opt.levels;
  o.brick = opt.brick;
  o.fill_value = opt.fill_value;
  return o;
}

void run_compress_volume(const CompressOptions& opt) {
  if (coder_of(opt) != pupwave::api::Coder::automatic && coder_of(opt) != pupwave::api::Coder::ebcot)
    throw std::invalid_argument("--entropy applies to images only");
  if (opt.effort != 0) throw std::invalid_argument("--effort applies to image --bpp targets only");
  if (opt.tune != "psnr") throw std::invalid_argument("--tune applies to images only");
  const VolumeInput in = read_volume_input(opt);
  const std::vector<VolumeGrid>& grids = in.grids;
  VolumeEncodeOptions enc = pupwave::api::resolve_volume_options(volume_options(opt), grids, in.views).encode;
  const auto executor = make_pool_executor(opt.threads);
  enc.executor = executor.get();
  const auto start = std::chrono::steady_clock::now();
  VolumeEncodeResult r;
  {
    ElapsedLine line("pupwave: compressing " + opt.input, !opt.verbosity.quiet);
    // Chunks go to the file as they are assembled; nothing is left on failure (write_output).
    write_output(opt.output, [&](const std::filesystem::path& path) {
      OutputFile file(path, opt.output);
      r = encode_volumes(grids, in.views, enc,
                         [&](std::span<const std::uint8_t> piece) { file.write(piece); });
      file.close();
      // Before the rename or the copy into a stream: a refused stream leaves OUT as it was.
      refuse_if_strict(opt.strict, volume_target_miss(enc, r, "the stream"), opt.output);
    });
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  warn_if_missed(volume_target_miss(enc, r, stream_subject(opt.output)));
  std::FILE* status = opt.verbosity.stream();
  if (status == nullptr) return;
  if (r.switched_to_lossless)
    std::fprintf(status,
                 "pupwave: error bound %.6g on integer samples allows no error (errors are whole "
                 "numbers); coded lossless instead\n",
                 enc.target);
  std::fprintf(status,
               "%s: %zu bytes, %.4f bpv (bits per active voxel), max error %.6g, PSNR %.3f dB, %zu "
               "outlier(s), %.3f s (%zu grid(s))\n",
               opt.output.c_str(), r.size, r.bpv, r.max_error, r.psnr, r.outliers, seconds, grids.size());
}

// Why a rate target gave the lossless stream (EncodeResult::switched_to_lossless).
std::string lossless_reason(const CompressOptions& opt, const EncodeOptions& enc, const EncodeResult& r) {
  char text[160];
  if (enc.mode == RateMode::bpp && r.target_met)
    std::snprintf(text, sizeof text, "the lossless file fits --bpp %.6g", opt.bpp);
  else if (enc.mode == RateMode::bpp)  // the budget is missed either way (the warning says by how much)
    std::snprintf(text, sizeof text, "no file made for --bpp %.6g is smaller than the lossless one", opt.bpp);
  else if (enc.mode == RateMode::psnr)
    std::snprintf(text, sizeof text, "no lossy file reaching --psnr %.6g is smaller than the lossless one",
                  enc.target);
  else
    std::snprintf(text, sizeof text, "--step %.6g gives no file smaller than the lossless one", opt.step);
  return text;
}

// The flags that decide what is coded (rate, transform, levels, coder, effort) as the library's
// image options, whose resolve_image_options supplies the defaults (--psnr 40; cdf97, or cdf53
// for --lossless): the CLI codes what the APIs code for the same settings.
pupwave::api::ImageOptions image_options(const CompressOptions& opt) {
  using pupwave::api::ImageRate;
  pupwave::api::ImageOptions o;
  if (opt.lossless)
    o.rate = ImageRate::lossless;
  else if (opt.bpp > 0.0)
    o.rate = ImageRate::bpp, o.target = opt.bpp;
  else if (opt.step > 0.0)
    o.rate = ImageRate::step, o.target = opt.step;
  else if (opt.psnr > 0.0)
    o.rate = ImageRate::psnr, o.target = opt.psnr;
  o.transform = opt.transform;
  o.levels = opt.levels;
  o.coder = coder_of(opt);
  if (opt.effort != 0) o.effort = opt.effort;
  o.tune = *pupwave::api::tune_from_name(opt.tune);  // checked by the option's IsMember
  return o;
}

// ", PSNR x dB" when measured; for a float image coded in the log domain the metric the
// target used (log-PSNR) and, beside it, ordinary PSNR of the decoded image, and the count of
// non-finite samples kept.
std::string quality_text(const Image& image, const EncodeResult& r) {
  if (std::isnan(r.psnr)) return "";
  char buf[160];
  std::snprintf(buf, sizeof buf, ", %s %.3f dB", r.metric.c_str(), r.psnr);
  std::string text = buf;
  if (r.metric != "PSNR") {
    const ImageError e = compare_images(image, decode_image(r.bytes));
    std::snprintf(buf, sizeof buf, " (PSNR %.3f dB)", e.overall.psnr);
    text += buf;
  }
  if (r.nonfinite > 0) text += ", " + std::to_string(r.nonfinite) + " non-finite sample(s) kept exactly";
  return text;
}

void run_compress(const CompressOptions& opt) {
  if (!is_stdio(opt.output)) check_output_path(opt.output);
  if (is_volume_input(opt)) return run_compress_volume(opt);
  if (opt.bpv > 0.0 || opt.max_error > 0.0 || opt.max_error_rel > 0.0 || !opt.dtype.empty() ||
      !opt.grid.empty() || opt.fill_value)
    throw std::invalid_argument(
        "--bpv, --max-error, --max-error-rel, --fill-value, --dtype and --grid apply to volumes only");
  // An 8-bit binary PGM/PPM is encoded from the file mapped in place, never widened to float.
  const auto mapped = is_stdio(opt.input) ? nullptr : MappedPnm::open(opt.input);
  const Image image = mapped ? Image() : read_image(opt.input);
  const ImageView view = mapped ? mapped->view() : view_of(image);
  if (!image.metadata.not_kept.empty()) {
    std::string names;
    for (const std::string& n : image.metadata.not_kept) names += (names.empty() ? "" : ", ") + n;
    std::fprintf(stderr,
                 "warning: %zu attribute(s) of %s are not kept (only string, integer and "
                 "float attributes are stored): %s\n",
                 image.metadata.not_kept.size(), opt.input.c_str(), names.c_str());
  }
  // Only the bit-plane coder's byte-budget search has more than one effort; elsewhere the option
  // would be ignored.
  if (opt.effort != 0 && !(opt.bpp > 0.0))
    throw std::invalid_argument("--effort applies to --bpp targets only");
  if (opt.effort != 0 && coder_of(opt) != pupwave::api::Coder::ebcot)
    throw std::invalid_argument("--effort applies to the bit-plane coder: add --entropy ebcot");
  if (opt.tune != "psnr" && opt.lossless)
    throw std::invalid_argument("--tune " + opt.tune + " applies to lossy coding, not --lossless");
  EncodeOptions enc = pupwave::api::resolve_image_options(image_options(opt));
  const auto executor = make_pool_executor(opt.threads);
  enc.executor = executor.get();
  enc.measure_psnr = opt.report_psnr;
  enc.keep_nonfinite = opt.keep_nonfinite;
  enc.transfer = opt.transfer == "linear"     ? Transfer::linear
                 : opt.transfer == "adaptive" ? Transfer::log2_adaptive
                                              : Transfer::log2;
  if (!image.metadata.empty()) enc.metadata = &image.metadata;
  const auto start = std::chrono::steady_clock::now();
  const EncodeResult r = [&] {
    ElapsedLine line("pupwave: compressing " + opt.input, !opt.verbosity.quiet);
    return pupwave::api::encode_resolved(view, enc, coder_of(opt));
  }();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  refuse_if_strict(opt.strict, image_target_miss(enc, r, "the stream"), opt.output);
  write_output_bytes(opt.output, r.bytes);
  warn_if_missed(image_target_miss(enc, r, stream_subject(opt.output)));
  std::FILE* status = opt.verbosity.stream();
  if (status == nullptr) return;
  if (r.switched_to_lossless)
    std::fprintf(status, "pupwave: %s; coded lossless instead\n", lossless_reason(opt, enc, r).c_str());
  // Only when measured; float images name their metric (log-PSNR) beside ordinary PSNR.
  const std::string psnr = std::isinf(r.psnr) ? std::string(", lossless (PSNR inf)") : quality_text(image, r);
  std::fprintf(status, "%s: %zu bytes, %.4f bpp%s, %.3f s (%zux%zu, %zu channel(s), %s)\n",
               opt.output.c_str(), r.bytes.size(), r.bpp, psnr.c_str(), seconds, view.width, view.height,
               view.channels, to_string(view.type).c_str());
  if (opt.verbosity.verbose)
    std::fprintf(status, "  transform %s, %s coder, base step %.6g\n",
                 r.switched_to_lossless ? "cdf53" : enc.transform.c_str(),
                 to_string(parse_container(r.bytes).header.entropy), r.base_step);
}

}  // namespace

void add_compress_command(CLI::App& app) {
  auto opt = std::make_shared<CompressOptions>();
  auto* cmd =
      app.add_subcommand("compress",
                         "Compress an image (default: cdf97, --psnr 40) or a volume (.vdb, or raw with "
                         "--dims/--dtype; default: lossless for u8/u16, --max-error-rel 1e-3 for float) "
                         "to a .pw stream. '-' as IN or OUT is stdin or stdout (status then goes to "
                         "stderr). For 8/16-bit images no rate target gives a file larger than "
                         "--lossless: the encoder then codes lossless and says so");
  cmd->add_option("IN", opt->input,
                  "input image (PNG, TIFF, EXR, PNM, ...) or volume (.vdb, raw), or - for stdin")
      ->required()
      ->check(existing_file_or_stdin());
  cmd->add_option("OUT", opt->output, "output .pw file, or - for stdout")->required();
  cmd->add_option("--transform", opt->transform, "transform spec (cdf97, cdf53, pups:..., kobbelt:...)");
  cmd->add_option("--levels", opt->levels,
                  "decomposition levels (default: from the image size; at most what halves the shortest "
                  "axis down to one sample)")
      ->check(CLI::Range(0, 32));
  auto* bpp =
      cmd->add_option("--bpp", opt->bpp, "target bits per pixel (whole file)")->check(positive_number());
  auto* psnr = cmd->add_option("--psnr", opt->psnr,
                               "target PSNR in dB (all channels; log-PSNR for half/float images, see "
                               "--transfer): the smallest file that reaches it (at most "
                               "0.15 dB above); float images: at most 120 dB")
                   ->check(positive_number());
  auto* step = cmd->add_option("--step", opt->step,
                               "fixed quantizer base step (sample units); float images: at least 2^-24 of "
                               "the value range")
                   ->check(positive_number());
  auto* lossless = cmd->add_flag("--lossless", opt->lossless, "bit-exact (cdf53 integer transform, RCT)");
  auto* bpv =
      cmd->add_option("--bpv", opt->bpv,
                      "volumes: target bits per active voxel (whole file; active tiles count their voxels)")
          ->check(positive_number());
  auto* max_error =
      cmd->add_option("--max-error", opt->max_error,
                      "float volumes: absolute point-wise error bound E, guaranteed on every active voxel "
                      "(integer volumes: E below 1 allows no error and codes lossless)")
          ->check(positive_number());
  auto* max_error_rel =
      cmd->add_option("--max-error-rel", opt->max_error_rel,
                      "float volumes: the bound as a fraction R of the value range (E = R * (max - min))")
          ->check(positive_number());
  bpp->excludes(psnr, step, lossless, bpv, max_error, max_error_rel);
  psnr->excludes(step, lossless, bpv, max_error, max_error_rel);
  step->excludes(lossless, bpv, max_error, max_error_rel);
  lossless->excludes(bpv, max_error, max_error_rel);
  bpv->excludes(max_error, max_error_rel);
  max_error->excludes(max_error_rel);
  cmd->add_option("--fill-value", opt->fill_value,
                  "dense volumes: voxels equal to V are missing values (as NaN and infinities always are): "
                  "restored exactly, outside the error bound, the value range and the statistics");
  cmd->add_option("--dims", opt->dims, "raw volume input: X,Y,Z (x fastest)");
  cmd->add_option("--dtype", opt->dtype, "raw volume input: u8, u16, f32 or f64 (little endian)");
  cmd->add_option("--grid", opt->grid, ".vdb input: compress only the grids of this name");
  cmd->add_option("--brick", opt->brick, "volumes: brick edge (power of two, 8..256, default 64)");
  cmd->add_option(
         "--entropy", opt->entropy,
         "entropy coder: auto (the default: lc for --lossless, else pc or ebcot as below), pc (lossy only, "
         "the default for rate targets on images of up to 4 "
         "Mpixel: one pass per band with parent contexts, chroma from luma and rate-distortion optimised "
         "quantization; about 10% fewer bits than ebcot at equal PSNR on photographs; holds the "
         "transformed image), ebcot (bit-plane, the default for larger images: encodes 8-bit "
         "PGM/PPM by strips in bounded memory), ht (high-throughput, no arithmetic coding), or lc "
         "(lossless only, the default with --lossless: weighted prediction and context modelling, the "
         "smallest lossless files)")
      ->transform(coder_option());
  cmd->add_option("--effort", opt->effort,
                  "images, --bpp, --entropy ebcot: 1 (default, fastest) or 2 (three base steps per band and "
                  "RDOQ: about 1% smaller at equal PSNR, up to 1.9x the encode time)")
      ->check(CLI::Range(1, 2));
  cmd->add_option(
         "--tune", opt->tune,
         "images, lossy: what the coding minimises: psnr (default: the squared error, the best PSNR "
         "at a size) or visual (a contrast-sensitivity-weighted error with less weight on chroma: "
         "better butteraugli and MS-SSIM at a size, lower PSNR); --bpp and --psnr targets hold in both")
      ->transform(CLI::IsMember({"psnr", "visual"}, CLI::ignore_case));
  cmd->add_flag("--keep-nonfinite", opt->keep_nonfinite,
                "float images: code NaN and infinite samples exactly in a side list (default: refuse them)");
  cmd->add_option(
         "--transfer", opt->transfer,
         "float images: coding domain, log (default: log2 of the value, --psnr is log-PSNR with peak "
         "1 stop), adaptive (log2 with an offset chosen per image: more bits to highlights, higher "
         "PSNR in linear light; --psnr is adaptive log-PSNR) or linear (--psnr against the value range)")
      ->transform(CLI::IsMember({"log", "adaptive", "linear"}, CLI::ignore_case));
  cmd->add_option("--threads", opt->threads, "worker threads (0: all cores)");
  cmd->add_flag("--report-psnr", opt->report_psnr,
                "images: decode the stream in memory and report its PSNR against the input (costs about "
                "a decode; --psnr targets always report it)");
  cmd->add_flag("--strict", opt->strict,
                "a missed rate target (--bpp, --psnr, --bpv) is an error: nothing is written and an "
                "existing OUT stays as it was. Without it the file is written and a line starting "
                "'warning:' on stderr (--quiet too) says what it reached");
  add_verbosity_flags(*cmd, opt->verbosity);
  cmd->callback([opt] {
    CompressOptions o = *opt;
    o.verbosity.to_stderr = is_stdio(o.output);
    const InputPath in(o.input);
    o.input = in.path;
    run_compress(o);
  });
}

}  // namespace pupwave::cli
