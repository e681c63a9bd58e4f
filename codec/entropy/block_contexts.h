#pragma once
// Coding state and contexts of one code-block, shared by the bit-plane encoder and decoder
// (EBCOT class, as in JPEG 2000 Part 1 Annex D): per-coefficient flags in a zero-padded
// array, significance contexts from the 8 in-plane neighbours (plus the 2 neighbours across
// slices for 3-D blocks) with orientation-dependent tables, sign contexts from the signs of
// the 4 (or 6) direct neighbours, refinement contexts, and the run-mode context.

#include <array>
#include <cstdint>
#include <vector>

#include "codec/entropy/bit_model.h"
#include "transforms/subband.h"

namespace pupwave {

// Flags of one coefficient.
enum : std::uint8_t {
  kSignificant = 1,  // a 1 bit has been coded
  kVisited = 2,      // coded in this bit-plane's significance propagation pass
  kRefined = 4,      // has had at least one magnitude refinement bit
  kNegative = 8,     // sign, valid once significant
};

// Context numbering inside a block's model array.
inline constexpr int kSignContext0 = 9;     // 9 significance contexts come first
inline constexpr int kRefineContext0 = 14;  // then 5 sign contexts, then 3 refinement
inline constexpr int kRunContext = 17;
inline constexpr int kBlockContexts = 18;

// Stripe height of the scan and of the run mode.
inline constexpr std::size_t kStripe = 4;

// Largest number of magnitude bit-planes a block may have (indices below 2^30).
inline constexpr int kMaxBitPlanes = 30;

// Number of coding passes of a block with `planes` bit-planes: one cleanup pass for the top
// plane, then significance, refinement and cleanup for each lower plane.
constexpr int passes_for_planes(int planes) { return planes > 0 ? 3 * planes - 2 : 0; }

class BlockState {
 public:
  BlockState(const Extent& size, unsigned orientation);

  const Extent& size() const { return size_; }
  // Position in the padded flag array of block coordinate (x, y, z).
  std::size_t at(std::size_t x, std::size_t y, std::size_t z) const {
    return (x + 1) + (y + 1) * stride_y_ + (z + 1) * stride_z_;
  }
  std::uint8_t& flags(std::size_t p) { return flags_[p]; }
  std::uint8_t flags(std::size_t p) const { return flags_[p]; }

  // Significance context from the packed neighbour counts (JPEG 2000 Table D.1).
  int significance_context(std::size_t p) const { return sig_table_[neighbours_[p]]; }
  // Sign context number and the bit the sign is XORed with before coding.
  std::pair<int, int> sign_context(std::size_t p) const;
  int refinement_context(std::size_t p) const {
    if (flags_[p] & kRefined) return kRefineContext0 + 2;
    return kRefineContext0 + (isolated(p) ? 0 : 1);
  }
  // True when no neighbour is significant (the run mode and the first refinement ask this).
  bool isolated(std::size_t p) const { return neighbours_[p] == 0; }
  // The run mode codes a whole stripe column (top at f0) with one bit when it is quiet and
  // uncoded: no coefficient significant or visited, none with a significant neighbour.
  bool run_eligible(std::size_t f0) const {
    for (std::size_t r = 0; r < kStripe; ++r) {
      const std::size_t f = f0 + r * stride_y_;
      if ((flags_[f] & (kSignificant | kVisited)) || !isolated(f)) return false;
    }
    return true;
  }

  // Marks coefficient p significant with the given sign and counts it in its neighbours'
  // packed words, so contexts are one table look-up instead of 8 (or 10) flag reads.
  void make_significant(std::size_t p, bool negative) {
    flags_[p] = std::uint8_t(flags_[p] | kSignificant | (negative ? kNegative : 0));
    std::uint8_t* n = neighbours_.data() + p;
    const std::size_t sy = stride_y_;
    n[-1] = std::uint8_t(n[-1] + kHorizontalUnit);
    n[1] = std::uint8_t(n[1] + kHorizontalUnit);
    *(n - sy) = std::uint8_t(*(n - sy) + kVerticalUnit);
    *(n + sy) = std::uint8_t(*(n + sy) + kVerticalUnit);
    *(n - sy - 1) = std::uint8_t(*(n - sy - 1) + kDiagonalUnit);
    *(n - sy + 1) = std::uint8_t(*(n - sy + 1) + kDiagonalUnit);
    *(n + sy - 1) = std::uint8_t(*(n + sy - 1) + kDiagonalUnit);
    *(n + sy + 1) = std::uint8_t(*(n + sy + 1) + kDiagonalUnit);
    if (volume_) {  // neighbours across slices count with the diagonal ones
      *(n - stride_z_) = std::uint8_t(*(n - stride_z_) + kDiagonalUnit);
      *(n + stride_z_) = std::uint8_t(*(n + stride_z_) + kDiagonalUnit);
    }
  }

  // Clears kVisited on every coefficient (end of each cleanup pass).
  void clear_visited();

  // A stripe (4 rows of one slice, index z * stripes + y / 4) is active once a coefficient in
  // it is significant or has a significant neighbour. An inactive stripe codes nothing in the
  // significance and refinement passes, and only run bits in the cleanup pass, so the passes
  // skip it (or take the run-only path) instead of testing every coefficient: most stripes of
  // the top bit-planes of a block are inactive.
  bool stripe_active(std::size_t stripe) const { return active_[stripe] != 0; }
  // Marks the stripes whose contexts change when the coefficient at row y of slice z becomes
  // significant: rows y - 1 .. y + 1 of its slice and row y of the adjacent slices.
  void mark_active(std::size_t y, std::size_t z) {
    const std::size_t s = z * stripes_;
    active_[s + y / kStripe] = 1;
    if (y > 0) active_[s + (y - 1) / kStripe] = 1;
    if (y + 1 < size_[1]) active_[s + (y + 1) / kStripe] = 1;
    if (volume_) {
      if (z > 0) active_[s - stripes_ + y / kStripe] = 1;
      if (z + 1 < size_[2]) active_[s + stripes_ + y / kStripe] = 1;
    }
  }

  std::array<BitModel, kBlockContexts> models;

 private:
  bool sig(std::size_t p) const { return flags_[p] & kSignificant; }
  // +1 / -1 for a significant positive / negative neighbour, 0 otherwise.
  int sign_of(std::size_t p) const { return sig(p) ? ((flags_[p] & kNegative) ? -1 : 1) : 0; }
  // Significance and sign of p as 2 bits (bit 0: significant, bit 1: negative).
  std::size_t sign_state(std::size_t p) const {
    return std::size_t(flags_[p] & kSignificant) | std::size_t((flags_[p] & kNegative) >> 2);
  }

  Extent size_;
  int table_ = 0;  // 0: LL and high-in-y bands, 1: high-in-x bands, 2: high in both
  bool volume_ = false;
  std::size_t stride_y_ = 0;
  std::size_t stride_z_ = 0;
  std::vector<std::uint8_t> flags_;
  // Per coefficient, counts of significant neighbours packed as h (bits 0-1, 0..2),
  // v (bits 2-3, 0..2) and diagonal plus across-slice (bits 4-7, 0..6).
  std::vector<std::uint8_t> neighbours_;
  const std::uint8_t* sig_table_ = nullptr;  // context by packed neighbour word, per orientation
  std::size_t stripes_ = 0;                  // stripes per slice
  std::vector<std::uint8_t> active_;         // per stripe: see stripe_active

  static constexpr std::uint8_t kHorizontalUnit = 1;
  static constexpr std::uint8_t kVerticalUnit = 4;
  static constexpr std::uint8_t kDiagonalUnit = 16;
};

// One stripe of the scan: up to kStripe rows from y0 in slice z; its first coefficient is at
// padded flag position f0 (see BlockState::at) and block index i0, row r of column x at
// f0 + x + r * (size[0] + 2) and i0 + x + r * size[0].
struct Stripe {
  std::size_t index, y0, z, f0, i0, rows;
};

// Calls visit(stripe) for every stripe in scan order (slice, then stripe).
template <class Visit>
void for_each_stripe(const Extent& size, Visit&& visit) {
  const std::size_t flag_row = size[0] + 2;
  const std::size_t flag_slice = flag_row * (size[1] + 2);
  std::size_t index = 0;
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y0 = 0; y0 < size[1]; y0 += kStripe, ++index) {
      const std::size_t rows = size[1] - y0 < kStripe ? size[1] - y0 : kStripe;
      visit(Stripe{index, y0, z, 1 + (y0 + 1) * flag_row + (z + 1) * flag_slice, size[0] * (y0 + size[1] * z),
                   rows});
    }
}

}  // namespace pupwave
