// `pupwave filters search`: ranks PUPs designs over the parameters the seeds allow by the
// AR(1) coding gain of their multi-level transform, optionally re-ranking the best with the
// real codec on images (BD-PSNR against CDF 9/7). Method and results: docs/pups.md.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "codec/image/image_codec.h"
#include "tools/bench/bd_metrics.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/filters_report.h"
#include "tools/image_io.h"
#include "transforms/analysis/merit.h"
#include "transforms/pups/pups_transform.h"
#include "transforms/pups/search.h"

namespace pupwave::cli {

namespace {

struct SearchOptions {
  std::string weight = "cinpact-interp";
  std::string c = "3:9:0.5";
  std::vector<double> sigma_scales{1.0};
  bool leak_free_sigma = false;
  std::vector<int> degrees{1, 2, 3, 4, 5};
  int moments = 4;
  std::vector<double> mask_t{2.0, 2.25, 2.5, 2.75, 3.0, 3.25, 3.5};
  int poly_degree = 16;
  std::vector<int> extensions{0, 8, 16, 32};
  std::vector<std::string> boundaries{"hss", "wss"};
  std::string objective = "cg";
  std::vector<std::string> images;
  std::vector<double> bpp{0.125, 0.25, 0.5, 1, 2};
  int rerank = 5;
  int top = 10;
};

struct Ranked {
  std::string body;
  merit::Merit merit;
  double bd_psnr = std::nan("");  // against CDF 9/7, images objective only
};

pups::SearchSpace to_space(const SearchOptions& o) {
  pups::SearchSpace s;
  s.weight = pups::weight_kind_from_string(o.weight);
  std::vector<double> c;
  std::istringstream in(o.c);
  for (std::string item; std::getline(in, item, ':');) {
    std::size_t used = 0;
    try {
      c.push_back(std::stod(item, &used));
    } catch (const std::logic_error&) {
      used = 0;
    }
    if (used == 0 || used != item.size())
      throw std::invalid_argument("--c needs LO:HI:STEP, got '" + o.c + "'");
  }
  if (c.size() != 3) throw std::invalid_argument("--c needs LO:HI:STEP, got '" + o.c + "'");
  s.c_lo = c[0], s.c_hi = c[1], s.c_step = c[2];
  s.sigma_scales = o.sigma_scales;
  s.leak_free_sigma = o.leak_free_sigma;
  s.degrees = o.degrees;
  s.moments = o.moments;
  s.mask_params = o.mask_t;
  s.poly_degree = o.poly_degree;
  s.extensions = o.extensions;
  s.boundaries.clear();
  for (const auto& b : o.boundaries) {
    if (b != "hss" && b != "wss") throw std::invalid_argument("--boundary takes hss and/or wss");
    s.boundaries.push_back(b == "wss" ? pups::BoundaryRule::line_wss : pups::BoundaryRule::wire_hss);
  }
  return s;
}

// Coding gain (and the cheap figures) of every candidate, best first.
std::vector<Ranked> rank_by_coding_gain(const std::vector<std::string>& bodies) {
  merit::MeritOptions o;
  o.condition = false;
  std::vector<Ranked> out;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    out.push_back({bodies[i], merit::figures_of_merit(*make_pups_transform_from_spec(bodies[i]), o)});
    std::cerr << "search: " << i + 1 << "/" << bodies.size() << " designs measured\r" << std::flush;
  }
  std::cerr << '\n';
  std::stable_sort(out.begin(), out.end(), [](const Ranked& a, const Ranked& b) {
    return a.merit.coding_gain_db > b.merit.coding_gain_db;
  });
  return out;
}

// The codec's rate-distortion curve of one image (in-process, rate control by bpp).
std::vector<bench::RdPoint> codec_curve(const Image& image, const std::string& spec,
                                        const std::vector<double>& bpp) {
  std::vector<bench::RdPoint> curve;
  for (double b : bpp) {
    EncodeOptions e;
    e.transform = spec;
    e.mode = RateMode::bpp;
    e.target = b;
    const EncodeResult r = encode_image(image, e);
    curve.push_back({r.bpp, r.psnr});
  }
  return curve;
}

// Mean BD-PSNR against CDF 9/7 over the images, for the first `count` designs; re-sorted.
void rerank_on_images(std::vector<Ranked>& ranked, const SearchOptions& o) {
  std::vector<Image> images;
  for (const auto& path : o.images) images.push_back(read_image(path));
  std::vector<std::vector<bench::RdPoint>> anchor;
  for (const Image& im : images) anchor.push_back(codec_curve(im, "cdf97", o.bpp));
  const std::size_t count = std::min<std::size_t>(ranked.size(), static_cast<std::size_t>(o.rerank));
  for (std::size_t i = 0; i < count; ++i) {
    double sum = 0;
    for (std::size_t k = 0; k < images.size(); ++k)
      sum += bench::bd_psnr(anchor[k], codec_curve(images[k], "pups:" + ranked[i].body, o.bpp));
    ranked[i].bd_psnr = sum / static_cast<double>(images.size());
    std::cerr << "search: " << i + 1 << "/" << count << " designs coded\r" << std::flush;
  }
  std::cerr << '\n';
  std::stable_sort(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(count),
                   [](const Ranked& a, const Ranked& b) { return a.bd_psnr > b.bd_psnr; });
}

void print_ranking(const std::vector<Ranked>& ranked, const SearchOptions& o) {
  const bool images = o.objective == "images";
  std::cout << "rank  " << (images ? "BD-PSNR vs cdf97 (dB)  " : "") << "figures  spec\n";
  const std::size_t n = std::min<std::size_t>(ranked.size(), static_cast<std::size_t>(o.top));
  for (std::size_t i = 0; i < n; ++i) {
    const Ranked& r = ranked[i];
    std::cout << i + 1 << "  ";
    if (images) std::cout << (std::isnan(r.bd_psnr) ? std::string("not coded") : fmt(r.bd_psnr, 3)) << "  ";
    std::cout << merit_summary(r.merit) << "\n   pups:" << r.body << '\n';
  }
  if (!ranked.empty()) std::cout << "best: pups:" << ranked.front().body << '\n';
}

void run_search(const SearchOptions& o) {
  if (o.objective == "images" && o.images.empty())
    throw std::invalid_argument("--objective images needs --images FILE...");
  std::vector<std::string> skipped;
  const std::vector<std::string> bodies = pups::search_candidates(to_space(o), &skipped);
  for (const auto& s : skipped) std::cerr << "search: skipped " << s << '\n';
  if (bodies.empty()) throw std::invalid_argument("search: no design in the given ranges could be built");
  std::vector<Ranked> ranked = rank_by_coding_gain(bodies);
  if (o.objective == "images") rerank_on_images(ranked, o);
  print_ranking(ranked, o);
}

}  // namespace

void add_search(CLI::App& filters) {
  auto o = std::make_shared<SearchOptions>();
  auto* cmd = filters.add_subcommand(
      "search",
      "Rank PUPs designs by coding gain (and optionally by the codec on images); prints transform specs");
  cmd->add_option("--weight", o->weight, "weight family")
      ->capture_default_str()
      ->check(CLI::IsMember({"bspline", "polynomial", "cinpact", "cinpact-interp"}));
  cmd->add_option("--c", o->c, "CINPACT support radius range LO:HI:STEP")->capture_default_str();
  cmd->add_option("--sigma-scale", o->sigma_scales, "sigma as multiples of the least-error sigma of each c")
      ->delimiter(',');
  cmd->add_flag("--leak-free-sigma", o->leak_free_sigma, "instead: every sigma with B.1 = 0 (no DC leak)");
  cmd->add_option("--degree", o->degrees, "B-spline degrees")->delimiter(',');
  cmd->add_option("--moments", o->moments, "polynomial: vanishing moments of the mask")
      ->capture_default_str();
  cmd->add_option("--mask-t", o->mask_t, "polynomial: mask parameters t")->delimiter(',');
  cmd->add_option("--poly-degree", o->poly_degree, "polynomial: degree of the weight")->capture_default_str();
  cmd->add_option("--l", o->extensions, "bandwidth extensions l (even)")->delimiter(',');
  cmd->add_option("--boundary", o->boundaries, "boundary rules: hss, wss")->delimiter(',');
  cmd->add_option("--objective", o->objective, "cg (AR(1) coding gain) or images (re-rank with the codec)")
      ->capture_default_str()
      ->check(CLI::IsMember({"cg", "images"}));
  cmd->add_option("--images", o->images, "images for --objective images")->check(CLI::ExistingFile);
  cmd->add_option("--bpp", o->bpp, "rates for --objective images")->delimiter(',');
  cmd->add_option("--rerank", o->rerank, "how many of the best by coding gain to code")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  cmd->add_option("--top", o->top, "how many designs to print")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  add_report_verbosity_flags(*cmd);
  cmd->callback([o] { run_search(*o); });
}

}  // namespace pupwave::cli
