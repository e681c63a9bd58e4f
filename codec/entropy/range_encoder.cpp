#include "codec/entropy/range_encoder.h"

#include <algorithm>

namespace pupwave {
namespace {

// Moves the top byte of `low` out of the 32-bit window; bytes become final once no carry
// can reach them. Shared by the encoder and its truncation-point flush.
void shift_low_into(std::uint64_t& low, std::uint8_t& cache, std::uint64_t& pending,
                    std::vector<std::uint8_t>& out) {
  if (std::uint32_t(low) < 0xFF000000u || (low >> 32) != 0) {
    const auto carry = std::uint8_t(low >> 32);
    std::uint8_t byte = cache;
    do {
      out.push_back(std::uint8_t(byte + carry));
      byte = 0xFF;
    } while (--pending != 0);
    cache = std::uint8_t(low >> 24);
  }
  ++pending;
  low = (low & 0x00FFFFFFu) << 8;
}

}  // namespace

void RangeEncoder::shift_low() { shift_low_into(low_, cache_, pending_, out_); }

std::span<const std::uint8_t> RangeEncoder::committed() const {
  return out_.empty() ? std::span<const std::uint8_t>() : std::span<const std::uint8_t>(out_).subspan(1);
}

TruncationPoint RangeEncoder::truncation_point() const {
  // Any value in [low, low + range) decodes the same bits. Rounding low up to a multiple of
  // 2^24 stays inside because range >= 2^24, and leaves one significant byte to emit.
  std::uint64_t low = (low_ + 0x00FFFFFFu) & ~std::uint64_t(0x00FFFFFFu);
  std::uint8_t cache = cache_;
  std::uint64_t pending = pending_;
  std::vector<std::uint8_t> tail;
  shift_low_into(low, cache, pending, tail);
  shift_low_into(low, cache, pending, tail);
  TruncationPoint point;
  point.prefix = out_.empty() ? 0 : out_.size() - 1;
  // The very first byte the coder emits is always 0 and is not stored.
  if (out_.empty() && !tail.empty()) tail.erase(tail.begin());
  while (!tail.empty() && tail.back() == 0) tail.pop_back();
  if (tail.empty())
    while (point.prefix > 0 && out_[point.prefix] == 0) --point.prefix;
  point.tail = std::move(tail);
  return point;
}

std::vector<std::uint8_t> RangeEncoder::codeword(std::span<const std::uint8_t> stream,
                                                 const TruncationPoint& point) {
  std::vector<std::uint8_t> bytes(stream.begin(), stream.begin() + std::ptrdiff_t(point.prefix));
  bytes.insert(bytes.end(), point.tail.begin(), point.tail.end());
  return bytes;
}

std::vector<std::uint8_t> RangeEncoder::finish() const { return codeword(committed(), truncation_point()); }

}  // namespace pupwave
