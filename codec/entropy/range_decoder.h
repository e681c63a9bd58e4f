#pragma once
// Decoder of the adaptive binary range coder (see range_encoder.h). Reads past the end of
// its codeword as zero bytes, which is how truncated codewords are completed; any byte
// sequence decodes to some bits without reading outside the given span.

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>

#include "codec/entropy/bit_model.h"

namespace pupwave {

class RangeDecoder {
 public:
  explicit RangeDecoder(std::span<const std::uint8_t> codeword) : in_(codeword) {
    for (int i = 0; i < 4; ++i) code_ = (code_ << 8) | (pos_ < in_.size() ? in_[pos_++] : 0u);
  }

  // Decodes one bit with the adaptive probability `model`, then adapts it.
  int decode(BitModel& model) {
    const int bit = decode_with(model.p0);
    model.update(bit);
    return bit;
  }
  int decode_equiprobable() { return decode_with(kProbabilityOne / 2); }

 private:
  // Branch-free: the bit of a well-adapted context is unpredictable, so selects beat a
  // mispredicted jump; renormalisation shifts in whole bytes counted by leading zeros.
  int decode_with(std::uint32_t p0) {
    const std::uint32_t bound = (range_ >> kProbabilityBits) * p0;
    const int bit = code_ >= bound ? 1 : 0;
    const std::uint32_t taken = bound & (0u - std::uint32_t(bit));
    code_ -= taken;
    range_ = bit ? range_ - bound : bound;
    // range_ >= 2^13 after any decision (p0 >= 31), so at most 2 bytes are shifted in.
    const int bytes = std::countl_zero(range_) >> 3;
    range_ <<= 8 * bytes;
    code_ = (code_ << (8 * bytes)) | next_bytes(bytes);
    return bit;
  }
  // The next `bytes` (0..2) bytes of the codeword, big-endian, zeros past its end.
  std::uint32_t next_bytes(int bytes) {
    std::uint32_t word = 0;
    if (pos_ + 4 <= in_.size()) {
      std::memcpy(&word, in_.data() + pos_, 4);
      if constexpr (std::endian::native == std::endian::little) word = byteswap32(word);
    } else {
      for (std::size_t k = 0; k < 4; ++k) word = (word << 8) | (pos_ + k < in_.size() ? in_[pos_ + k] : 0u);
    }
    pos_ += std::size_t(bytes);
    return std::uint32_t(std::uint64_t(word) >> (32 - 8 * bytes));
  }
  static std::uint32_t byteswap32(std::uint32_t v) {
    return (v >> 24) | ((v >> 8) & 0xFF00u) | ((v << 8) & 0xFF0000u) | (v << 24);
  }

  std::span<const std::uint8_t> in_;
  std::size_t pos_ = 0;
  std::uint32_t code_ = 0;
  std::uint32_t range_ = 0xFFFFFFFFu;
};

}  // namespace pupwave
