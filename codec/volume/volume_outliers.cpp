#include "codec/volume/volume_outliers.h"

#include <zstd.h>

#include <algorithm>
#include <cmath>

#include "codec/error.h"

namespace pupwave {
namespace {

constexpr int kZstdLevel = 9;
constexpr std::size_t kMaxVarintBytes = 10;
// Corrections beyond this many bounds mean a broken reconstruction; refuse rather than overflow.
constexpr double kMaxCorrection = 9.0e15;

void put_varint(std::vector<std::uint8_t>& out, std::uint64_t v) {
  while (v >= 0x80u) {
    out.push_back(std::uint8_t(v | 0x80u));
    v >>= 7;
  }
  out.push_back(std::uint8_t(v));
}

std::uint64_t get_varint(std::span<const std::uint8_t> in, std::size_t& pos) {
  std::uint64_t v = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    require_stream(pos < in.size(), "outlier list truncated");
    const std::uint8_t b = in[pos++];
    v |= std::uint64_t(b & 0x7fu) << shift;
    if ((b & 0x80u) == 0) return v;
  }
  throw DecodeError("outlier list: bad varint");
}

std::uint64_t zigzag(std::int64_t v) { return (std::uint64_t(v) << 1) ^ std::uint64_t(v >> 63); }
std::int64_t unzigzag(std::uint64_t v) { return std::int64_t(v >> 1) ^ -std::int64_t(v & 1u); }

// The correction of voxel i, whose stored reconstruction `value` is farther than bound from
// `original`: appends it to out and returns the corrected stored value.
double correct(std::size_t i, double original, double value, double bound, VoxelType type,
               std::vector<Outlier>& out) {
  const double residual = original - value;
  const double k = std::round(residual / bound);
  if (!(std::abs(k) < kMaxCorrection)) throw EncodeError("error bound too small for the data range");
  const double fixed = to_stored(value + k * bound, type);
  if (!(std::abs(original - fixed) <= bound))
    throw EncodeError("error bound below the precision of the stored type");
  out.push_back({std::uint32_t(i), std::int64_t(k)});
  return fixed;
}

// kStore: also write every stored value; kMeasure: also sum the error (its serial chain of
// additions costs ~8% of a u16 encode when run for every candidate step, so only on request).
template <VoxelType kType, bool kStore, bool kMeasure, class S>
void store_and_find(std::span<const S> original, std::span<const float> requantized, std::span<double> stored,
                    std::span<const std::uint8_t> check, double bound, std::vector<Outlier>& out,
                    StoredError* error) {
  double max_error = 0.0, sse = 0.0;  // locals: through `error` every voxel would store both
  for (std::size_t i = 0; i < original.size(); ++i) {
    double value = to_stored(double(requantized[i]), kType);
    if (!check.empty() && check[i] == 0) {
      if constexpr (kStore) stored[i] = value;
      continue;
    }
    const double o = double(original[i]);
    if (!(std::abs(o - value) <= bound)) value = correct(i, o, value, bound, kType, out);
    if constexpr (kStore) stored[i] = value;
    if constexpr (kMeasure) {
      const double e = std::abs(o - value);
      max_error = std::max(max_error, e);
      sse += e * e;
    }
  }
  if constexpr (kMeasure) *error = {max_error, sse};
}

template <VoxelType kType, class S>
void store_and_find(std::span<const S> original, std::span<const float> requantized, std::span<double> stored,
                    std::span<const std::uint8_t> check, double bound, std::vector<Outlier>& out,
                    StoredError* error) {
  if (!stored.empty() && error != nullptr)
    store_and_find<kType, true, true>(original, requantized, stored, check, bound, out, error);
  else if (!stored.empty())
    store_and_find<kType, true, false>(original, requantized, stored, check, bound, out, error);
  else if (error != nullptr)
    store_and_find<kType, false, true>(original, requantized, stored, check, bound, out, error);
  else
    store_and_find<kType, false, false>(original, requantized, stored, check, bound, out, error);
}

}  // namespace

template <class S>
void store_and_find_outliers(std::span<const S> original, std::span<const float> requantized,
                             std::span<double> stored, std::span<const std::uint8_t> check, double bound,
                             VoxelType type, std::vector<Outlier>& out, StoredError* error) {
  out.clear();
  switch (type) {  // one loop per type, so that to_stored's switch leaves the loop
    case VoxelType::u8:
      return store_and_find<VoxelType::u8>(original, requantized, stored, check, bound, out, error);
    case VoxelType::u16:
      return store_and_find<VoxelType::u16>(original, requantized, stored, check, bound, out, error);
    case VoxelType::f32:
      return store_and_find<VoxelType::f32>(original, requantized, stored, check, bound, out, error);
    case VoxelType::f64:
      return store_and_find<VoxelType::f64>(original, requantized, stored, check, bound, out, error);
  }
}

template void store_and_find_outliers(std::span<const std::uint8_t>, std::span<const float>,
                                      std::span<double>, std::span<const std::uint8_t>, double, VoxelType,
                                      std::vector<Outlier>&, StoredError*);
template void store_and_find_outliers(std::span<const std::uint16_t>, std::span<const float>,
                                      std::span<double>, std::span<const std::uint8_t>, double, VoxelType,
                                      std::vector<Outlier>&, StoredError*);
template void store_and_find_outliers(std::span<const float>, std::span<const float>, std::span<double>,
                                      std::span<const std::uint8_t>, double, VoxelType, std::vector<Outlier>&,
                                      StoredError*);
template void store_and_find_outliers(std::span<const double>, std::span<const float>, std::span<double>,
                                      std::span<const std::uint8_t>, double, VoxelType, std::vector<Outlier>&,
                                      StoredError*);

std::vector<Outlier> find_outliers(std::span<const double> original, std::span<double> reconstruction,
                                   std::span<const std::uint8_t> check, double bound, VoxelType type) {
  std::vector<Outlier> out;
  for (std::size_t i = 0; i < original.size(); ++i) {
    if (!check.empty() && check[i] == 0) continue;
    if (std::abs(original[i] - reconstruction[i]) <= bound) continue;
    reconstruction[i] = correct(i, original[i], reconstruction[i], bound, type, out);
  }
  return out;
}

void apply_outliers(std::span<double> reconstruction, std::span<const Outlier> outliers, double bound,
                    VoxelType type) {
  for (const Outlier& o : outliers)
    reconstruction[o.index] = to_stored(reconstruction[o.index] + double(o.k) * bound, type);
}

std::vector<std::uint8_t> encode_outliers(std::span<const Outlier> outliers) {
  if (outliers.empty()) return {};
  std::vector<std::uint8_t> raw;
  put_varint(raw, outliers.size());
  std::uint32_t next = 0;
  for (const Outlier& o : outliers) {
    put_varint(raw, o.index - next);
    next = o.index + 1;
  }
  for (const Outlier& o : outliers) put_varint(raw, zigzag(o.k));
  std::vector<std::uint8_t> out(ZSTD_compressBound(raw.size()));
  const std::size_t n = ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), kZstdLevel);
  if (ZSTD_isError(n)) throw EncodeError(std::string("zstd: ") + ZSTD_getErrorName(n));
  out.resize(n);
  return out;
}

std::vector<Outlier> decode_outliers(std::span<const std::uint8_t> bytes, std::size_t count) {
  if (bytes.empty()) return {};
  const unsigned long long content = ZSTD_getFrameContentSize(bytes.data(), bytes.size());
  require_stream(content != ZSTD_CONTENTSIZE_ERROR && content != ZSTD_CONTENTSIZE_UNKNOWN &&
                     content <= (2 * count + 1) * kMaxVarintBytes,
                 "outlier list size");
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(content));
  const std::size_t n = ZSTD_decompress(raw.data(), raw.size(), bytes.data(), bytes.size());
  require_stream(!ZSTD_isError(n) && n == raw.size(), "corrupt outlier list");
  std::size_t pos = 0;
  const std::uint64_t total = get_varint(raw, pos);
  require_stream(total >= 1 && total <= count, "outlier count");
  std::vector<Outlier> out(static_cast<std::size_t>(total));
  std::uint64_t next = 0;
  for (Outlier& o : out) {
    require_stream(next < count, "outlier index out of range");
    const std::uint64_t gap = get_varint(raw, pos);
    require_stream(gap < count - next, "outlier index out of range");  // also rules out wrap-around
    next += gap;
    o.index = std::uint32_t(next++);
  }
  for (Outlier& o : out) {
    o.k = unzigzag(get_varint(raw, pos));
    require_stream(o.k != 0, "outlier correction");
  }
  require_stream(pos == raw.size(), "trailing bytes in outlier list");
  return out;
}

}  // namespace pupwave
