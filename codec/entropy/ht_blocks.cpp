#include "codec/entropy/ht_blocks.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdlib>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/block_encoder.h"
#include "codec/entropy/ht_bits.h"
#include "codec/error.h"

namespace pupwave {
namespace {

// Run length exponents by run state (JPEG-LS's table): a state codes runs of up to 2^E - 1
// zeros in E + 1 bits, a full run of 2^E zeros in one bit; long runs raise the state.
constexpr std::array<int, 32> kRunExponent = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,  2,  3,  3,  3,  3,
                                              4, 4, 5, 5, 6, 6, 7, 7, 8, 9, 10, 11, 12, 13, 14, 15};
constexpr int kRunStates = int(kRunExponent.size());
// Rice quotients from this on are escaped: the value's bit length in 5 bits, then its bits.
constexpr int kEscapeQuotient = 16;
constexpr int kBitLengthBits = 5;
// Context 0 codes the magnitude - 1 of the nonzero that ends a run; contexts 1.. the bit length
// of the neighbours' weighted sum 2W + 2N + NW + NE, capped.
constexpr int kContexts = 25;
// Magnitudes are capped here in the neighbour rows and statistics, so sums fit 32 bits.
constexpr std::uint32_t kMagnitudeCap = std::uint32_t(1) << 25;
// Statistics halve when this many values were seen: recent values weigh more.
constexpr std::uint32_t kStatsWindow = 32;

// Adaptive Golomb-Rice parameter of one context (LOCO-I's A and N).
struct RiceStats {
  std::uint32_t sum = 1, count = 1;
  // The smallest k with count * 2^k >= sum: the bit-length difference, or one more.
  int k() const {
    int k = std::max(0, int(std::bit_width(sum)) - int(std::bit_width(count)));
    if ((std::uint64_t(count) << k) < sum) ++k;
    return k;
  }
  void update(std::uint32_t v) {
    sum += std::min(v, kMagnitudeCap);
    if (++count == kStatsWindow) {
      sum = (sum + 1) >> 1;
      count >>= 1;
    }
  }
};

struct Contexts {
  std::array<RiceStats, kContexts> rice{};
  int run_state = 0;
  Contexts() {
    // A context of bit length c holds neighbours of sum about 2^(c-1) over weight 6.
    for (int c = 1; c < kContexts; ++c) rice[std::size_t(c)].sum = std::max(1u, (1u << (c - 1)) / 6u);
  }
};

// The context of a coefficient from its padded magnitude rows (cur[x] is W, up[x + 1] is N).
inline std::uint32_t neighbour_sum(const std::uint32_t* up, const std::uint32_t* cur, std::size_t x) {
  return 2 * cur[x] + 2 * up[x + 1] + up[x] + up[x + 2];
}
inline int context_of(std::uint32_t sum) { return std::min(int(std::bit_width(sum)), kContexts - 1); }

// Writes v with Rice parameter k and, for v > 0 when `sign` >= 0, the sign bit.
inline void put_rice(HtBitWriter& w, std::uint32_t v, int k, int sign) {
  const std::uint32_t quotient = v >> k;
  const int extra = sign >= 0 ? 1 : 0;
  if (quotient < std::uint32_t(kEscapeQuotient)) {
    const int n = int(quotient) + 1 + k + extra;
    const std::uint64_t code = ((std::uint64_t(1) << k) | (v & ((std::uint64_t(1) << k) - 1)));
    if (n <= 32) {
      w.put(extra ? (code << 1) | std::uint64_t(sign) : code, n);
    } else {
      w.put(0, int(quotient));
      w.put(code, k + 1);
      if (extra) w.put(std::uint64_t(sign), 1);
    }
    return;
  }
  w.put(0, kEscapeQuotient);
  const int bits = int(std::bit_width(v));
  w.put(std::uint64_t(bits), kBitLengthBits);
  if (bits > 1) w.put(v & ((1u << (bits - 1)) - 1u), bits - 1);
  if (extra) w.put(std::uint64_t(sign), 1);
}

// Reads a value written by put_rice (without its sign).
inline std::uint64_t get_rice(HtBitReader& r, int k) {
  const int zeros = std::countl_zero(r.peek());
  if (zeros < kEscapeQuotient) {
    r.skip(zeros + 1);
    return (std::uint64_t(zeros) << k) | r.get(k);
  }
  r.skip(kEscapeQuotient);
  const int bits = int(r.get(kBitLengthBits));
  require_stream(bits <= kMaxBitPlanes, "ht code-block: escaped magnitude too long");
  if (bits <= 1) return std::uint64_t(bits);
  return (std::uint64_t(1) << (bits - 1)) | r.get(bits - 1);
}

// Whether every index is 0, ORed 16 at a time (vectorized) so a nonzero block stops early.
bool all_zero(std::span<const std::int32_t> indices) {
  const std::int32_t* p = indices.data();
  const std::size_t n = indices.size();
  std::size_t k = 0;
  for (; k + 16 <= n; k += 16) {
    std::uint32_t any = 0;
    for (std::size_t j = 0; j < 16; ++j) any |= std::uint32_t(p[k + j]);
    if (any != 0) return false;
  }
  for (; k < n; ++k)
    if (p[k] != 0) return false;
  return true;
}

void update_run_state(Contexts& c, int change) {
  c.run_state = std::clamp(c.run_state + change, 0, kRunStates - 1);
}

// Codes the zeros of row `q` from x on until a nonzero (coded too) or the row's end; returns
// the position after them.
std::size_t encode_run(HtBitWriter& w, Contexts& c, const std::int32_t* q, std::size_t x, std::size_t width,
                       std::uint32_t* cur, std::uint32_t& all) {
  // The zeros are found first, then their full runs written one per step (not one step per
  // zero: at low rates most of a block is runs): the same bits as counting them one by one.
  const std::size_t start = x;
  while (x < width && q[x] == 0) ++x;
  std::size_t count = x - start;
  for (std::size_t run; count >= (run = std::size_t(1) << kRunExponent[std::size_t(c.run_state)]);) {
    w.put(1, 1);
    count -= run;
    update_run_state(c, 1);
  }
  if (x == width) {
    if (count > 0) w.put(1, 1);  // a run cut short by the row's end
    return x;
  }
  w.put(count, kRunExponent[std::size_t(c.run_state)] + 1);  // a 0, then the run length
  update_run_state(c, -1);
  const std::uint32_t v = std::uint32_t(std::abs(q[x]));
  all |= v;
  RiceStats& s = c.rice[0];
  put_rice(w, v - 1, s.k(), q[x] < 0);
  s.update(v - 1);
  cur[x + 1] = std::min(v, kMagnitudeCap);
  return x + 1;
}

std::size_t decode_run(HtBitReader& r, Contexts& c, std::int32_t* q, std::size_t x, std::size_t width,
                       std::uint32_t* cur) {
  for (;;) {
    const int e = kRunExponent[std::size_t(c.run_state)];
    const std::size_t left = width - x;
    if (r.get(1)) {
      const std::size_t run = std::size_t(1) << e;
      if (run > left) {  // cut short by the row's end
        std::fill_n(q + x, left, 0);
        return width;
      }
      std::fill_n(q + x, run, 0);
      x += run;
      update_run_state(c, 1);
      if (x == width) return x;
      continue;
    }
    const std::size_t run = r.get(e);
    require_stream(run < left, "ht code-block: run past the row's end");
    std::fill_n(q + x, run, 0);
    x += run;
    update_run_state(c, -1);
    RiceStats& s = c.rice[0];
    const std::uint64_t v = get_rice(r, s.k()) + 1;
    require_stream(v < (std::uint64_t(1) << kMaxBitPlanes), "ht code-block: magnitude too large");
    const bool negative = r.get(1) != 0;
    s.update(std::uint32_t(v - 1));
    q[x] = negative ? -std::int32_t(v) : std::int32_t(v);
    cur[x + 1] = std::min(std::uint32_t(v), kMagnitudeCap);
    return x + 1;
  }
}

}  // namespace

HtCodeword ht_encode_block(std::span<const std::int32_t> indices, std::size_t width, std::size_t height) {
  HtCodeword out;
  if (all_zero(indices)) return out;
  // Magnitude rows padded by one column each side; row 0 is the zero row above the block.
  const std::size_t stride = width + 2;
  thread_local std::vector<std::uint32_t> rows;
  rows.assign(stride * (height + 1), 0);
  thread_local std::vector<std::uint8_t> scratch;
  Contexts c;
  HtBitWriter w(scratch);
  std::uint32_t all = 0;  // every magnitude OR-ed, gathered while coding (not a pass of its own)
  for (std::size_t y = 0; y < height; ++y) {
    const std::uint32_t* up = rows.data() + y * stride;
    std::uint32_t* cur = rows.data() + (y + 1) * stride;
    const std::int32_t* q = indices.data() + y * width;
    for (std::size_t x = 0; x < width;) {
      const std::uint32_t sum = neighbour_sum(up, cur, x);
      if (sum == 0) {
        x = encode_run(w, c, q, x, width, cur, all);
        continue;
      }
      RiceStats& s = c.rice[std::size_t(context_of(sum))];
      const std::uint32_t v = std::uint32_t(std::abs(q[x]));
      all |= v;
      put_rice(w, v, s.k(), v != 0 ? int(q[x] < 0) : -1);
      s.update(v);
      cur[x + 1] = std::min(v, kMagnitudeCap);
      ++x;
    }
  }
  // Checked after coding: a too-large magnitude only makes codes that are thrown away.
  if (int(std::bit_width(all)) > kMaxBitPlanes)
    throw IndexRangeError("quantization index too large for the ht coder");
  out.planes = int(std::bit_width(all));
  out.bytes = w.finish();
  return out;
}

void ht_decode_block(std::span<const std::uint8_t> codeword, std::size_t width, std::size_t height,
                     int planes, std::int32_t* out) {
  require_stream(planes >= 1 && planes <= kMaxBitPlanes && !codeword.empty(),
                 "ht code-block: empty codeword");
  const std::size_t stride = width + 2;
  thread_local std::vector<std::uint32_t> rows;
  rows.assign(stride * (height + 1), 0);
  Contexts c;
  HtBitReader r(codeword);
  std::uint64_t all = 0;
  for (std::size_t y = 0; y < height; ++y) {
    const std::uint32_t* up = rows.data() + y * stride;
    std::uint32_t* cur = rows.data() + (y + 1) * stride;
    std::int32_t* q = out + y * width;
    for (std::size_t x = 0; x < width;) {
      const std::uint32_t sum = neighbour_sum(up, cur, x);
      if (sum == 0) {
        x = decode_run(r, c, q, x, width, cur);
        all |= std::uint64_t(std::abs(std::int64_t(q[x - 1])));  // the nonzero that ended the run, or 0
        continue;
      }
      RiceStats& s = c.rice[std::size_t(context_of(sum))];
      const std::uint64_t v = get_rice(r, s.k());
      all |= v;
      const std::int32_t sign = v != 0 ? -std::int32_t(r.get(1)) : 0;  // 0 or -1
      s.update(std::uint32_t(std::min<std::uint64_t>(v, kMagnitudeCap)));
      q[x] = (std::int32_t(v) ^ sign) - sign;
      cur[x + 1] = std::uint32_t(std::min<std::uint64_t>(v, kMagnitudeCap));
      ++x;
    }
    require_stream(!r.overran(codeword.size()), "ht code-block: truncated");
  }
  require_stream((r.consumed() + 7) / 8 == codeword.size(),
                 "ht code-block: length does not match its indices");
  require_stream(int(std::bit_width(all)) == planes,
                 "ht code-block: magnitudes do not match the bit-plane count");
}

}  // namespace pupwave
