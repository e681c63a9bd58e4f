#pragma once
// The parent-context coefficient coder: entropy coder 4 of lossy image streams (`--entropy pc`,
// docs/bitstream.md; codec/image/image_encoder_pc.cpp and pc_decoder.cpp use it). One pass
// over a detail block's quantization indices with the volume coefficient coder's binarisation
// (pc_index.h: Rice class from the causal neighbour magnitudes, unary high part with models, modelled
// top low bits, raw rest, sign by neighbour signs) and pc's own models (pc_bit.h), the index of the
// parent (the next coarser band of the same orientation, already decoded) and its neighbours towards
// the child added to the activity sum, the parent's sign to the sign context (ECECOW-style), and for
// chroma the co-located luma (and, for Cr, Cb) indices as further parents (pc_groups.h), every
// model starting from its band class's trained state (pc_priors.h); the chroma detail blocks code
// the residual of a prediction from luma (and Cb) (pc_cfl.h). Figures: bench/results/image-rd.md.

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <utility>
#include <vector>

#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/coef_encoder.h"
#include "codec/entropy/lc_blocks.h"
#include "codec/entropy/pc_index.h"

namespace pupwave {

// A chroma block's further parents: the co-located luma indices (row y at origin + y * stride)
// and, for Cr, Cb's, decoded before it. Null origin: none.
struct PcLuma {
  const std::int32_t* origin = nullptr;
  std::size_t stride = 0;
  // The third component's: the co-located indices of the second (Cb for Cr), same stride.
  const std::int32_t* cb = nullptr;
};

// A chroma detail block's chroma-from-luma prediction (codec/entropy/pc_cfl.h): `count` codes
// (1 for Cb: luma's weight; 2 for Cr: luma's and Cb's), each weight code / 16 in [-2, 2], coded
// at the head of the block's codeword. count 0: the block has no prediction.
struct PcCfl {
  int count = 0;
  int code[2] = {0, 0};
};

// The activity class of three times the activity s3 (PcContext::at): s = s3 / 3 rounded, its
// bit length and next bit (s < 2: s itself), capped at the last class.
constexpr int pc_activity_class(std::uint64_t s3) {
  const std::uint64_t s = (2 * s3 + 3) / 6;
  const int w = int(std::bit_width(s));
  return std::min(s < 2 ? int(s) : 2 * w - 2 + int((s >> (w - 2)) & 1u), kCoefClasses - 1);
}

// pc_activity_class of the small activities, where most coefficients are: a load, not a division.
inline constexpr std::array<std::uint8_t, 3 * 256> kPcActivityClasses = [] {
  std::array<std::uint8_t, 3 * 256> t{};
  for (std::size_t k = 0; k < t.size(); ++k) t[k] = std::uint8_t(pc_activity_class(k));
  return t;
}();

// A block's contexts from outside it: the parent band and, for chroma, the luma parent (pc_visit
// adds the causal in-band neighbours as the codeword goes). The coder's weights are 1 and 1.
class PcContext {
 public:
  // Weight of Cb's magnitude in Cr's S (3 x the activity): measured best of 3 .. 48 (the
  // chroma components' magnitudes go together more than the neighbours').
  static constexpr std::uint64_t kCbWeight = 24;

  PcContext(std::size_t w, std::size_t h, const LcParent& parent, const PcLuma& luma = {},
            int parent_weight = 1, int scale = 1);

  // Activity class and sign context of coefficient (x, y) of a block with no coefficient coded
  // yet (its in-band neighbours zero; pc_visit adds theirs as it goes). Activity: the in-band sum
  // 2 (W + N) + NW + NE (the volume coder's), with a parent doubled (x scale) plus weight x |P|
  // plus the mean of P's three neighbours towards the child (horizontal, vertical, diagonal: the
  // parent band's values nearest the child's position), plus |L| (the co-located luma index) for
  // chroma and 8 |Cb| (Cb's co-located index) for Cr; rounded to an integer. Sign context: the
  // signs of W, N, the parent and the luma parent (Cb for Cr).
  PcCtx at(std::size_t x, std::size_t y) const { return row(y).at(x, 0, 0, 0); }
  // What at() reads of row y besides the in-band neighbours, as plain pointers a caller keeps in
  // registers along the row (pc_visit): the parent's row and side row, the luma and Cb rows.
  struct Row {
    const std::uint32_t* parent = nullptr;  // null: no parent
    const std::uint32_t* side = nullptr;
    const std::int8_t* parent_sign = nullptr;
    const std::size_t* cols = nullptr;   // parent_cols_
    const std::int32_t* luma = nullptr;  // null: no luma parent
    const std::int32_t* cb = nullptr;
    std::uint64_t in_weight = 0, parent_weight = 0;
    // The context from the in-band sum in = 2 (W + N) + NW + NE and the signs of W and N.
    PcCtx at(std::size_t x, std::uint64_t in, int sign_w, int sign_n) const {
      std::uint64_t s3 = in_weight * in;  // three times the activity (P's neighbours count a third)
      PcCtx c;
      c.sign_w = sign_w;
      c.sign_n = sign_n;
      if (parent) {
        const std::size_t px = cols[2 * x], nx = cols[2 * x + 1];
        s3 += parent_weight * parent[px] + parent[nx] + side[px] + side[nx];
        c.parent = parent_sign + px;
      }
      if (luma) {
        s3 += 3 * magnitude(luma[x]);
        c.luma = luma + x;
        if (cb) {  // Cr: Cb's magnitude weighs 8 and its sign replaces luma's
          s3 += kCbWeight * magnitude(cb[x]);
          c.luma = cb + x;
        }
      }
      c.cls = s3 < kPcActivityClasses.size() ? kPcActivityClasses[s3] : pc_activity_class(s3);
      return c;
    }
  };
  Row row(std::size_t y) const {
    Row r;
    r.in_weight = in_weight_;
    r.parent_weight = parent_weight_;
    if (parent_.origin) {
      r.parent = pmag_.data() + parent_rows_[2 * y];
      r.side = pmag_.data() + parent_rows_[2 * y + 1];
      r.parent_sign = psign_.data() + parent_rows_[2 * y];
      r.cols = parent_cols_.data();
    }
    if (luma_.origin) {
      r.luma = luma_.origin + y * luma_.stride;
      if (luma_.cb) r.cb = luma_.cb + y * luma_.stride;
    }
    return r;
  }
  // Indices stay within +-2^kCoefMaxBits, so abs cannot overflow.
  static std::uint64_t magnitude(std::int32_t v) { return std::uint32_t(std::abs(v)); }
  static int sign_of(std::int32_t v) { return v == 0 ? 0 : (v < 0 ? -1 : 1); }

 private:
  LcParent parent_;
  PcLuma luma_;
  std::uint64_t in_weight_, parent_weight_;  // 3 (x 2 x scale with a parent) and 3 x weight
  // The magnitudes and signs of the parent band's samples this block reads (its window of rows
  // and columns, row-major), made once per block so that the per-coefficient loop does no abs.
  std::vector<std::uint32_t> pmag_;
  std::vector<std::int8_t> psign_;
  // Per child row y: the offsets in pmag_ of the parent's row and its neighbour row towards y
  // (2y, 2y + 1); per child column x: the parent's column and its neighbour column towards x
  // (2x, 2x + 1), clamped to the band, relative to the window.
  std::vector<std::size_t> parent_rows_;
  std::vector<std::size_t> parent_cols_;
};

// Greedy rate-distortion optimised quantization inside the encoder: each index starts at the
// reconstruction point nearest its coefficient and takes the one of {nearest, nearest - 1, 0}
// with the least squared error (index units) + lambda x the bits the models would spend on it,
// a non-zero one also + lambda x pc_neighbour_bits (its effect on the contexts of the indices
// coded after it).
struct PcRdoq {
  std::span<const float> coefficients;  // the block's coefficients in index units (x / step)
  double lambda = 0.1;                  // squared index-unit error per bit (measured best: 0.1)
  double delta = 0.05;                  // the decoder's reconstruction offset (measured best: 0.05)
  // The neighbour term's bits at activity class 0 and the class at which it has halved (measured
  // on the test photographs: 3 and 8, a plateau from 2 to 4 bits; 0 bits: the plain greedy choice).
  double neighbour_bits = 3.0;
  double neighbour_fade = 8.0;
};

// Codes the indices `q` (`width` x `height`, x fastest) of a block whose parent is `parent`
// (LcParent's origin, stride, extent and the block's offset in its band; null origin: none).
// With `rdoq`, q is first re-chosen (and rewritten) as PcRdoq says; with `cfl`, its codes head the
// codeword. Throws IndexRangeError for an index of 2^kCoefMaxBits or more.
// `start`: the models the block starts with (its band's trained priors, pc_priors.h), null: flat
// ones; `end` (optional) receives the models' end state (their start when no codeword is written).
CoefCodeword pc_encode_block(std::vector<std::int32_t>& q, std::size_t width, std::size_t height,
                             const LcParent& parent, const PcRdoq* rdoq = nullptr, const PcLuma& luma = {},
                             const PcCfl* cfl = nullptr, const PcModels* start = nullptr,
                             PcModels* end = nullptr);

// Decodes a codeword of `bits` (the largest index's bit length, 1 .. kCoefMaxBits) into `width` x
// `height` indices at `out` (row y at out + y * stride); with `cfl` (its count set), its codes are
// read first. Throws DecodeError unless the largest decoded index has bit length `bits`, or for a
// code beyond [-32, 32]. `start` and `end` as pc_encode_block's.
void pc_decode_block(std::span<const std::uint8_t> codeword, int bits, std::size_t width, std::size_t height,
                     const LcParent& parent, std::int32_t* out, std::size_t stride, const PcLuma& luma = {},
                     PcCfl* cfl = nullptr, const PcModels* start = nullptr, PcModels* end = nullptr);

// The coders under any context (`ctx` fresh): pc_encode_block's loop (no empty-block rules),
// returning the codeword and the largest magnitude coded, and pc_decode_block's (magnitudes
// clamped to `limit`), returning the largest magnitude decoded. `models`: the models to code
// with, left in their end state; null: fresh ones.
std::pair<std::vector<std::uint8_t>, std::uint32_t> pc_encode_indices(std::vector<std::int32_t>& q,
                                                                      std::size_t width, std::size_t height,
                                                                      PcContext ctx, const PcRdoq* rdoq,
                                                                      const PcCfl* cfl = nullptr,
                                                                      PcModels* models = nullptr);
std::uint32_t pc_decode_indices(std::span<const std::uint8_t> codeword, std::uint64_t limit,
                                std::size_t width, std::size_t height, PcContext ctx, std::int32_t* out,
                                std::size_t stride, PcCfl* cfl = nullptr, PcModels* models = nullptr);

// Greedy RDOQ of one index: `v` (the signed nearest point of coefficient u, in index units)
// becomes the one of {nearest, nearest - 1, 0} with the least squared error + lambda x (the bits
// models m would spend on it now, + `neighbour_bits` if it is non-zero). 0 stays 0.
std::int32_t pc_rdoq_index(PcModels& m, const PcCtx& c, float u, std::int32_t v, double lambda, double delta,
                           double neighbour_bits = 0.0);

// The bits a non-zero index at (x, y) of class `cls` is charged for what it does to the later
// coefficients' contexts (it joins the activity of E and S with weight 2, of SW and SE with 1):
// where those are zero it makes their zeros dearer, where they are non-zero it brings their
// class nearer their magnitudes. q holds the nearest points ahead of (x, y), standing in for the
// final indices: rdoq.neighbour_bits x (zero weights - non-zero weights) / 6, fading with the
// class (an index moves a high activity less): x fade / (fade + cls).
double pc_neighbour_bits(const std::vector<std::int32_t>& q, std::size_t width, std::size_t height,
                         std::size_t x, std::size_t y, int cls, const PcRdoq& rdoq);

// Visits a block in coding order: `code(x, y, ctx)` codes coefficient (x, y) and
// returns its signed index, which joins the contexts. Returns the largest magnitude. The
// neighbours W, NW, N and their signs move along the row in registers (only NE and N's sign are
// loaded), the same contexts as PcContext::at(x, y).
template <class Code>
std::uint32_t pc_visit(std::size_t width, std::size_t height, PcContext& ctx, Code code) {
  // Two rows of magnitudes and signs, each padded by a zero column on both sides: the row above
  // (zero above the block) and the row being coded, alternating. Signs as int32, not int8: a store
  // through a character type may alias anything, and the loop would reload every pointer it reads
  // after each coefficient.
  thread_local std::vector<std::uint32_t> magnitudes;
  thread_local std::vector<std::int32_t> signs;
  const std::size_t stride = width + 2;
  magnitudes.assign(2 * stride, 0u);
  signs.assign(2 * stride, 0);
  std::uint32_t largest = 0;
  for (std::size_t y = 0; y < height; ++y) {
    const PcContext::Row row = ctx.row(y);
    const std::size_t above_at = ((y + 1) & 1u) * stride, out_at = (y & 1u) * stride + 1;
    const std::uint32_t* above = magnitudes.data() + above_at;
    const std::int32_t* signs_above = signs.data() + above_at;
    std::uint32_t* magnitudes_out = magnitudes.data() + out_at;  // each coefficient joins the contexts here
    std::int32_t* signs_out = signs.data() + out_at;
    std::uint64_t w = 0, nw = above[0], n = above[1];  // the left padding column is zero
    int sign_w = 0;
    for (std::size_t x = 0; x < width; ++x) {
      const std::uint64_t ne = above[x + 2];
      const std::int32_t v = code(x, y, row.at(x, 2 * (w + n) + nw + ne, sign_w, signs_above[x + 1]));
      w = PcContext::magnitude(v);
      sign_w = PcContext::sign_of(v);
      magnitudes_out[x] = std::uint32_t(w);
      signs_out[x] = sign_w;
      nw = n;
      n = ne;
      largest = std::max(largest, std::uint32_t(w));
    }
  }
  return largest;
}

}  // namespace pupwave
