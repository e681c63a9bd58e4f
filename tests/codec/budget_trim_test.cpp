// BudgetTrim (codec/image/budget_trim.h): coded blocks held with only the passes a byte budget
// can still use give PCRD exactly the truncation, codewords and next hull points (what
// fill_budget offers) that every pass gives, for budgets from nearly nothing to everything,
// whatever order the blocks arrive in; and KeptBlock keeps the coder's sizes and codewords.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "codec/entropy/block_encoder.h"
#include "codec/image/budget_trim.h"
#include "codec/image/kept_block.h"
#include "codec/rate/pcrd.h"

namespace pupwave {
namespace {

// A 32 x 32 block of Laplacian-like magnitudes at `scale` (index units), a third of them zero.
EncodedBlock random_block(double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::exponential_distribution<double> mag(1.0);
  std::vector<float> magnitude(32 * 32);
  std::vector<std::uint8_t> negative(magnitude.size());
  for (std::size_t i = 0; i < magnitude.size(); ++i) {
    magnitude[i] = rng() % 3 == 0 ? 0.0f : float(mag(rng) * scale);
    negative[i] = std::uint8_t(rng() & 1u);
  }
  return encode_block(magnitude, negative, {32, 32, 1}, unsigned(seed % 4), 0.375);
}

std::vector<EncodedBlock> random_blocks(std::size_t n) {
  std::vector<EncodedBlock> blocks;
  for (std::size_t i = 0; i < n; ++i)  // scales over 3 decades, as over the bands of an image
    blocks.push_back(random_block(std::pow(10.0, double(i % 7) / 2.0), unsigned(i) + 1));
  return blocks;
}

// The first hull point past `passes` (fill_budget's candidate), or passes -1 if none.
HullPoint next_point(const std::vector<HullPoint>& hull, int passes) {
  for (const HullPoint& p : hull)
    if (p.passes > passes) return p;
  return HullPoint{-1, 0, 0.0, 0.0};
}

std::vector<std::uint8_t> codeword(const KeptBlock& b, int n) {
  std::vector<std::uint8_t> out;
  b.append_codeword(n, out);
  return out;
}

TEST(KeptBlock, KeepsTheCodersSizesAndCodewords) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const EncodedBlock coded = random_block(40.0, seed);
    ASSERT_GT(coded.pass_count(), 6);
    EncodedBlock copy = coded;
    KeptBlock kept(std::move(copy));
    ASSERT_EQ(kept.pass_count(), coded.pass_count());
    for (int n = 0; n <= coded.pass_count(); ++n) {
      EXPECT_EQ(kept.size(n), coded.size(n)) << n;
      EXPECT_EQ(codeword(kept, n), coded.codeword(n)) << n;
      if (n > 0) {
        EXPECT_EQ(kept.distortion_drop(n - 1), coded.distortion_drop[std::size_t(n - 1)]);
      }
    }
    const int cut = coded.pass_count() / 2;
    kept.truncate(cut);
    ASSERT_EQ(kept.pass_count(), cut);
    for (int n = 0; n <= cut; ++n) EXPECT_EQ(codeword(kept, n), coded.codeword(n)) << n;
    EXPECT_LT(kept.bytes_held(), KeptBlock(EncodedBlock(coded)).bytes_held());
    copy = coded;
    EXPECT_THROW(KeptBlock(std::move(copy), 3, false).distortion_drop(0), std::logic_error);
  }
}

TEST(BudgetTrim, GivesPcrdTheTruncationOfEveryPass) {
  const std::vector<EncodedBlock> coded = random_blocks(480);
  std::vector<KeptBlock> full;
  std::vector<std::vector<HullPoint>> full_hulls;
  for (const EncodedBlock& b : coded) {
    full_hulls.push_back(rd_hull(b));
    full.emplace_back(EncodedBlock(b));
  }
  // Budgets as shares of the bytes of every hull point. The bound is raised once the blocks
  // held pass the budget by a 16th of it or 64 KiB (budget_trim.cpp): below that it must cut.
  const double hull_bytes = bytes_at_slope(full_hulls, 0.0);
  int must_cut = 0;
  std::mt19937 rng(7);
  for (const double share : {0.001, 0.01, 0.05, 0.2, 0.4, 0.6, 0.8, 0.95, 1.0, 1.5}) {
    const double budget = std::floor(share * hull_bytes);
    std::vector<KeptBlock> blocks(coded.size());
    std::vector<std::vector<HullPoint>> hulls(coded.size());
    {
      BudgetTrim trim(blocks, hulls, budget);
      std::vector<std::size_t> order(coded.size());
      std::iota(order.begin(), order.end(), std::size_t(0));
      std::shuffle(order.begin(), order.end(), rng);  // blocks arrive in any order (threads)
      for (std::size_t i : order) trim.add(i, EncodedBlock(coded[i]), rd_hull(coded[i]));
    }
    // Held below the bytes of every hull point: the slope bound cut some (not only the
    // passes past each block's last hull point).
    std::size_t held = 0;
    for (const KeptBlock& b : blocks) held += b.size(b.pass_count());
    if (budget + std::max(budget / 16.0, 65536.0) < hull_bytes) {
      ++must_cut;
      EXPECT_LT(double(held), hull_bytes) << share;
    }
    const auto fits_in = [&](const std::vector<KeptBlock>& b) {
      return [&, budget](const std::vector<int>& p) {
        double bytes = 0.0;
        for (std::size_t i = 0; i < p.size(); ++i) bytes += double(b[i].size(p[i]));
        return bytes <= budget;
      };
    };
    const double lambda = slope_threshold(full_hulls, true, fits_in(full));
    EXPECT_EQ(slope_threshold(hulls, true, fits_in(blocks)), lambda) << share;
    const auto passes = passes_at_slope(full_hulls, lambda);
    EXPECT_EQ(passes_at_slope(hulls, lambda), passes) << share;
    for (std::size_t i = 0; i < coded.size(); ++i) {
      EXPECT_EQ(codeword(blocks[i], passes[i]), codeword(full[i], passes[i])) << share << " block " << i;
      const HullPoint a = next_point(full_hulls[i], passes[i]), b = next_point(hulls[i], passes[i]);
      EXPECT_EQ(a.passes, b.passes) << share << " block " << i;
      EXPECT_EQ(a.slope, b.slope) << share << " block " << i;
      if (b.passes > 0) {
        EXPECT_EQ(codeword(blocks[i], b.passes), codeword(full[i], b.passes));
      }
    }
  }
  EXPECT_GE(must_cut, 5);  // the blocks are large enough for the bound to matter
}

TEST(BudgetTrim, OverflowSlopeIsABound) {
  const std::vector<EncodedBlock> coded = random_blocks(60);
  std::vector<std::vector<HullPoint>> hulls;
  for (const EncodedBlock& b : coded) hulls.push_back(rd_hull(b));
  const double all = bytes_at_slope(hulls, 0.0);
  EXPECT_EQ(overflow_slope(hulls, all, 0.0), 0.0);  // nothing overflows a budget of everything
  for (const double share : {0.1, 0.5, 0.9}) {
    const double budget = share * all;
    const double bound = overflow_slope(hulls, budget, 0.0);
    EXPECT_GT(bound, 0.0);
    EXPECT_GT(bytes_at_slope(hulls, bound), budget);
    EXPECT_LE(bytes_at_slope(hulls, bound * 1.01), budget);  // and close to the tightest one
    EXPECT_EQ(overflow_slope(hulls, budget, bound), bound);  // a bound is kept when no higher is found
  }
}

}  // namespace
}  // namespace pupwave
