// Missing values of dense volumes (codec/volume/volume_missing.h): NaN, infinities and a fill
// value come back bit for bit in every rate mode, at coarse levels and in box decodes, and the
// other voxels keep the bound of the valid voxels' range and cost what they cost in a smoothly
// filled field; a corrupted mask is a clear error.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <span>

#include "codec/error.h"
#include "codec/format/chunks.h"
#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"
#include "pupwave/pupwave.hpp"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

constexpr double kFill = -999.0;

std::uint32_t bits(double v) { return std::bit_cast<std::uint32_t>(float(v)); }

bool missing(double v) { return !std::isfinite(v) || v == kFill; }

// wmag91 with a land mask: every voxel below 8 (the calm low ground, about a fifth) is NaN, a
// corner block holds the fill value, and a few voxels hold infinities and a NaN with a payload.
Volume masked_wmag91() {
  Volume v = test::read_wmag91();
  for (double& s : v.samples)
    if (s < 8.0) s = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t z = 0; z < 20; ++z)
    for (std::size_t y = 0; y < 24; ++y)
      for (std::size_t x = 60; x < 91; ++x) v.at(x, y, z) = kFill;
  v.at(45, 45, 45) = std::numeric_limits<double>::infinity();
  v.at(46, 45, 45) = -std::numeric_limits<double>::infinity();
  v.at(47, 45, 45) = double(std::bit_cast<float>(0x7fc12345u));  // a quiet NaN with a payload
  return v;
}

double valid_range(const Volume& v) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double s : v.samples)
    if (!missing(s)) lo = std::min(lo, s), hi = std::max(hi, s);
  return hi - lo;
}

VolumeEncodeResult encode(const Volume& v, VolumeRateMode mode, double target) {
  VolumeGrid g;
  g.name = "masked";
  g.volume = v;
  VolumeEncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.transform = mode == VolumeRateMode::max_error ? kMaxErrorVolumeTransform : "cdf97";
  o.fill_value = kFill;
  return encode_volumes({g}, o);
}

// Missing voxels bit for bit, the rest within `bound`; returns the largest error of the rest.
double check_decode(const Volume& original, const Volume& decoded) {
  EXPECT_FALSE(decoded.is_sparse());
  double worst = 0.0;
  for (std::size_t i = 0; i < original.count(); ++i) {
    if (missing(original.samples[i]))
      EXPECT_EQ(bits(decoded.samples[i]), bits(original.samples[i])) << i;
    else
      worst = std::max(worst, std::abs(decoded.samples[i] - original.samples[i]));
  }
  return worst;
}

TEST(VolumeMissing, LandMaskedWmag91KeepsMissingVoxelsExactAndTheRestWithinTheBound) {
  const Volume v = masked_wmag91();
  const double bound = 1e-3 * valid_range(v);
  const auto r = encode(v, VolumeRateMode::max_error, bound);
  EXPECT_TRUE(r.target_met);
  EXPECT_LE(r.max_error, bound);
  const auto grids = decode_volumes(r.bytes);
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_LE(check_decode(v, grids[0].volume), bound);
  EXPECT_NE(describe_volume_stream(r.bytes).find("missing voxels"), std::string::npos);
}

// The field with its missing voxels replaced by a smooth fill (the mean of the valid voxels,
// then Jacobi sweeps of the 6-neighbour mean over the missing ones): what a user without
// missing values would code, every voxel then valid.
Volume smoothly_filled(const Volume& masked) {
  Volume v = masked;
  double sum = 0.0;
  std::size_t n = 0;
  for (double s : v.samples)
    if (!missing(s)) sum += s, ++n;
  for (double& s : v.samples)
    if (missing(s)) s = sum / double(n);
  const Extent& d = v.dims;
  for (int sweep = 0; sweep < 40; ++sweep) {
    const std::vector<double> before = v.samples;
    for (std::size_t z = 0; z < d[2]; ++z)
      for (std::size_t y = 0; y < d[1]; ++y)
        for (std::size_t x = 0; x < d[0]; ++x) {
          if (!missing(masked.at(x, y, z))) continue;
          double t = 0.0;
          int k = 0;
          if (x > 0) t += before[v.index(x - 1, y, z)], ++k;
          if (x + 1 < d[0]) t += before[v.index(x + 1, y, z)], ++k;
          if (y > 0) t += before[v.index(x, y - 1, z)], ++k;
          if (y + 1 < d[1]) t += before[v.index(x, y + 1, z)], ++k;
          if (z > 0) t += before[v.index(x, y, z - 1)], ++k;
          if (z + 1 < d[2]) t += before[v.index(x, y, z + 1)], ++k;
          v.at(x, y, z) = double(float(t / k));
        }
  }
  return v;
}

// Bytes of a stream's MASK chunks (payload and framing).
std::size_t mask_bytes(std::span<const std::uint8_t> stream) {
  ChunkReader chunks(stream, "PUPV", kVolumeStreamVersion, "volume stream");
  std::size_t n = 0;
  while (!chunks.at_end()) {
    const Chunk c = chunks.next();
    if (c.is("MASK")) n += c.payload.size() + 12;
  }
  return n;
}

// The valid voxels cost what they cost in the same field with the missing ones smoothly filled
// and coded as data: the fill keeps missing voxels from pulling the transform. The mask itself
// (zstd over one state byte a voxel) comes on top: about 60 KB, 15% of this stream, for a mask
// as ragged as a threshold of the field (bench/results/volumes.md).
TEST(VolumeMissing, ValidVoxelsCostWhatTheyCostInASmoothlyFilledField) {
  const Volume masked = masked_wmag91();
  const double bound = 1e-3 * valid_range(masked);
  const auto with_mask = encode(masked, VolumeRateMode::max_error, bound);
  const auto filled = encode(smoothly_filled(masked), VolumeRateMode::max_error, bound);
  const std::size_t mask = mask_bytes(with_mask.bytes);
  std::printf("wmag91 at E %.4g: %zu bytes with the land mask (%zu of them the mask), %zu smoothly filled\n",
              bound, with_mask.size, mask, filled.size);
  EXPECT_LT(double(with_mask.size - mask), 1.05 * double(filled.size));
  EXPECT_LT(mask, with_mask.size / 5);
}

TEST(VolumeMissing, EveryRateModeKeepsMissingVoxelsAndMeasuresOnlyValidOnes) {
  const Volume v = masked_wmag91();
  const std::pair<VolumeRateMode, double> modes[] = {
      {VolumeRateMode::psnr, 60.0}, {VolumeRateMode::bpv, 2.0}, {VolumeRateMode::step, 0.5}};
  for (const auto& [mode, target] : modes) {
    const auto r = encode(v, mode, target);
    EXPECT_TRUE(std::isfinite(r.psnr)) << int(mode);
    const auto grids = decode_volumes(r.bytes);
    check_decode(v, grids[0].volume);
  }
}

// Through the public API: the relative bound is of the valid voxels' range.
TEST(VolumeMissing, RelativeBoundIsOfTheValidRange) {
  const Volume v = masked_wmag91();
  std::vector<float> data(v.samples.begin(), v.samples.end());
  api::VolumeOptions o;
  o.rate = api::VolumeRate::max_error_rel;
  o.target = 1e-3;
  o.fill_value = kFill;
  const auto stream = api::compress_volume({data.data(), {91, 91, 91}, api::VoxelType::f32}, o);
  const auto grids = decode_volumes(stream);
  const double worst = check_decode(v, grids[0].volume);
  EXPECT_LE(worst, 1e-3 * valid_range(v));
  EXPECT_GT(worst, 0.5e-3 * valid_range(v));  // the bound is the valid range's, not 0 or NaN's
}

// At a coarse level a voxel is missing where all its children are (their mean: NaN with any
// NaN); box decodes are crops of the whole decode, bit for bit.
TEST(VolumeMissing, CoarseLevelsAndBoxDecodesAgreeWithTheWholeDecode) {
  const Volume v = masked_wmag91();
  const auto r = encode(v, VolumeRateMode::max_error, 0.5);
  for (int level : {0, 1}) {
    const Volume whole = decode_volumes(r.bytes, level)[0].volume;
    ASSERT_FALSE(whole.is_sparse());
    const VoxelBox box{{30, 10, 0}, {91, 50, 33}};
    const VolumeGrid crop = decode_volume_box(r.bytes, "", box, level, default_executor(), DecodeLimits{});
    ASSERT_FALSE(crop.volume.is_sparse());
    const Extent first{box.lo[0] >> level, box.lo[1] >> level, box.lo[2] >> level};
    for (std::size_t z = 0; z < crop.volume.dims[2]; ++z)
      for (std::size_t y = 0; y < crop.volume.dims[1]; ++y)
        for (std::size_t x = 0; x < crop.volume.dims[0]; ++x)
          ASSERT_EQ(std::bit_cast<std::uint64_t>(crop.volume.at(x, y, z)),
                    std::bit_cast<std::uint64_t>(whole.at(first[0] + x, first[1] + y, first[2] + z)))
              << level << " " << x << " " << y << " " << z;
  }
  // The fill block [60,91) x [0,24) x [0,20) holds only fill values: so do its coarse voxels.
  const Volume coarse = decode_volumes(r.bytes, 1)[0].volume;
  EXPECT_EQ(coarse.at(35, 5, 5), kFill);
}

TEST(VolumeMissing, EntirelyMissingVolumeRoundTrips) {
  Volume v({9, 8, 7}, VoxelType::f32);
  for (std::size_t i = 0; i < v.count(); ++i)
    v.samples[i] = i % 3 == 0 ? kFill : std::numeric_limits<double>::quiet_NaN();
  const auto r = encode(v, VolumeRateMode::max_error, 0.01);
  const Volume d = decode_volumes(r.bytes)[0].volume;
  check_decode(v, d);
}

TEST(VolumeMissing, FillValueMustBeFiniteAndSparseGridsStillRefuseNan) {
  VolumeGrid g;
  g.volume = test::smooth_volume({9, 8, 7}, VoxelType::f32, 1.0);
  VolumeEncodeOptions o;
  o.fill_value = std::numeric_limits<double>::infinity();
  EXPECT_THROW(encode_volumes({g}, o), std::invalid_argument);
  g.volume = test::sphere_level_set({16, 16, 16}, 5.0, 2.0, 0.3);
  g.volume.samples[g.volume.index(8, 8, 8)] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(encode_volumes({g}, VolumeEncodeOptions{}), EncodeError);
}

// A corrupted MASK chunk (its CRC made to match) is a DecodeError, never a crash.
TEST(VolumeMissing, CorruptedMaskIsADecodeError) {
  Volume v = test::smooth_volume({20, 20, 20}, VoxelType::f32, 10.0);
  for (std::size_t i = 0; i < v.count(); i += 7) v.samples[i] = std::numeric_limits<double>::quiet_NaN();
  const auto r = encode(v, VolumeRateMode::max_error, 0.01);
  ChunkReader chunks(r.bytes, "PUPV", 7, "volume stream");
  std::vector<std::uint8_t> head(r.bytes.begin(), r.bytes.begin() + 5);
  std::vector<std::vector<std::uint8_t>> variants;
  std::vector<Chunk> all;
  while (!chunks.at_end()) all.push_back(chunks.next());
  std::size_t tried = 0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (!all[k].is("MASK")) continue;
    for (std::size_t at = 4; at < all[k].payload.size(); at += 3) {
      std::vector<std::uint8_t> out = head;
      for (std::size_t j = 0; j < all.size(); ++j) {
        std::vector<std::uint8_t> p(all[j].payload.begin(), all[j].payload.end());
        if (j == k) p[at] ^= 0x5a;
        const char tag[5] = {all[j].tag[0], all[j].tag[1], all[j].tag[2], all[j].tag[3], 0};
        write_chunk(out, tag, p);
      }
      ++tried;
      try {
        const auto grids = decode_volumes(out);
        ASSERT_EQ(grids.size(), 1u);  // a flip the mask survives must still give a whole volume
        EXPECT_EQ(grids[0].volume.samples.size(), v.count());
      } catch (const DecodeError& e) {
        EXPECT_NE(std::string(e.what()).find("volume"), std::string::npos) << e.what();
      }
    }
  }
  EXPECT_GT(tried, 3u);
}

}  // namespace
}  // namespace pupwave
