#pragma once
// Coding state and contexts of one code-block, shared by the bit-plane encoder and decoder
// (EBCOT class, as in JPEG 2000 Part 1 Annex D): significance contexts from the 8 in-plane
// neighbours (plus the 2 neighbours across slices for 3-D blocks) with orientation-dependent
// tables (context 0 and the run context split by whether a coefficient two rows or columns
// away is significant), sign contexts from the signs of the 4 (or 6) direct neighbours,
// refinement contexts, and the run-mode context. Every context starts at a trained prior
// (ctx_priors.h).
//
// The state is kept for speed in two incrementally updated forms: per coefficient, a word of
// significant-neighbour counts and neighbour sign sums (so a context is one table look-up),
// and per stripe column (the kStripe coefficients the scan visits together), bit masks of
// the rows that are significant, visited, refined or have a significant neighbour (so a pass
// finds the coefficients it codes with a few bit operations per column instead of a test per
// coefficient).

#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "codec/entropy/bit_model.h"
#include "transforms/subband.h"

namespace pupwave {

// Context numbering inside a block's model array.
inline constexpr int kSignContext0 = 9;     // 9 significance contexts come first
inline constexpr int kRefineContext0 = 14;  // then 5 sign contexts, then 3 refinement
inline constexpr int kRunContext = 17;
// Context 0 and the run context of coefficients (columns) with a significant coefficient two
// rows or columns away (the 5x5 neighbourhood beyond the 8 neighbours).
inline constexpr int kFarContext = 18;
inline constexpr int kFarRunContext = 19;
inline constexpr int kBlockContexts = 20;

// Stripe height of the scan and of the run mode.
inline constexpr std::size_t kStripe = 4;

// Largest number of magnitude bit-planes a block may have (indices below 2^30).
inline constexpr int kMaxBitPlanes = 30;

// Number of coding passes of a block with `planes` bit-planes: one cleanup pass for the top
// plane, then significance, refinement and cleanup for each lower plane.
constexpr int passes_for_planes(int planes) { return planes > 0 ? 3 * planes - 2 : 0; }

// Bit fields of a stripe column word: bit r of each field is row r of the column.
inline constexpr unsigned kColumnSignificant = 0;  // a 1 bit has been coded
inline constexpr unsigned kColumnVisited = 4;      // coded in this plane's significance pass
inline constexpr unsigned kColumnRefined = 8;      // has had a magnitude refinement bit
inline constexpr unsigned kColumnNeighbour = 12;   // has a significant neighbour
inline constexpr unsigned kColumnFar = 16;         // has a significant coefficient 2 away
inline constexpr std::uint32_t kRows = (1u << kStripe) - 1;

class BlockState {
 public:
  BlockState(const Extent& size, unsigned orientation);

  const Extent& size() const { return size_; }
  std::size_t stripes() const { return stripes_; }
  // Position of block coordinate (x, y, z) in the padded per-coefficient array.
  std::size_t at(std::size_t x, std::size_t y, std::size_t z) const {
    return (x + 1) + (y + 1) * stride_y_ + (z + 1) * stride_z_;
  }
  // Position of the word of column x of stripe s in slice z in the padded column array (two
  // pad columns on each side, for the far bits, and a pad stripe above and below).
  std::size_t column_at(std::size_t x, std::size_t s, std::size_t z) const {
    return (x + 2) + (s + 1) * column_row_ + (z + 1) * column_slice_;
  }
  std::uint32_t& column(std::size_t c) { return columns_[c]; }
  std::uint32_t column(std::size_t c) const { return columns_[c]; }

  // Significance context of coefficient p (JPEG 2000 Table D.1); 0 exactly when no
  // neighbour is significant (then zero_context refines it).
  int significance_context(std::size_t p) const { return sig_table_[neighbours_[p] & 0xFFu]; }
  // Significance context of row r of column word w whose significance_context is 0.
  static int zero_context(std::uint32_t w, unsigned r) {
    return kFarContext * int((w >> (kColumnFar + r)) & 1u);
  }
  // Significance context of coefficient p, row r of column word w: significance_context,
  // refined by zero_context where that is 0, selected without a branch.
  int full_significance_context(std::size_t p, std::uint32_t w, unsigned r) const {
    const int ctx = significance_context(p);
    return ctx + (zero_context(w, r) & -int(ctx == 0));
  }
  // Run context of a stripe column with word w.
  static int run_context(std::uint32_t w) { return (w >> kColumnFar) & kRows ? kFarRunContext : kRunContext; }
  // Sign context number and the bit the sign is XORed with before coding (Table D.3).
  std::pair<int, int> sign_context(std::size_t p) const {
    const std::uint8_t e = kSignTable[neighbours_[p] >> 8];
    return {kSignContext0 + (e >> 1), e & 1};
  }
  // True when no neighbour of coefficient p is significant.
  bool isolated(std::size_t p) const { return (neighbours_[p] & 0xFFu) == 0; }
  // Size of the padded per-coefficient array.
  std::size_t padded_count() const { return neighbours_.size(); }
  // Refinement context of row r of column word w.
  // Without a branch (whether a row was refined before is a coin toss to a predictor).
  static int refinement_context(std::uint32_t w, unsigned r) {
    const std::uint32_t refined = (w >> (kColumnRefined + r)) & 1u;
    const std::uint32_t near = (w >> (kColumnNeighbour + r)) & 1u;
    return kRefineContext0 + int((refined << 1) | (near & ~refined));
  }

  // Marks coefficient p (row y of slice z, column x) significant with the given sign: counts
  // it and its sign in its neighbours' words, sets their neighbour bits and its significant
  // bit in the column words, and activates the stripes whose contexts change.
  void make_significant(std::size_t p, std::size_t x, std::size_t y, std::size_t z, bool negative);

  // A stripe (index z * stripes() + y / 4) is active once a coefficient in it is significant
  // or has a significant neighbour. An inactive stripe codes nothing in the significance and
  // refinement passes, and only run bits in the cleanup pass, so passes skip it quickly.
  bool stripe_active(std::size_t stripe) const { return active_[stripe] != 0; }

  std::array<BitModel, kBlockContexts> models;

 private:
  // Sign context * 2 + XOR bit by the sign word (h + 2) + 5 (v + 4), h the sum of the
  // horizontal neighbours' signs (-2..2), v of the vertical and across-slice ones (-4..4).
  static constexpr int kSignCodeH = 1;
  static constexpr int kSignCodeV = 5;
  static constexpr int kSignCodeZero = 2 * kSignCodeH + 4 * kSignCodeV;
  static const std::array<std::uint8_t, 45> kSignTable;

  // Per-coefficient word: bits 0-1 significant horizontal neighbours (0..2), bits 2-3
  // vertical (0..2), bits 4-6 diagonal plus across-slice (0..6), bits 8-13 the sign word.
  static constexpr std::uint16_t kHorizontalUnit = 1;
  static constexpr std::uint16_t kVerticalUnit = 4;
  static constexpr std::uint16_t kDiagonalUnit = 16;
  static constexpr std::uint16_t kSignUnit = 256;

  void add(std::size_t p, std::uint16_t delta) { neighbours_[p] = std::uint16_t(neighbours_[p] + delta); }

  Extent size_;
  bool volume_ = false;
  std::size_t stride_y_ = 0;
  std::size_t stride_z_ = 0;
  std::vector<std::uint16_t> neighbours_;
  const std::uint8_t* sig_table_ = nullptr;  // context by neighbour count bits, per orientation
  std::size_t stripes_ = 0;                  // stripes per slice
  std::size_t column_row_ = 0;               // column words between adjacent stripes
  std::size_t column_slice_ = 0;             // column words between adjacent slices
  std::vector<std::uint32_t> columns_;
  std::vector<std::uint8_t> active_;  // per stripe: see stripe_active
};

// Always inlined: called once per significant coefficient from the passes' inner loops, and
// too large (with the far-neighbour bits) for the compiler's own inlining limit.
[[gnu::always_inline]] inline void BlockState::make_significant(std::size_t p, std::size_t x, std::size_t y,
                                                                std::size_t z, bool negative) {
  // Counts and signs in the neighbours' words: h and v are the horizontal and vertical
  // (or across-slice) sign contributions, as two's-complement steps of the sign word.
  const std::uint16_t h =
      negative ? std::uint16_t(0u - kSignCodeH * kSignUnit) : std::uint16_t(kSignCodeH * kSignUnit);
  const std::uint16_t v =
      negative ? std::uint16_t(0u - kSignCodeV * kSignUnit) : std::uint16_t(kSignCodeV * kSignUnit);
  const std::size_t sy = stride_y_;
  add(p - 1, std::uint16_t(kHorizontalUnit + h));
  add(p + 1, std::uint16_t(kHorizontalUnit + h));
  add(p - sy, std::uint16_t(kVerticalUnit + v));
  add(p + sy, std::uint16_t(kVerticalUnit + v));
  add(p - sy - 1, kDiagonalUnit);
  add(p - sy + 1, kDiagonalUnit);
  add(p + sy - 1, kDiagonalUnit);
  add(p + sy + 1, kDiagonalUnit);
  if (volume_) {  // neighbours across slices count with the diagonal ones, signs with vertical
    add(p - stride_z_, std::uint16_t(kDiagonalUnit + v));
    add(p + stride_z_, std::uint16_t(kDiagonalUnit + v));
  }
  // Column words: rows y - 1 .. y + 1 of columns x - 1 .. x + 1 (not p itself) have a
  // significant neighbour now, rows spilling into the stripes above and below included.
  const std::size_t s = y / kStripe;
  const unsigned r = unsigned(y % kStripe);
  const std::size_t c = column_at(x, s, z);
  const std::uint32_t rows = ((7u << r) >> 1) & kRows;
  const std::uint32_t near = rows << kColumnNeighbour;
  columns_[c - 1] |= near;
  columns_[c + 1] |= near;
  columns_[c] |= (near & ~(1u << (kColumnNeighbour + r))) | (1u << (kColumnSignificant + r));
  const std::size_t a = z * stripes_;
  active_[a + s] = 1;
  // Far bits: rows y - 2 .. y + 2 of columns x - 2 .. x + 2 (in this slice). They span this
  // stripe and the one above (r < 2) or below; bits past the block's edges fall in pad words.
  const std::uint32_t far = 0x1Fu << (r + 2);  // rows of the stripes above, here, below: 4 bits each
  const std::size_t far_row = r < 2 ? c - column_row_ : c;  // word of column x, upper stripe
  const std::uint32_t far_top = ((r < 2 ? far : far >> kStripe) & kRows) << kColumnFar;
  const std::uint32_t far_bottom = ((r < 2 ? far >> kStripe : far >> (2 * kStripe)) & kRows) << kColumnFar;
  for (std::size_t cc = far_row - 2; cc <= far_row + 2; ++cc) {
    columns_[cc] |= far_top;
    columns_[cc + column_row_] |= far_bottom;
  }
  if (r == 0 && s > 0) {
    const std::uint32_t bottom = 1u << (kColumnNeighbour + kStripe - 1);
    columns_[c - column_row_ - 1] |= bottom;
    columns_[c - column_row_] |= bottom;
    columns_[c - column_row_ + 1] |= bottom;
    active_[a + s - 1] = 1;
  }
  if (r == kStripe - 1 && y + 1 < size_[1]) {
    const std::uint32_t top = 1u << kColumnNeighbour;
    columns_[c + column_row_ - 1] |= top;
    columns_[c + column_row_] |= top;
    columns_[c + column_row_ + 1] |= top;
    active_[a + s + 1] = 1;
  }
  if (volume_) {
    const std::uint32_t across = 1u << (kColumnNeighbour + r);
    if (z > 0) {
      columns_[c - column_slice_] |= across;
      active_[a - stripes_ + s] = 1;
    }
    if (z + 1 < size_[2]) {
      columns_[c + column_slice_] |= across;
      active_[a + stripes_ + s] = 1;
    }
  }
}

// One stripe of the scan: up to kStripe rows from y0 in slice z; its first coefficient is at
// padded position f0 (see BlockState::at), block index i0 and column word c0 (see
// BlockState::column_at); row r of column x is at f0 + x + r * (size[0] + 2) and
// i0 + x + r * size[0], its word at c0 + x. `rows` masks the rows that exist.
struct Stripe {
  std::size_t index, y0, z, f0, i0, c0;
  std::uint32_t rows;
};

// Calls visit(stripe) for every stripe in scan order (slice, then stripe).
template <class Visit>
void for_each_stripe(const BlockState& state, Visit&& visit) {
  const Extent& size = state.size();
  const std::size_t flag_row = size[0] + 2;
  const std::size_t flag_slice = flag_row * (size[1] + 2);
  std::size_t index = 0;
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y0 = 0, s = 0; y0 < size[1]; y0 += kStripe, ++s, ++index) {
      const std::size_t rows = size[1] - y0 < kStripe ? size[1] - y0 : kStripe;
      visit(Stripe{index, y0, z, 1 + (y0 + 1) * flag_row + (z + 1) * flag_slice, size[0] * (y0 + size[1] * z),
                   state.column_at(0, s, z), (1u << rows) - 1u});
    }
}

}  // namespace pupwave
