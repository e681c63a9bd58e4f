#include "codec/entropy/block_index.h"

#include <array>
#include <bit>
#include <string>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"
#include "codec/error.h"

namespace pupwave {
namespace {

// Adaptive Elias-gamma-like code for unsigned integers: the bit length in unary with one
// adaptive model per position, then the bits below the leading one.
struct UintModels {
  std::array<BitModel, 34> length;
  std::array<BitModel, 34> top;  // first bit below the leading one, per length
};

void encode_uint(RangeEncoder& rc, UintModels& m, std::uint32_t v) {
  const int bits = std::bit_width(v);
  for (int k = 0; k < bits; ++k) rc.encode(1, m.length[std::size_t(k)]);
  rc.encode(0, m.length[std::size_t(bits)]);
  for (int k = bits - 2; k >= 0; --k) {
    const int bit = int((v >> k) & 1u);
    if (k == bits - 2)
      rc.encode(bit, m.top[std::size_t(bits)]);
    else
      rc.encode_equiprobable(bit);
  }
}

// Returns false for a bit length beyond 32 (only corrupt input has one).
bool decode_uint(RangeDecoder& rc, UintModels& m, std::uint32_t& v) {
  int bits = 0;
  while (rc.decode(m.length[std::size_t(bits)])) {
    if (++bits > 32) return false;
  }
  v = bits ? 1u : 0u;
  for (int k = bits - 2; k >= 0; --k) {
    const int bit = k == bits - 2 ? rc.decode(m.top[std::size_t(bits)]) : rc.decode_equiprobable();
    v = (v << 1) | std::uint32_t(bit);
  }
  return true;
}

std::uint32_t zigzag(int v) { return v >= 0 ? std::uint32_t(v) << 1 : (std::uint32_t(-v) << 1) - 1; }
std::int64_t unzigzag(std::uint32_t v) {
  return (v & 1u) ? -(std::int64_t(v >> 1) + 1) : std::int64_t(v >> 1);
}

// Models shared by the encoder and decoder, with contexts from the previous entry.
struct IndexModels {
  std::array<UintModels, 2> passes;  // context: previous block had passes or not
  UintModels planes;                 // zigzag difference to the previous block's planes
  std::array<UintModels, 4> length;  // context: bucket of the pass count
  int previous_planes = 0;
  int previous_passes = 0;
  static std::size_t length_context(int passes) {
    return passes < 4 ? 0 : passes < 10 ? 1 : passes < 20 ? 2 : 3;
  }
};

}  // namespace

std::vector<std::uint8_t> encode_index(std::span<const BlockEntry> entries) {
  RangeEncoder rc;
  IndexModels m;
  for (const BlockEntry& e : entries) {
    encode_uint(rc, m.passes[m.previous_passes > 0], std::uint32_t(e.passes));
    m.previous_passes = e.passes;
    if (e.passes == 0) continue;
    encode_uint(rc, m.planes, zigzag(e.planes - m.previous_planes));
    m.previous_planes = e.planes;
    encode_uint(rc, m.length[IndexModels::length_context(e.passes)], e.length);
  }
  return rc.finish();
}

std::vector<BlockEntry> decode_index(std::span<const std::uint8_t> bytes, std::size_t count) {
  RangeDecoder rc(bytes);
  IndexModels m;
  std::vector<BlockEntry> entries(count);
  for (std::size_t i = 0; i < count; ++i) {
    BlockEntry& e = entries[i];
    std::uint32_t passes = 0, planes = 0, length = 0;
    require_stream(decode_uint(rc, m.passes[m.previous_passes > 0], passes), "block index: bad pass count");
    require_stream(passes <= std::uint32_t(passes_for_planes(kMaxBitPlanes)), "block index: bad pass count");
    e.passes = int(passes);
    m.previous_passes = e.passes;
    if (e.passes == 0) continue;
    require_stream(decode_uint(rc, m.planes, planes), "block index: bad bit-plane count");
    const std::int64_t p = m.previous_planes + unzigzag(planes);
    require_stream(p >= 1 && p <= kMaxBitPlanes && e.passes <= passes_for_planes(int(p)), [&] {
      return "block index: bit-plane count " + std::to_string(p) + " for " + std::to_string(e.passes) +
             " passes";
    });
    e.planes = int(p);
    m.previous_planes = e.planes;
    require_stream(decode_uint(rc, m.length[IndexModels::length_context(e.passes)], length),
                   "block index: bad codeword length");
    e.length = length;
  }
  return entries;
}

}  // namespace pupwave
