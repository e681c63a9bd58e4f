#pragma once
// Decoder of the adaptive binary range coder (see range_encoder.h). Reads past the end of
// its codeword as zero bytes, which is how truncated codewords are completed; any byte
// sequence decodes to some bits without reading outside the given span.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>

#include "codec/entropy/bit_model.h"

namespace pupwave {

class RangeDecoder {
 public:
  explicit RangeDecoder(std::span<const std::uint8_t> codeword)
      : next_(codeword.data()), end_(codeword.data() + codeword.size()) {
    code_ = next_bytes(4);
  }

  // Decodes one bit with the adaptive probability `model`, then adapts it.
  int decode(BitModel& model) {
    const int bit = decode_with(model.p0);
    model.update(bit);
    return bit;
  }
  // Inverse of RangeEncoder::encode_probability.
  int decode_probability(std::uint32_t p0) { return decode_with(p0); }
  int decode_equiprobable() { return decode_with(kProbabilityOne / 2); }
  // Inverse of RangeEncoder::encode_raw: `n` (1..16) raw bits. A corrupt codeword can put the
  // code past the last part; the value is then clamped (wrong bits, never out of range).
  std::uint32_t decode_raw(int n) {
    const std::uint32_t part = range_ >> n;
    const std::uint32_t value = std::min(code_ / part, (1u << n) - 1u);
    code_ -= value * part;
    range_ = part;
    // part >= 2^8 (range >= 2^24 before), so at most 2 bytes are shifted in.
    if (range_ < (1u << 24)) {
      const int bytes = std::countl_zero(range_) >> 3;
      range_ <<= 8 * bytes;
      code_ = (code_ << (8 * bytes)) | next_bytes(bytes);
    }
    return value;
  }

 private:
  // The bit is selected without a branch: the bit of a well-adapted context is
  // unpredictable, and a mispredicted jump costs more than computing both outcomes.
  int decode_with(std::uint32_t p0) {
    const std::uint32_t bound = (range_ >> kProbabilityBits) * p0;
    // zero: all ones when the bit is 0 (code below bound), from the borrow of the 64-bit
    // difference, so GCC cannot turn the selection into a jump.
    const std::uint32_t zero = std::uint32_t((std::uint64_t(code_) - bound) >> 32);
    const int bit = int(zero + 1u);
    code_ -= bound & ~zero;
    range_ = (bound & zero) | ((range_ - bound) & ~zero);
    // Renormalisation is rare (about once per 8 bits of output), so a branch keeps the
    // leading-zero count off the common path. range_ >= 2^13 after any decision
    // (p0 >= 31), so at most 2 bytes are shifted in.
    if (range_ < (1u << 24)) {
      const int bytes = std::countl_zero(range_) >> 3;
      range_ <<= 8 * bytes;
      code_ = (code_ << (8 * bytes)) | next_bytes(bytes);
    }
    return bit;
  }
  // The next `bytes` (0..4) bytes of the codeword, big-endian, zeros past its end.
  std::uint32_t next_bytes(int bytes) {
    std::uint32_t word = 0;
    if (end_ - next_ >= 4) {
      std::memcpy(&word, next_, 4);
      if constexpr (std::endian::native == std::endian::little) word = byteswap32(word);
    } else {
      const std::ptrdiff_t left = end_ - next_;
      for (std::ptrdiff_t k = 0; k < 4; ++k) word = (word << 8) | (k < left ? next_[k] : 0u);
    }
    next_ += std::min<std::ptrdiff_t>(bytes, end_ - next_);
    return std::uint32_t(std::uint64_t(word) >> (32 - 8 * bytes));
  }
  static std::uint32_t byteswap32(std::uint32_t v) {
    return (v >> 24) | ((v >> 8) & 0xFF00u) | ((v << 8) & 0xFF0000u) | (v << 24);
  }

  const std::uint8_t* next_;  // next unread byte of the codeword
  const std::uint8_t* end_;
  std::uint32_t code_ = 0;
  std::uint32_t range_ = 0xFFFFFFFFu;
};

}  // namespace pupwave
