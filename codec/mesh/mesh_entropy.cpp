#include "codec/mesh/mesh_entropy.h"

#include <bit>
#include <stdexcept>

#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"
#include "codec/error.h"

namespace pupwave::mesh {
namespace {

constexpr int kPrefixContexts = 42;

struct AxisContexts {
  std::array<BitModel, 3> zero;  // by magnitude class of the previous value: 0, 1, >= 2
  std::array<BitModel, kPrefixContexts> prefix;
  int previous_class = 0;
};

int magnitude_class(std::int64_t v) { return v == 0 ? 0 : (v == 1 || v == -1) ? 1 : 2; }

void encode_one(RangeEncoder& enc, AxisContexts& ctx, std::int64_t v) {
  enc.encode(v == 0 ? 1 : 0, ctx.zero[std::size_t(ctx.previous_class)]);
  ctx.previous_class = magnitude_class(v);
  if (v == 0) return;
  enc.encode_equiprobable(v < 0 ? 1 : 0);
  const std::uint64_t m = std::uint64_t(v < 0 ? -v : v);  // >= 1: code m as Exp-Golomb of m - 1
  const int k = int(std::bit_width(m)) - 1;
  for (int i = 0; i < k; ++i) enc.encode(1, ctx.prefix[std::size_t(i)]);
  enc.encode(0, ctx.prefix[std::size_t(k)]);
  for (int i = k - 1; i >= 0; --i) enc.encode_equiprobable(int((m >> i) & 1u));
}

std::int64_t decode_one(RangeDecoder& dec, AxisContexts& ctx) {
  const bool zero = dec.decode(ctx.zero[std::size_t(ctx.previous_class)]) != 0;
  if (zero) {
    ctx.previous_class = 0;
    return 0;
  }
  const bool negative = dec.decode_equiprobable() != 0;
  int k = 0;
  while (dec.decode(ctx.prefix[std::size_t(k)]) != 0) {
    if (++k >= kPrefixContexts - 1)
      throw DecodeError("mesh details: integer prefix too long (corrupt stream)");
  }
  std::uint64_t m = 1;
  for (int i = 0; i < k; ++i) m = (m << 1) | std::uint64_t(dec.decode_equiprobable());
  const std::int64_t v = negative ? -std::int64_t(m) : std::int64_t(m);
  ctx.previous_class = magnitude_class(v);
  return v;
}

}  // namespace

std::vector<std::uint8_t> encode_triples(std::span<const std::int64_t> values) {
  if (values.size() % 3 != 0) throw std::invalid_argument("encode_triples: count not a multiple of 3");
  RangeEncoder enc;
  std::array<AxisContexts, 3> ctx{};
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] > kMaxQuantised || values[i] < -kMaxQuantised) {
      throw std::invalid_argument("quantised mesh value out of range (step too small for the mesh)");
    }
    encode_one(enc, ctx[i % 3], values[i]);
  }
  return enc.finish();
}

std::vector<std::int64_t> decode_triples(std::span<const std::uint8_t> bytes, std::size_t count) {
  RangeDecoder dec(bytes);
  std::array<AxisContexts, 3> ctx{};
  std::vector<std::int64_t> v(count);
  for (std::size_t i = 0; i < count; ++i) v[i] = decode_one(dec, ctx[i % 3]);
  return v;
}

}  // namespace pupwave::mesh
