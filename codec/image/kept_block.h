#pragma once
// Internal to the image encoder (image_encoder.cpp): a code-block's coded passes as rate
// control holds them until the final cut.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "codec/entropy/block_encoder.h"
#include "codec/entropy/range_encoder.h"

namespace pupwave {

// A coded block as rate control keeps it until the final cut: EncodedBlock's truncation points
// in flat arrays (a heap-allocated tail per pass costs more than the pass's bytes: about 0.35
// GB over the 262,144 blocks of a 32768^2 image), with the same sizes and codewords.
class KeptBlock {
 public:
  KeptBlock() = default;
  explicit KeptBlock(EncodedBlock&& b)
      : planes(b.planes),
        initial_distortion(b.initial_distortion),
        committed(std::move(b.committed)),
        distortion_drop(std::move(b.distortion_drop)) {
    committed.shrink_to_fit();  // the coder's buffer grows by doubling
    distortion_drop.shrink_to_fit();
    prefix_.reserve(b.passes.size());
    tail_end_.reserve(b.passes.size());
    for (const TruncationPoint& p : b.passes) {
      prefix_.push_back(std::uint32_t(p.prefix));
      tails_.insert(tails_.end(), p.tail.begin(), p.tail.end());
      tail_end_.push_back(std::uint32_t(tails_.size()));
    }
    tails_.shrink_to_fit();
  }

  int pass_count() const { return int(prefix_.size()); }
  // Size in bytes of the codeword of the first n passes (EncodedBlock::size).
  std::size_t size(int n) const {
    return n > 0 ? prefix_[std::size_t(n - 1)] + tail_end_[std::size_t(n - 1)] - tail_begin(n - 1) : 0;
  }
  // The codeword of the first n passes: the committed prefix, then that pass's tail (as
  // RangeEncoder::codeword builds it).
  std::vector<std::uint8_t> codeword(int n) const {
    if (n <= 0) return {};
    const auto k = std::size_t(n - 1);
    std::vector<std::uint8_t> bytes;
    bytes.reserve(size(n));
    bytes.insert(bytes.end(), committed.begin(), committed.begin() + std::ptrdiff_t(prefix_[k]));
    bytes.insert(bytes.end(), tails_.begin() + std::ptrdiff_t(tail_begin(n - 1)),
                 tails_.begin() + std::ptrdiff_t(tail_end_[k]));
    return bytes;
  }

  int planes = 0;
  double initial_distortion = 0.0;
  std::vector<std::uint8_t> committed;
  std::vector<double> distortion_drop;

 private:
  std::size_t tail_begin(int k) const { return k > 0 ? tail_end_[std::size_t(k - 1)] : 0; }
  std::vector<std::uint32_t> prefix_;    // per pass: bytes of `committed` its codeword starts with
  std::vector<std::uint32_t> tail_end_;  // per pass: end of its tail in tails_
  std::vector<std::uint8_t> tails_;
};

}  // namespace pupwave
