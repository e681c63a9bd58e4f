#pragma once
// Bit packing for the high-throughput block coder (ht_blocks.h): MSB-first, 64 bits at a time,
// no arithmetic coding. The reader treats its input as hostile: bits past the end read as 0
// and are counted, so a decoder checks `overran()` once per block instead of every read.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <utility>
#include <vector>

namespace pupwave {

class HtBitWriter {
 public:
  // Packs into `scratch`, reused from block to block (its size is its capacity here), so a block
  // costs one allocation of the exact size in finish() instead of a growing vector's several.
  explicit HtBitWriter(std::vector<std::uint8_t>& scratch) : out_(scratch) {}
  // Appends the low `n` bits of v (n <= 32), most significant first.
  void put(std::uint64_t v, int n) {
    acc_ = (acc_ << n) | v;
    used_ += n;
    if (used_ >= 32) {
      used_ -= 32;
      if (out_.size() < size_ + 4) out_.resize(std::max<std::size_t>(256, 2 * out_.size()));
      const auto word = std::uint32_t(acc_ >> used_);
      std::uint8_t* p = out_.data() + size_;
      p[0] = std::uint8_t(word >> 24);
      p[1] = std::uint8_t(word >> 16);
      p[2] = std::uint8_t(word >> 8);
      p[3] = std::uint8_t(word);
      size_ += 4;
    }
  }
  // The bytes written, the last one padded with zeros.
  std::vector<std::uint8_t> finish() {
    std::vector<std::uint8_t> bytes(size_ + std::size_t(used_ + 7) / 8);
    std::copy_n(out_.data(), size_, bytes.data());
    std::size_t n = size_;
    while (used_ >= 8) {
      used_ -= 8;
      bytes[n++] = std::uint8_t(acc_ >> used_);
    }
    if (used_ > 0) bytes[n] = std::uint8_t(acc_ << (8 - used_));
    used_ = 0;
    size_ = 0;
    return bytes;
  }
  std::size_t bits() const { return size_ * 8 + std::size_t(used_); }

 private:
  std::uint64_t acc_ = 0;
  int used_ = 0;  // bits of acc_ not yet in out_ (< 32)
  std::vector<std::uint8_t>& out_;
  std::size_t size_ = 0;  // bytes of out_ written
};

class HtBitReader {
 public:
  explicit HtBitReader(std::span<const std::uint8_t> bytes)
      : p_(bytes.data()), end_(bytes.data() + bytes.size()) {
    refill();
  }
  // The next 64 bits, left-aligned, without consuming them (at least 57 are valid).
  std::uint64_t peek() const { return buf_; }
  void skip(int n) {  // n <= 57
    buf_ <<= n;
    have_ -= n;
    consumed_ += std::size_t(n);
    if (have_ < 57) refill();
  }
  std::uint32_t get(int n) {  // 0 <= n <= 32
    if (n == 0) return 0;
    const auto v = std::uint32_t(buf_ >> (64 - n));
    skip(n);
    return v;
  }
  // Bits consumed so far, and whether that went past the end of the input.
  std::size_t consumed() const { return consumed_; }
  bool overran(std::size_t size_bytes) const { return consumed_ > size_bytes * 8; }

 private:
  void refill() {
    if (end_ - p_ >= 8) {  // the fast path: one unaligned 8-byte load
      std::uint64_t w;
      std::memcpy(&w, p_, 8);
      if constexpr (std::endian::native == std::endian::little) w = __builtin_bswap64(w);
      buf_ |= w >> have_;
      const int take = (64 - have_) >> 3;
      p_ += take;
      have_ += take * 8;
      buf_ &= ~std::uint64_t(0) << (64 - have_);  // drop the partial byte: read again next time
      return;
    }
    while (have_ <= 56) {  // the tail: bytes past the end read as zero
      const std::uint64_t b = p_ < end_ ? *p_++ : 0;
      buf_ |= b << (56 - have_);
      have_ += 8;
    }
  }
  const std::uint8_t* p_;
  const std::uint8_t* end_;
  std::uint64_t buf_ = 0;
  int have_ = 0;  // valid bits at the top of buf_
  std::size_t consumed_ = 0;
};

}  // namespace pupwave
