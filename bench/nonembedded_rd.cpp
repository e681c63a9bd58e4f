// What a NON-EMBEDDED context coder would give for lossy images, measured before any
// format work. Each photograph goes through the codec's own colour transform and cdf97 transform
// (plan_image / transform_all_components, every band one block), every band is dead-zone
// quantized at the codec's per-band steps (set_base_step) and coded in full in one pass, and the
// base step is bisected to the largest stream within each rate. Coders (--coders):
//   coef   the volume codec's coefficient coder (coef_encoder.h), real codewords
//   lc0    the lossless lc coder (lc_blocks.h) on the indices, without the parent band, real
//   lc     the same with the parent coefficient one level coarser in the context, real
//   coef0  code length of coef's model (nonembedded_coef.h), the coarse band the smaller of lc/coef
//   coefp  the same with the parent in the place of the volume coder's z-1 neighbour (--pw)
//   est    code length of lc's model (nonembedded_model.h) with --pw / --scale / --ring / --psign
// Knobs: --round R (index = floor(|x| / step + R)), --delta D (reconstruction offset; default
// 0.4375 - R), --zero T (isolated +-1 below 1 + T steps dropped), --lambda L (greedy RDOQ of
// coef0 / coefp / est: index-unit squared error per bit). A code length is the exact sum of
// -log2 p under the adaptive models (EST_COMPARE=1 prints it next to the real coder's bytes per
// band for est and coef0: equal but for the range coder's 0-2 flush bytes). Rates are codeword
// bytes plus the container (header with the per-band steps, block index), PSNR that of the
// dequantized, inverse-transformed image. The same binary's default encoder (encode_image
// --bpp, effort 1 and 2) gives the reference curves, and the BD-rate of each coder against
// effort 1 is printed (tools/bench/bd_metrics.h, the harness's method).
// --families L: coef0 / coefp with --lambda also choose a step per band among x 2^(-1/3), 1,
// 2^(1/3) by output error + L x bits (did not pay: bench/results/rd_issue20.md).
// --verify: coef0 / coefp also write the real codewords of every final point (range coder, these
// contexts) and decode them, printing real against estimated bytes and decode mismatches.
// Run: build/bench/nonembedded_rd [--bpp LIST] [--coders LIST] [knobs] [--families L] [--verify]
// [--no-reference] IMAGES/DIRS
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "codec/entropy/coef_encoder.h"
#include "codec/entropy/lc_blocks.h"
#include "codec/entropy/pc_blocks.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_components.h"
#include "codec/image/image_encoder_lc.h"
#include "codec/image/image_plan.h"
#include "codec/image/lc_parent.h"
#include "image_list.h"
#include "nonembedded_coef.h"
#include "nonembedded_model.h"
#include "tools/bench/bd_metrics.h"
#include "tools/image_io.h"
#include "transforms/separable.h"

namespace {
namespace fs = std::filesystem;
using namespace pupwave;
using bench::RdPoint;

struct Args {
  std::vector<double> bpps{0.125, 0.25, 0.5, 1.0, 2.0};
  std::vector<std::string> coders{"coef", "lc0", "lc"};
  double zero = 0.0;          // isolated +-1 indices below 1 + zero (index units) become 0 (0: off)
  double round = 0.0;         // index = floor(|x| / step + round): 0 is the codec's dead-zone quantizer
  double delta = -1.0;        // reconstruction offset; negative: the codec's 0.4375 less `round`
  estimate::BandOptions est;  // the `est` coder's knobs
  bool reference = true;
  bool verify = false;         // coef0 / coefp: real codewords of the final points, decoded and compared
  bool families = false;       // coef0 / coefp with --lambda: a step per band (x 2^(-1/3), 1, 2^(1/3))
  double family_lambda = 0.1;  // the slope the families are chosen at (base-step units per bit)
  std::vector<fs::path> images;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    if (s == "--bpp" && i + 1 < argc) {
      a.bpps = bench::number_list(argv[++i]);
    } else if (s == "--coders" && i + 1 < argc) {
      a.coders = bench::split_list(argv[++i]);
    } else if (s == "--zero" && i + 1 < argc) {
      a.zero = std::stod(argv[++i]);
    } else if (s == "--round" && i + 1 < argc) {
      a.round = std::stod(argv[++i]);
    } else if (s == "--delta" && i + 1 < argc) {
      a.delta = std::stod(argv[++i]);
    } else if (s == "--pw" && i + 1 < argc) {
      a.est.parent_weight = std::stoi(argv[++i]);
    } else if (s == "--scale" && i + 1 < argc) {
      a.est.scale = std::stoi(argv[++i]);
    } else if (s == "--ring") {
      a.est.parent_ring = true;
    } else if (s == "--psign") {
      a.est.parent_sign = true;
    } else if (s == "--lambda" && i + 1 < argc) {
      a.est.lambda = std::stod(argv[++i]);
    } else if (s == "--families" && i + 1 < argc) {
      a.families = true;
      a.family_lambda = std::stod(argv[++i]);
    } else if (s == "--verify") {
      a.verify = true;
    } else if (s == "--no-reference") {
      a.reference = false;
    } else if (!s.empty() && s[0] == '-') {
      throw std::invalid_argument("unknown option " + s);
    } else {
      bench::add_images(s, a.images);
    }
  }
  if (a.images.empty())
    throw std::invalid_argument(
        "usage: nonembedded_rd [--bpp LIST] [--coders coef,lc0,lc] [--zero T] IMAGES");
  return a;
}

// The volume coder's real codeword of signed indices v.
CoefCodeword coef_codeword(const std::vector<std::int32_t>& v, const Extent& size) {
  std::vector<std::uint32_t> index(v.size());
  std::vector<std::uint8_t> negative(v.size());
  for (std::size_t k = 0; k < v.size(); ++k) {
    index[k] = std::uint32_t(std::abs(v[k]));
    negative[k] = v[k] < 0;
  }
  return encode_coefficients(index, negative, size);
}

// One photograph, transformed once; each trial quantizes and codes it at a base step.
class Trial {
 public:
  Trial(const Image& image, const Args& args) : image_(image), view_(view_of(image_)), args_(args) {
    EncodeOptions o;
    o.mode = RateMode::step;
    o.target = 1.0;
    o.block_size = kLcBlockSize;  // every band one block: the models learn over the whole band
    plan_ = plan_image(view_, o);
    transform_all_components(plan_);
    for (const auto& b : plan_.bands) require(b.size[0] <= 1024 && b.size[1] <= 1024, "band over 1024");
    for (const auto& b : plan_.blocks) require(b.size == plan_.bands[b.band].size, "band split in blocks");
  }

  // Bytes of the whole stream with `coder` at `base` (quantizes into q_).
  std::size_t bytes(double base, const std::string& coder) {
    quantize(base);
    verify_ = {};
    const Extent& dims = plan_.header.dims;
    std::vector<BlockEntry> entries(plan_.blocks.size());
    std::vector<std::vector<std::uint8_t>> words(plan_.blocks.size());
    for (std::size_t i = 0; i < plan_.blocks.size(); ++i) {
      const CodeBlock& b = plan_.blocks[i];
      std::vector<std::int32_t> v(b.count());
      copy_block_out(q_[b.component].data(), dims, b, v.data());
      if (coder == "est" && b.orientation != 0 && std::getenv("EST_COMPARE")) {
        std::vector<std::int32_t> w = v;
        const std::size_t e = est_band(b, w);
        const LcParent lp = lc_parent(plan_.bands, b, q_[b.component].data(), dims[0], nullptr);
        std::fprintf(stderr, "band %u c %u est %zu real %zu\n", b.band, b.component, e,
                     lc_encode_block(v, b.size[0], b.size[1], false, lp).bytes.size());
      }
      if ((coder == "coefp" || coder == "coef0") && b.orientation != 0) {
        const LcParent lp = lc_parent(plan_.bands, b, q_[b.component].data(), dims[0], nullptr);
        const double bits = coef_est_band(b, v, coder == "coefp" ? lp : LcParent{});
        words[i].assign(bits > 0.0 ? std::size_t(std::ceil(bits / 8.0)) : 0, 0);
        entries[i] = {1, 1, std::uint32_t(words[i].size())};
        if (std::getenv("EST_COMPARE")) {
          std::fprintf(stderr, "band %u c %u est %zu real %zu\n", b.band, b.component, words[i].size(),
                       coef_codeword(v, b.size).bytes.size());
        }
      } else if (coder == "est" && b.orientation != 0) {
        words[i].assign(est_band(b, v), 0);
        entries[i] = {1, 1, std::uint32_t(words[i].size())};
      } else if (coder == "coef") {
        CoefCodeword w = coef_codeword(v, b.size);
        entries[i] = {w.bits, w.bits > 0 ? 1 : 0, std::uint32_t(w.bytes.size())};
        words[i] = std::move(w.bytes);
      } else {
        const std::int32_t* first = b.component > 0 ? q_[0].data() : nullptr;
        const std::int32_t* previous = b.component > 1 ? q_[b.component - 1].data() : nullptr;
        LcParent parent = lc_parent(plan_.bands, b, q_[b.component].data(), dims[0], first, previous);
        if (coder == "lc0" && b.orientation != 0) parent = LcParent{};
        LcCodeword w = lc_encode_block(v, b.size[0], b.size[1], b.orientation == 0, parent);
        entries[i] = {w.planes, w.planes > 0 ? 1 : 0, std::uint32_t(w.bytes.size())};
        words[i] = std::move(w.bytes);
        if (coder != "lc" && coder != "lc0") {  // the coarse band: the smaller of lc and coef (+1 bit)
          CoefCodeword c = coef_codeword(v, b.size);
          if (c.bytes.size() + 1 < words[i].size()) {
            entries[i] = {c.bits, c.bits > 0 ? 1 : 0, std::uint32_t(c.bytes.size() + 1)};
            words[i].assign(c.bytes.size() + 1, 0);
          }
        }
      }
    }
    return assemble(plan_, entries, words).size();
  }

  // PSNR of the image decoded from the last quantization.
  double psnr() {
    const Extent& dims = plan_.header.dims;
    const float delta = this->delta();
    std::vector<std::vector<float>> planes(q_.size());
    for (std::size_t c = 0; c < q_.size(); ++c) {
      planes[c].assign(q_[c].size(), 0.0f);
      for (std::size_t i = 0; i < plan_.blocks.size(); ++i) {
        const CodeBlock& b = plan_.blocks[i];
        if (b.component != c) continue;
        const float step = plan_.header.steps[c * plan_.bands.size() + b.band];
        std::vector<std::int32_t> v(b.count());
        copy_block_out(q_[c].data(), dims, b, v.data());
        std::vector<float> r(v.size());
        for (std::size_t k = 0; k < v.size(); ++k)
          r[k] = v[k] == 0 ? 0.0f : (float(v[k]) + (v[k] < 0 ? -delta : delta)) * step;
        copy_block_in(r.data(), dims, b, planes[c].data());
      }
      inverse(*plan_.transform, planes[c].data(), dims, plan_.header.levels);
    }
    return components_psnr(view_, planes, plan_.header.colour);
  }

  double pixels() const { return double(plan_.pixels); }

  // Estimated codeword bytes of detail band block b (indices v; RDOQ writes its choice back).
  std::size_t est_band(const CodeBlock& b, std::vector<std::int32_t>& v) {
    const Extent& dims = plan_.header.dims;
    const float inv = 1.0f / plan_.header.steps[b.component * plan_.bands.size() + b.band];
    std::vector<float> u(b.count());
    copy_block_out(plan_.coef[b.component].data(), dims, b, u.data());
    for (float& x : u) x *= inv;
    estimate::ParentBand parent;
    const LcParent lp = lc_parent(plan_.bands, b, q_[b.component].data(), dims[0], nullptr);
    if (lp.origin) {
      parent = {lp.origin, lp.stride, lp.width, lp.height};
      require(lp.x0 == 0 && lp.y0 == 0, "band offset");
    }
    estimate::BandOptions o = args_.est;
    o.delta = delta();
    const double bits = estimate::band_bits(v, u, b.size[0], b.size[1], parent, o);
    copy_block_in(v.data(), dims, b, q_[b.component].data());    // the children's parent
    return bits > 0.0 ? std::size_t(std::ceil(bits / 8.0)) : 0;  // the flush adds 0-1 byte (checked)
  }

  // The same under the volume coder's model (nonembedded_coef.h), the parent in `lp` or none.
  double coef_est_band(const CodeBlock& b, std::vector<std::int32_t>& v, const LcParent& lp) {
    const Extent& dims = plan_.header.dims;
    const float inv = 1.0f / plan_.header.steps[b.component * plan_.bands.size() + b.band];
    std::vector<float> u(b.count());
    copy_block_out(plan_.coef[b.component].data(), dims, b, u.data());
    for (float& x : u) x *= inv;
    const PcContext ctx(b.size[0], b.size[1], LcParent{lp.origin, lp.stride, lp.width, lp.height}, PcLuma{},
                        args_.est.parent_weight, args_.est.scale);
    double bits = 0.0;
    if (args_.families && args_.est.lambda > 0.0) {
      // Per-band step families: the step x 2^(-1/3), 1, 2^(1/3) with the least output error +
      // lambda x bits (error in base-step units: index-unit error x the multiplier squared;
      // RDOQ in the band at lambda / multiplier^2), coarse bands first so children see the choice.
      float& step = plan_.header.steps[b.component * plan_.bands.size() + b.band];
      const float base_step = step;
      double best = 1e300;
      std::vector<std::int32_t> best_v;
      float best_step = base_step;
      for (double e : {-1.0 / 3.0, 0.0, 1.0 / 3.0}) {
        const double mult = std::exp2(e);
        std::vector<float> um(u.size());
        for (std::size_t k = 0; k < u.size(); ++k) um[k] = float(u[k] / mult);
        std::vector<std::int32_t> vm(v.size());
        const double b_bits = estimate::coef_band_bits(vm, b.size[0], b.size[1], ctx, um,
                                                       args_.est.lambda / (mult * mult), delta());
        double d = 0.0;
        for (std::size_t k = 0; k < um.size(); ++k) {
          const double r = vm[k] == 0 ? 0.0 : double(std::abs(vm[k])) + double(delta());
          d += (std::fabs(double(um[k])) - r) * (std::fabs(double(um[k])) - r);
        }
        const double j = d * mult * mult + args_.family_lambda * b_bits;
        if (j < best) {
          best = j;
          bits = b_bits;
          best_v = std::move(vm);
          best_step = float(base_step * mult);
        }
      }
      v = std::move(best_v);
      step = best_step;
    } else {
      bits = estimate::coef_band_bits(v, b.size[0], b.size[1], ctx, u, args_.est.lambda, delta());
    }
    if (args_.verify && bits > 0.0) {  // real codeword and its decode, contexts from the same parents
      const std::vector<std::uint8_t> word = estimate::coef_band_encode(v, b.size[0], b.size[1], ctx);
      verify_.real += word.size();
      verify_.estimated += std::size_t(std::ceil(bits / 8.0));
      verify_.mismatches += estimate::coef_band_decode(word, b.size[0], b.size[1], ctx) != v;
      if (args_.est.parent_weight == 1 && args_.est.scale == 1) {  // the codec's copy (pc_blocks.h)
        std::vector<std::int32_t> copy = v;
        verify_.codec_differs += pc_encode_block(copy, b.size[0], b.size[1], lp).bytes != word;
        if (args_.est.lambda > 0.0 && !args_.families) {  // and its RDOQ from the coefficients
          const PcRdoq rdoq{u, args_.est.lambda, double(delta())};
          std::vector<std::int32_t> chosen(v.size());
          verify_.codec_differs += pc_encode_block(chosen, b.size[0], b.size[1], lp, &rdoq).bytes != word;
          verify_.codec_differs += chosen != v;
        }
      }
      ++verify_.bands;
    }
    copy_block_in(v.data(), dims, b, q_[b.component].data());  // the children's parent
    return bits;
  }

  // --verify: totals of the last bytes() call.
  struct Verify {
    std::size_t real = 0, estimated = 0, bands = 0, mismatches = 0, codec_differs = 0;
  };
  const Verify& verified() const { return verify_; }

  float delta() const {
    return float(args_.delta >= 0.0 ? args_.delta : std::max(0.0, plan_.header.delta - args_.round));
  }

 private:
  static void require(bool ok, const char* what) {
    if (!ok) throw std::runtime_error(what);
  }

  void quantize(double base) {
    set_base_step(plan_, base);
    const Extent& dims = plan_.header.dims;
    q_.resize(plan_.coef.size());
    for (std::size_t c = 0; c < plan_.coef.size(); ++c) {
      q_[c].assign(plan_.coef[c].size(), 0);
      for (const CodeBlock& b : plan_.blocks) {
        if (b.component != c) continue;
        const float inv = 1.0f / plan_.header.steps[c * plan_.bands.size() + b.band];
        std::vector<float> v(b.count());
        copy_block_out(plan_.coef[c].data(), dims, b, v.data());
        std::vector<std::int32_t> q(v.size());
        for (std::size_t k = 0; k < v.size(); ++k) {
          const auto m = std::int32_t(std::fabs(v[k]) * inv + float(args_.round));
          q[k] = v[k] < 0 ? -m : m;
        }
        if (args_.zero > 0.0 && b.orientation != 0) zero_isolated(v, q, inv, b.size[0], b.size[1]);
        copy_block_in(q.data(), dims, b, q_[c].data());
      }
    }
  }

  // RDOQ-style: a +-1 index with no nonzero index among its 8 neighbours, whose magnitude is
  // below 1 + zero steps, is dropped (its cost in bits far exceeds its distortion gain).
  void zero_isolated(const std::vector<float>& v, std::vector<std::int32_t>& q, float inv, std::size_t w,
                     std::size_t h) const {
    const std::vector<std::int32_t> before = q;
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) {
        const std::size_t k = y * w + x;
        if (std::abs(before[k]) != 1 ||
            std::fabs(v[k]) * inv + float(args_.round) >= 1.0f + float(args_.zero))
          continue;
        bool alone = true;
        for (std::size_t yy = y > 0 ? y - 1 : 0; yy <= std::min(h - 1, y + 1) && alone; ++yy)
          for (std::size_t xx = x > 0 ? x - 1 : 0; xx <= std::min(w - 1, x + 1); ++xx)
            if ((yy != y || xx != x) && before[yy * w + xx] != 0) alone = false;
        if (alone) q[k] = 0;
      }
  }

  Image image_;
  ImageView view_;
  const Args& args_;
  ImagePlan plan_;
  std::vector<std::vector<std::int32_t>> q_;  // signed indices per component, Mallat layout
  Verify verify_;
};

// The largest stream within `bpp`: bisection of log(base step).
RdPoint at_rate(Trial& t, const std::string& coder, double bpp) {
  double lo = std::log(0.05), hi = std::log(2000.0);  // small step: too big; large: fits
  double best = hi;
  std::size_t best_bytes = 0;
  for (int it = 0; it < 22; ++it) {
    const double mid = 0.5 * (lo + hi);
    const std::size_t n = t.bytes(std::exp(mid), coder);
    if (double(n) * 8.0 / t.pixels() <= bpp) {
      hi = mid;
      best = mid;
      best_bytes = n;
    } else {
      lo = mid;
    }
  }
  t.bytes(std::exp(best), coder);
  if (t.verified().bands > 0)
    std::fprintf(stderr,
                 "verify %s %g bpp: %zu bands, estimated %zu bytes, real %zu, decode mismatches %zu, "
                 "pc_blocks codewords differing %zu\n",
                 coder.c_str(), bpp, t.verified().bands, t.verified().estimated, t.verified().real,
                 t.verified().mismatches, t.verified().codec_differs);
  return {double(best_bytes) * 8.0 / t.pixels(), t.psnr()};
}

}  // namespace

int main(int argc, char** argv) try {
  const Args args = parse(argc, argv);
  std::map<std::string, std::map<std::string, std::vector<RdPoint>>> curves;  // coder -> image -> points
  std::vector<std::string> names;
  for (const fs::path& path : args.images) {
    const Image image = cli::read_image(path);
    const std::string name = path.stem().string();
    names.push_back(name);
    if (args.reference)
      for (int effort : {1, 2}) {
        const std::string label = "default_e" + std::to_string(effort);
        for (double bpp : args.bpps) {
          EncodeOptions o;
          o.mode = RateMode::bpp;
          o.target = bpp;
          o.effort = effort;
          const EncodeResult r = encode_image(image, o);
          curves[label][name].push_back({r.bpp, r.psnr});
          std::printf("%s,%s,%g,%.5f,%.4f\n", name.c_str(), label.c_str(), bpp, r.bpp, r.psnr);
        }
      }
    Trial trial(image, args);
    for (const std::string& coder : args.coders)
      for (double bpp : args.bpps) {
        const RdPoint p = at_rate(trial, coder, bpp);
        curves[coder][name].push_back(p);
        std::printf("%s,%s,%g,%.5f,%.4f\n", name.c_str(), coder.c_str(), bpp, p.bpp, p.psnr);
      }
    std::fflush(stdout);
  }
  if (!args.reference) return 0;
  std::printf("\nBD-rate %% against default_e1 (negative: fewer bits)\n| coder | mean |");
  for (const auto& n : names) std::printf(" %s |", n.c_str());
  std::printf("\n");
  for (const auto& [coder, per] : curves) {
    double sum = 0.0;
    std::string cells;
    for (const auto& n : names) {
      const double d = bench::bd_rate(curves["default_e1"][n], per.at(n));
      sum += d;
      char buf[32];
      std::snprintf(buf, sizeof buf, " %+.2f |", d);
      cells += buf;
    }
    std::printf("| %s | %+.2f |%s\n", coder.c_str(), sum / double(names.size()), cells.c_str());
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "nonembedded_rd: %s\n", e.what());
  return 1;
}
