#pragma once
// Little-endian serialization helpers. ByteReader checks every read against the end of its
// buffer and throws DecodeError, so container parsing never reads past the input.

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "codec/error.h"

namespace pupwave {

// Appends little-endian fields to a growing byte vector.
class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void u8(std::uint32_t v) { out_.push_back(std::uint8_t(v)); }
  void u16(std::uint32_t v) { put(v, 2); }
  void u32(std::uint32_t v) { put(v, 4); }
  void f32(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, 4);
    u32(bits);
  }
  void bytes(std::span<const std::uint8_t> b) { out_.insert(out_.end(), b.begin(), b.end()); }
  void str16(const std::string& s) {  // u16 length then the characters
    u16(std::uint32_t(s.size()));
    out_.insert(out_.end(), s.begin(), s.end());
  }

 private:
  void put(std::uint32_t v, int n) {
    for (int i = 0; i < n; ++i) out_.push_back(std::uint8_t(v >> (8 * i)));
  }
  std::vector<std::uint8_t>& out_;
};

// Reads little-endian fields from a byte span; every read is bounds checked.
class ByteReader {
 public:
  // `what` names the structure in error messages (a string literal: it is not copied).
  ByteReader(std::span<const std::uint8_t> in, const char* what) : in_(in), what_(what) {}
  std::uint32_t u8() { return get(1); }
  std::uint32_t u16() { return get(2); }
  std::uint32_t u32() { return get(4); }
  float f32() {
    const std::uint32_t bits = u32();
    float v;
    std::memcpy(&v, &bits, 4);
    return v;
  }
  std::span<const std::uint8_t> bytes(std::size_t n) {
    need(n);
    auto s = in_.subspan(pos_, n);
    pos_ += n;
    return s;
  }
  std::string str16(std::size_t max_len) {
    const std::size_t n = u16();
    require_stream(n <= max_len, [&] { return std::string(what_) + ": string too long"; });
    auto s = bytes(n);
    return std::string(s.begin(), s.end());
  }
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return in_.size() - pos_; }

 private:
  void need(std::size_t n) const {
    require_stream(n <= in_.size() - pos_, [&] { return std::string(what_) + " truncated"; });
  }
  std::uint32_t get(int n) {
    need(std::size_t(n));
    std::uint32_t v = 0;
    for (int i = 0; i < n; ++i) v |= std::uint32_t(in_[pos_ + i]) << (8 * i);
    pos_ += std::size_t(n);
    return v;
  }
  std::span<const std::uint8_t> in_;
  const char* what_;
  std::size_t pos_ = 0;
};

}  // namespace pupwave
