#pragma once
// Decoder of the adaptive binary range coder (see range_encoder.h). Reads past the end of
// its codeword as zero bytes, which is how truncated codewords are completed; any byte
// sequence decodes to some bits without reading outside the given span.

#include <cstdint>
#include <span>

#include "codec/entropy/bit_model.h"

namespace pupwave {

class RangeDecoder {
 public:
  explicit RangeDecoder(std::span<const std::uint8_t> codeword) : in_(codeword) {
    for (int i = 0; i < 4; ++i) code_ = (code_ << 8) | next_byte();
  }

  // Decodes one bit with the adaptive probability `model`, then adapts it.
  int decode(BitModel& model) {
    const int bit = decode_with(model.p0);
    model.update(bit);
    return bit;
  }
  int decode_equiprobable() { return decode_with(kProbabilityOne / 2); }

 private:
  int decode_with(std::uint32_t p0) {
    const std::uint32_t bound = (range_ >> kProbabilityBits) * p0;
    int bit;
    if (code_ < bound) {
      range_ = bound;
      bit = 0;
    } else {
      code_ -= bound;
      range_ -= bound;
      bit = 1;
    }
    while (range_ < (1u << 24)) {
      range_ <<= 8;
      code_ = (code_ << 8) | next_byte();
    }
    return bit;
  }
  std::uint32_t next_byte() { return pos_ < in_.size() ? in_[pos_++] : 0u; }

  std::span<const std::uint8_t> in_;
  std::size_t pos_ = 0;
  std::uint32_t code_ = 0;
  std::uint32_t range_ = 0xFFFFFFFFu;
};

}  // namespace pupwave
