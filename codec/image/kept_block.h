#pragma once
// Internal to the image encoder (image_encoder.cpp): a code-block's coded passes as rate
// control holds them until the final cut.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "codec/entropy/block_encoder.h"

namespace pupwave {

// A coded block as rate control keeps it until the final cut: EncodedBlock's truncation points
// with the same sizes and codewords, in one allocation (a heap-allocated tail per pass cost
// more than the pass's bytes, about 0.35 GB over the 262,144 blocks of a 32768^2 image, and
// a vector per field 0.05 GB more).
class KeptBlock {
 public:
  KeptBlock() = default;
  // The block's first `limit` passes (all by default), with each pass's distortion drop when
  // `distortions` (the PSNR search needs them; a byte budget needs only the hull).
  explicit KeptBlock(EncodedBlock&& b, int limit = std::numeric_limits<int>::max(), bool distortions = true);

  int pass_count() const { return int(passes_); }
  // Size in bytes of the codeword of the first n passes (EncodedBlock::size).
  std::size_t size(int n) const;
  // Appends the codeword of the first n passes: the committed prefix, then that pass's tail
  // (as RangeEncoder::codeword builds it).
  void append_codeword(int n, std::vector<std::uint8_t>& out) const;
  // Squared error removed by pass k (index units); throws std::logic_error if not kept.
  double distortion_drop(int k) const;
  // Keeps the first n passes only: rate control has found it will never choose more.
  void truncate(int n);
  // Bytes of its allocation.
  std::size_t bytes_held() const;

  int planes = 0;
  double initial_distortion = 0.0;

 private:
  // Layout of data_: per pass the u32 length of `committed` its codeword starts with, then per
  // pass the u32 end of its tail in the tails, [per pass the f64 distortion drop], then the
  // committed bytes the codewords use, then the tails one after another.
  std::size_t prefix(std::size_t k) const;
  std::size_t tail_end(std::size_t k) const;
  std::size_t committed_at() const { return passes_ * (distortions_ ? 16 : 8); }
  std::size_t tails_at() const { return committed_at() + committed_; }

  std::unique_ptr<std::uint8_t[]> data_;
  std::uint32_t passes_ = 0, committed_ = 0, tails_ = 0;
  bool distortions_ = false;
};

}  // namespace pupwave
