#include "codec/entropy/zstd_blocks.h"

#include <zstd.h>

#include <stdexcept>

#include "codec/error.h"

namespace pupwave {
namespace {

constexpr int kZstdLevel = 9;
constexpr std::size_t kMaxVarintBytes = 5;

std::uint32_t zigzag(std::int32_t v) { return (std::uint32_t(v) << 1) ^ std::uint32_t(v >> 31); }
std::int32_t unzigzag(std::uint32_t v) { return std::int32_t(v >> 1) ^ -std::int32_t(v & 1u); }

}  // namespace

std::vector<std::uint8_t> zstd_encode_block(std::span<const float> magnitude,
                                            std::span<const std::uint8_t> negative) {
  std::vector<std::uint8_t> raw;
  raw.reserve(magnitude.size() * 2);
  bool any = false;
  for (std::size_t i = 0; i < magnitude.size(); ++i) {
    if (!(magnitude[i] < 2147483648.0f)) throw std::invalid_argument("quantization index too large");
    const auto q = std::int32_t(magnitude[i]);
    any = any || q != 0;
    std::uint32_t z = zigzag(negative[i] ? -q : q);
    while (z >= 0x80u) {
      raw.push_back(std::uint8_t(z | 0x80u));
      z >>= 7;
    }
    raw.push_back(std::uint8_t(z));
  }
  if (!any) return {};
  std::vector<std::uint8_t> out(ZSTD_compressBound(raw.size()));
  const std::size_t n = ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), kZstdLevel);
  if (ZSTD_isError(n)) throw EncodeError(std::string("zstd: ") + ZSTD_getErrorName(n));
  out.resize(n);
  return out;
}

std::vector<std::int32_t> zstd_decode_block(std::span<const std::uint8_t> codeword, std::size_t count) {
  std::vector<std::int32_t> values(count, 0);
  if (codeword.empty()) return values;
  const unsigned long long content = ZSTD_getFrameContentSize(codeword.data(), codeword.size());
  require_stream(content != ZSTD_CONTENTSIZE_ERROR && content != ZSTD_CONTENTSIZE_UNKNOWN &&
                     content <= count * kMaxVarintBytes,
                 "zstd code-block size");
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(content));
  const std::size_t n = ZSTD_decompress(raw.data(), raw.size(), codeword.data(), codeword.size());
  require_stream(!ZSTD_isError(n) && n == raw.size(), "zstd code-block payload");
  std::size_t pos = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t z = 0;
    for (int shift = 0;; shift += 7) {
      require_stream(pos < raw.size() && shift <= 28, "zstd code-block indices");
      const std::uint8_t b = raw[pos++];
      z |= std::uint32_t(b & 0x7Fu) << shift;
      if (!(b & 0x80u)) break;
    }
    values[i] = unzigzag(z);
  }
  require_stream(pos == raw.size(), "zstd code-block has trailing bytes");
  return values;
}

}  // namespace pupwave
