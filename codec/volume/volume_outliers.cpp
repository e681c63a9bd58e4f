#include "codec/volume/volume_outliers.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "codec/entropy/bit_model.h"
#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"
#include "codec/error.h"

namespace pupwave {
namespace {

// Corrections beyond this many bounds mean a broken reconstruction; refuse rather than overflow.
constexpr double kMaxCorrection = 9.0e15;

// A brick's corrections are range coded with adaptive models (fresh per brick): each index as
// the gap from the previous one, Elias-gamma style (its bit width in unary with models chosen by
// the previous gap's width, since outliers cluster where the coding error is large; the top
// mantissa bits with models, the rest raw), then the correction's sign and |k| - 1 in unary.
constexpr int kGapClasses = 12;        // contexts: the previous gap's bit width, capped
constexpr int kMaxWidth = 32;          // gaps + 1 are below 2^32 (a brick holds at most 256^3 voxels)
constexpr int kModelledMantissa = 2;   // mantissa bits below the leading one with models
constexpr int kMagnitudeModels = 8;    // unary bins of |k| - 1 before the raw escape
constexpr int kMaxMagnitudeBits = 53;  // |k| < kMaxCorrection < 2^53
constexpr int kRawChunk = 16;          // the range coder takes at most 16 raw bits at once

struct OutlierModels {
  std::array<BitModel, kMaxWidth> count{};
  std::array<std::array<BitModel, kMaxWidth>, kGapClasses> width{};
  std::array<std::array<BitModel, 1 << kModelledMantissa>, kMaxWidth + 1> mantissa{};
  std::array<BitModel, 3> sign{};  // by the previous correction's sign (none yet, +, -)
  std::array<BitModel, kMagnitudeModels> magnitude{};
  int previous_width = 0;
  int previous_sign = 0;
};

void put_raw(RangeEncoder& enc, std::uint64_t v, int n) {
  for (; n > kRawChunk; n -= kRawChunk)
    enc.encode_raw(std::uint32_t(v >> (n - kRawChunk)) & 0xffffu, kRawChunk);
  if (n > 0) enc.encode_raw(std::uint32_t(v) & ((1u << n) - 1u), n);
}

std::uint64_t get_raw(RangeDecoder& dec, int n) {
  std::uint64_t v = 0;
  for (; n > kRawChunk; n -= kRawChunk) v = (v << kRawChunk) | dec.decode_raw(kRawChunk);
  return n > 0 ? (v << n) | dec.decode_raw(n) : v;
}

// v in [1, 2^kMaxWidth): its bit width - 1 in unary with `bins`, the rest of the mantissa as
// `mantissa` says (the top bits with models when given).
void put_gamma(RangeEncoder& enc, std::span<BitModel, kMaxWidth> bins, std::uint64_t v,
               std::span<std::array<BitModel, 1 << kModelledMantissa>> mantissa = {}) {
  const int w = int(std::bit_width(v)) - 1;
  for (int j = 0; j < w; ++j) enc.encode(1, bins[std::size_t(j)]);
  if (w < kMaxWidth - 1) enc.encode(0, bins[std::size_t(w)]);
  const int modelled = mantissa.empty() ? 0 : std::min(w, kModelledMantissa);
  std::size_t node = 1;
  for (int b = w - 1; b >= w - modelled; --b) {
    const int bit = int((v >> b) & 1u);
    enc.encode(bit, mantissa[std::size_t(w)][node]);
    node = 2 * node + std::size_t(bit);
  }
  put_raw(enc, v, w - modelled);
}

std::uint64_t get_gamma(RangeDecoder& dec, std::span<BitModel, kMaxWidth> bins,
                        std::span<std::array<BitModel, 1 << kModelledMantissa>> mantissa = {}) {
  int w = 0;
  while (w < kMaxWidth - 1 && dec.decode(bins[std::size_t(w)]) != 0) ++w;
  const int modelled = mantissa.empty() ? 0 : std::min(w, kModelledMantissa);
  std::size_t node = 1;
  for (int b = 0; b < modelled; ++b)
    node = 2 * node + std::size_t(dec.decode(mantissa[std::size_t(w)][node]));
  const std::uint64_t top = node;  // the leading one and the modelled bits
  return (top << (w - modelled)) | get_raw(dec, w - modelled);
}

void put_gap(RangeEncoder& enc, OutlierModels& m, std::uint64_t gap) {
  const std::uint64_t v = gap + 1;
  put_gamma(enc, m.width[std::size_t(std::min(m.previous_width, kGapClasses - 1))], v, m.mantissa);
  m.previous_width = int(std::bit_width(v)) - 1;
}

std::uint64_t get_gap(RangeDecoder& dec, OutlierModels& m) {
  const std::uint64_t v =
      get_gamma(dec, m.width[std::size_t(std::min(m.previous_width, kGapClasses - 1))], m.mantissa);
  m.previous_width = int(std::bit_width(v)) - 1;
  return v - 1;
}

void put_correction(RangeEncoder& enc, OutlierModels& m, std::int64_t k) {
  const bool negative = k < 0;
  enc.encode(negative ? 1 : 0, m.sign[std::size_t(m.previous_sign)]);
  m.previous_sign = negative ? 2 : 1;
  const std::uint64_t a = (negative ? 0 - std::uint64_t(k) : std::uint64_t(k)) - 1;
  for (std::uint64_t j = 0; j < std::min<std::uint64_t>(a, kMagnitudeModels); ++j)
    enc.encode(1, m.magnitude[j]);
  if (a < kMagnitudeModels) {
    enc.encode(0, m.magnitude[a]);
    return;
  }
  const std::uint64_t rest = a - kMagnitudeModels;
  const int n = int(std::bit_width(rest));
  enc.encode_raw(std::uint32_t(n), 6);
  put_raw(enc, rest, n);
}

std::int64_t get_correction(RangeDecoder& dec, OutlierModels& m) {
  const bool negative = dec.decode(m.sign[std::size_t(m.previous_sign)]) != 0;
  m.previous_sign = negative ? 2 : 1;
  std::uint64_t a = 0;
  while (a < kMagnitudeModels && dec.decode(m.magnitude[a]) != 0) ++a;
  if (a == kMagnitudeModels) {
    const int n = int(dec.decode_raw(6));
    require_stream(n <= kMaxMagnitudeBits, "outlier correction too large");
    a += get_raw(dec, n);
    require_stream(a < (std::uint64_t(1) << kMaxMagnitudeBits), "outlier correction too large");
  }
  const auto magnitude = std::int64_t(a + 1);
  return negative ? -magnitude : magnitude;
}

// The correction of voxel i, whose stored reconstruction `value` is farther than bound from
// `original`: appends it to out and returns the corrected stored value.
double correct(std::size_t i, double original, double value, double bound, VoxelType type,
               std::vector<Outlier>& out) {
  const double residual = original - value;
  double k = std::round(residual / bound);
  if (!(std::abs(k) < kMaxCorrection)) throw EncodeError("error bound too small for the data range");
  double fixed = to_stored(value + k * bound, type);
  // The smallest |k| that holds the bound codes shorter (|k| - 1 in unary) than the nearest. Float
  // types only: the decoder adds k E to the unrounded reconstruction, which for u8/u16 differs from
  // `value` by up to 1/2, a margin only the nearest k leaves.
  const double smaller = k - (k > 0 ? 1.0 : -1.0);
  if (smaller != 0.0 && (type == VoxelType::f32 || type == VoxelType::f64)) {
    const double f = to_stored(value + smaller * bound, type);
    if (std::abs(original - f) <= bound) k = smaller, fixed = f;
  }
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
  RangeEncoder enc;
  OutlierModels m;
  put_gamma(enc, m.count, std::uint64_t(outliers.size()));
  std::uint32_t next = 0;
  for (const Outlier& o : outliers) {
    put_gap(enc, m, o.index - next);
    next = o.index + 1;
    put_correction(enc, m, o.k);
  }
  std::vector<std::uint8_t> bytes = enc.finish();
  // A short list can code to no bytes (the decoder reads zeros past the end), but an empty list
  // means no outliers: one zero byte decodes the same.
  if (bytes.empty()) bytes.push_back(0);
  return bytes;
}

std::vector<Outlier> decode_outliers(std::span<const std::uint8_t> bytes, std::size_t count) {
  if (bytes.empty()) return {};
  RangeDecoder dec(bytes);
  OutlierModels m;
  const std::uint64_t total = get_gamma(dec, m.count);
  require_stream(total >= 1 && total <= count, "outlier count");
  std::vector<Outlier> out(static_cast<std::size_t>(total));
  std::uint64_t next = 0;
  for (Outlier& o : out) {
    require_stream(next < count, "outlier index out of range");
    const std::uint64_t gap = get_gap(dec, m);
    require_stream(gap < count - next, "outlier index out of range");  // also rules out wrap-around
    next += gap;
    o.index = std::uint32_t(next++);
    o.k = get_correction(dec, m);
  }
  return out;
}

}  // namespace pupwave
