// Trains the bit-plane block coder's context priors (codec/entropy/ctx_priors.h): codes every
// training image at every rate (as `pupwave compress --bpp R`), keeps the first kTallyWindow
// bits each context codes in each block, by band class, and fits each context's prior
// probability and weight (BitModel's starting count) to the least code length of those bits
// under BitModel's own adaptation. Prints kContextPriors and kContextPriorCounts to paste,
// and the start-of-block code length of the compiled-in priors, the fitted ones and flat 1/2
// priors on the training images and on the --check images (held out: never fitted on).
// Run: build/train/train_priors [--bpp 0.125,0.25,0.5,1,2] [--effort 1] TRAIN... [--check CHECK...]
// (directories: their .png files). Train on photographs other than the scored ones
// (testimages/); tools/train/README.md names the sets used.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "codec/entropy/block_tally.h"
#include "codec/entropy/ctx_priors.h"
#include "codec/image/encode_stats.h"
#include "codec/image/image_codec.h"
#include "image_list.h"
#include "tools/image_io.h"

namespace {
namespace fs = std::filesystem;
using pupwave::BitModel;
using pupwave::ContextTally;
using pupwave::kBlockContexts;

struct Args {
  std::vector<double> bpps{0.125, 0.25, 0.5, 1.0, 2.0};
  int effort = 1;
  std::vector<fs::path> train, check;
};

Args parse(int argc, char** argv) {
  Args a;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    if (s == "--bpp" && i + 1 < argc) {
      a.bpps = pupwave::train::number_list(argv[++i]);
    } else if (s == "--effort" && i + 1 < argc) {
      a.effort = std::stoi(argv[++i]);
    } else if (s == "--check") {
      check = true;
    } else if (!s.empty() && s[0] == '-') {
      throw std::invalid_argument("unknown option " + s);
    } else {
      pupwave::train::add_images(s, check ? a.check : a.train);
    }
  }
  if (a.train.empty())
    throw std::invalid_argument("usage: train_priors [--bpp LIST] [--effort N] TRAIN... [--check CHECK...]");
  return a;
}

// Codes every image at every rate, adding the blocks' context starts to `tally`.
void add_tally(const std::vector<fs::path>& images, const Args& args, ContextTally& tally) {
  pupwave::EncodeStats stats;
  stats.tally = &tally;
  for (const auto& path : images) {
    const pupwave::Image image = pupwave::cli::read_image(path);
    for (const double bpp : args.bpps) {
      pupwave::EncodeOptions options;
      options.mode = pupwave::RateMode::bpp;
      options.target = bpp;
      options.effort = args.effort;
      options.measure_psnr = false;
      options.stats = &stats;
      pupwave::encode_image(image, options);
    }
    std::fprintf(stderr, "%s: %llu blocks so far\n", path.string().c_str(), (unsigned long long)tally.blocks);
  }
}

using Starts = std::vector<std::pair<std::uint64_t, std::uint64_t>>;  // (tally key, blocks)

// Code length in bits of a 0 and of a 1 at each probability state p0.
const std::array<std::array<float, pupwave::kProbabilityOne + 1>, 2>& bit_costs() {
  static const auto table = [] {
    auto t = std::make_unique<std::array<std::array<float, pupwave::kProbabilityOne + 1>, 2>>();
    for (std::uint32_t p = 1; p < pupwave::kProbabilityOne; ++p) {
      const double p0 = double(p) / pupwave::kProbabilityOne;
      (*t)[0][p] = float(-std::log2(p0));
      (*t)[1][p] = float(-std::log2(1.0 - p0));
    }
    return t;
  }();
  return *table;
}

// Bits BitModel spends on `starts` from prior (one256, count).
double code_length(const Starts& starts, int one256, int count) {
  const auto& cost = bit_costs();
  double total = 0.0;
  for (const auto& [key, blocks] : starts) {
    BitModel m = pupwave::prior_model(std::uint8_t(one256), std::uint8_t(count));
    double bits = 0.0;
    for (unsigned i = 0; i < pupwave::tally_length(key); ++i) {
      const int bit = int((pupwave::tally_bits(key) >> i) & 1u);
      bits += cost[std::size_t(bit)][m.p0];
      m.update(bit);
    }
    total += bits * double(blocks);
  }
  return total;
}

struct Prior {
  int one256 = 128, count = 0;
  double bits = 0.0;
};

// Least code length over the counts tried and all priors (a coarse scan, then the
// neighbourhood of its best: the length is unimodal in the prior).
Prior fit(const Starts& starts) {
  Prior best{128, 0, code_length(starts, 128, 0)};
  for (const int count : {0, 1, 2, 3, 5, 7, 11, 15, 23, 31}) {
    Prior here{128, count, code_length(starts, 128, count)};
    for (int p = 4; p < 256; p += 8) {
      const double b = code_length(starts, p, count);
      if (b < here.bits) here = {p, count, b};
    }
    for (int p = std::max(1, here.one256 - 7); p <= std::min(255, here.one256 + 7); ++p) {
      const double b = code_length(starts, p, count);
      if (b < here.bits) here = {p, count, b};
    }
    if (here.bits < best.bits) best = here;
  }
  return best;
}

Starts starts_of(const ContextTally& t, std::size_t c, std::size_t k) {
  return Starts(t.starts[c][k].begin(), t.starts[c][k].end());
}

using Table = std::array<std::array<Prior, kBlockContexts>, 3>;

// The first rule (the first priors the codec shipped): (ones + 1) / (bits + 2) over the first 16 bits
// each context codes in a block, worth 7 bits. Kept to compare with the fit.
Prior mean_of_first_bits(const Starts& starts) {
  double ones = 0.0, bits = 0.0;
  for (const auto& [key, blocks] : starts) {
    const unsigned n = std::min(pupwave::tally_length(key), 16u);
    ones += double(std::popcount(pupwave::tally_bits(key) & ((1u << n) - 1u))) * double(blocks);
    bits += double(n) * double(blocks);
  }
  return {std::clamp(int(std::lround((ones + 1.0) / (bits + 2.0) * 256.0)), 1, 255), 7, 0.0};
}

// Start-of-block code length of a set under a table of priors, in bits.
double total_length(const ContextTally& t, const Table& table) {
  double total = 0.0;
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t k = 0; k < std::size_t(kBlockContexts); ++k)
      total += code_length(starts_of(t, c, k), table[c][k].one256, table[c][k].count);
  return total;
}

struct Tables {
  Table compiled, fitted, mean16, flat;
};

void report(const char* set, const ContextTally& t, const Tables& tables) {
  const double now = total_length(t, tables.compiled);
  auto vs_now = [&](const Table& table) {
    const double b = total_length(t, table);
    return std::to_string(std::lround(b / 8)) + " (" + std::to_string(100.0 * (b - now) / now).substr(0, 5) +
           "%)";
  };
  std::printf(
      "// %s: %llu blocks; start-of-block bytes: compiled-in %.0f, fitted %s, mean of 16 %s, flat 1/2 %s\n",
      set, (unsigned long long)t.blocks, now / 8, vs_now(tables.fitted).c_str(),
      vs_now(tables.mean16).c_str(), vs_now(tables.flat).c_str());
}

void print_table(const Table& fitted, const char* name) {
  std::printf("// %s\n", name);
  std::printf("inline constexpr std::array<std::array<std::uint8_t, %d>, 3> kContextPriors{{\n",
              kBlockContexts);
  for (const auto& row : fitted) {
    std::printf("    {");
    for (std::size_t k = 0; k < row.size(); ++k) std::printf("%s%d", k ? ", " : "", row[k].one256);
    std::printf("},\n");
  }
  std::printf("}};\ninline constexpr std::array<std::array<std::uint8_t, %d>, 3> kContextPriorCounts{{\n",
              kBlockContexts);
  for (const auto& row : fitted) {
    std::printf("    {");
    for (std::size_t k = 0; k < row.size(); ++k) std::printf("%s%d", k ? ", " : "", row[k].count);
    std::printf("},\n");
  }
  std::printf("}};\n");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = parse(argc, argv);
    ContextTally train;
    add_tally(args.train, args, train);
    Tables t;
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t k = 0; k < std::size_t(kBlockContexts); ++k) {
        t.fitted[c][k] = fit(starts_of(train, c, k));
        t.mean16[c][k] = mean_of_first_bits(starts_of(train, c, k));
        t.compiled[c][k] = {pupwave::kContextPriors[c][k], pupwave::kContextPriorCounts[c][k], 0.0};
        t.flat[c][k] = {128, 0, 0.0};
      }
    print_table(t.fitted, "fitted to the least code length");
    print_table(t.mean16, "mean of the first 16 bits, worth 7");
    report("training images", train, t);
    if (!args.check.empty()) {
      ContextTally check;
      add_tally(args.check, args, check);
      report("check images", check, t);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "train_priors: %s\n", e.what());
    return 1;
  }
}
