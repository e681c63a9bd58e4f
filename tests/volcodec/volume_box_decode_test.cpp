// decode_volume_box on a 61x45x37 corner of wmag91 (a real turbulence field, testimages/README.md;
// odd sizes, so edge bricks are partial) in 16^3 bricks: a box decoded at
// levels 0..2 equals the same box cropped out of the whole decode, bit for bit (lossy, lossless
// and sparse streams), only the bricks the box touches are decoded, and bad boxes are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <fstream>

#include "codec/error.h"
#include "codec/volume/volume_codec.h"
#include "pupwave/pupwave.h"
#include "pupwave/pupwave.hpp"

namespace pupwave {
namespace {

std::vector<float> read_wmag91() {
  std::vector<float> raw(91 * 91 * 91);
  std::ifstream in(PUPWAVE_TESTIMAGES_DIR "/wmag91.float", std::ios::binary);
  in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size() * 4));
  EXPECT_TRUE(in.good()) << "cannot read wmag91.float";
  return raw;
}

VolumeGrid wmag91_grid(VoxelType type) {
  const std::vector<float> raw = read_wmag91();
  const auto [lo, hi] = std::minmax_element(raw.begin(), raw.end());
  VolumeGrid g;
  g.name = "wmag";
  g.origin = {-5, 3, 10};  // odd, so the level placement is exercised
  g.volume = Volume({61, 45, 37}, type);
  for (std::size_t z = 0; z < 37; ++z)
    for (std::size_t y = 0; y < 45; ++y)
      for (std::size_t x = 0; x < 61; ++x) {
        const double v = raw[x + 91 * (y + 91 * z)];  // u16: the field quantized to 16 bits
        g.volume.at(x, y, z) = type == VoxelType::u16 ? std::round((v - *lo) / (*hi - *lo) * 65535.0) : v;
      }
  return g;
}

// That field as a sparse box: active above the median, inactive voxels of every state, and
// x >= 48 inactive background (whole bricks uncoded).
VolumeGrid sparse_wmag91() {
  VolumeGrid g = wmag91_grid(VoxelType::f32);
  Volume& v = g.volume;
  v.background = 0.5;
  std::vector<double> sorted = v.samples;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  v.active.assign(v.count(), 0);
  for (std::size_t z = 0; z < 37; ++z)
    for (std::size_t y = 0; y < 45; ++y)
      for (std::size_t x = 0; x < 61; ++x) {
        const std::size_t i = v.index(x, y, z);
        if (x >= 48)
          v.samples[i] = v.background;
        else if (v.samples[i] > median)
          v.active[i] = 1;
        else if (x % 7 == 0)
          v.samples[i] = -v.background;
        else if (x % 3 != 0)
          v.samples[i] = v.background;  // else: an inactive voxel with its own value
      }
  return g;
}

std::vector<std::uint8_t> encode(const VolumeGrid& g, VolumeRateMode mode, double target) {
  VolumeEncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.transform = mode == VolumeRateMode::lossless ? "cdf53" : "cdf97";
  o.brick = 16;  // 4 x 3 x 3 bricks
  o.levels = 2;
  return encode_volumes({g}, o).bytes;
}

// Boxes (full-resolution, half-open): inside one brick, straddling bricks, touching the far
// edges, one voxel, the whole grid.
const std::vector<VoxelBox> kBoxes = {{{3, 5, 1}, {14, 15, 9}},     {{10, 20, 5}, {40, 30, 33}},
                                      {{40, 0, 30}, {61, 45, 37}},  {{60, 44, 36}, {61, 45, 37}},
                                      {{33, 17, 17}, {34, 18, 18}}, {{0, 0, 0}, {61, 45, 37}}};

// The level-`level` voxels of `whole` whose footprint meets `box`, as decode_volume_box documents.
VolumeGrid crop(const VolumeGrid& whole, const VoxelBox& box, int level) {
  VolumeGrid out = whole;
  Extent first, dims;
  for (std::size_t a = 0; a < 3; ++a) {
    first[a] = box.lo[a] >> level;
    dims[a] = ((box.hi[a] - 1) >> level) + 1 - first[a];
    out.origin[a] += std::int64_t(first[a]);
  }
  out.volume = Volume(dims, whole.volume.type);
  out.volume.background = whole.volume.background;
  if (whole.volume.is_sparse()) out.volume.active.assign(out.volume.count(), 0);
  for (std::size_t z = 0; z < dims[2]; ++z)
    for (std::size_t y = 0; y < dims[1]; ++y)
      for (std::size_t x = 0; x < dims[0]; ++x) {
        const std::size_t i = whole.volume.index(first[0] + x, first[1] + y, first[2] + z);
        out.volume.at(x, y, z) = whole.volume.samples[i];
        if (whole.volume.is_sparse()) out.volume.active[out.volume.index(x, y, z)] = whole.volume.active[i];
      }
  return out;
}

void expect_box_is_crop(const std::vector<std::uint8_t>& bytes, const char* what) {
  for (int level = 0; level <= 2; ++level) {
    const VolumeGrid whole = decode_volumes(bytes, level)[0];
    for (const VoxelBox& box : kBoxes) {
      const VolumeGrid expected = crop(whole, box, level);
      const VolumeGrid got = decode_volume_box(bytes, "", box, level, default_executor(), DecodeLimits{});
      const std::string where =
          std::string(what) + " level " + std::to_string(level) + " box " + to_string(box);
      ASSERT_EQ(got.volume.dims, expected.volume.dims) << where;
      EXPECT_EQ(got.origin, expected.origin) << where;
      EXPECT_EQ(got.index_to_world, expected.index_to_world) << where;
      EXPECT_EQ(got.volume.active, expected.volume.active) << where;
      EXPECT_EQ(std::memcmp(got.volume.samples.data(), expected.volume.samples.data(),
                            expected.volume.count() * sizeof(double)),
                0)
          << where;
    }
  }
}

TEST(VolumeBoxDecode, LossyBoxEqualsCropOfWholeDecode) {
  const VolumeGrid g = wmag91_grid(VoxelType::f32);
  expect_box_is_crop(encode(g, VolumeRateMode::max_error, 1e-3), "max-error");
}

TEST(VolumeBoxDecode, LosslessBoxEqualsCropOfWholeDecode) {
  expect_box_is_crop(encode(wmag91_grid(VoxelType::u16), VolumeRateMode::lossless, 0.0), "lossless");
}

TEST(VolumeBoxDecode, SparseBoxEqualsCropOfWholeDecode) {
  expect_box_is_crop(encode(sparse_wmag91(), VolumeRateMode::max_error, 1e-3), "sparse");
}

// Counts the tasks run: decode_volume_box runs one per brick it decodes.
class CountingExecutor : public Executor {
 public:
  void run(std::size_t count, const std::function<void(std::size_t)>& task) const override {
    tasks += count;
    serial_executor().run(count, task);
  }
  unsigned concurrency() const override { return 1; }
  mutable std::atomic<std::size_t> tasks{0};
};

std::size_t bricks_decoded(const std::vector<std::uint8_t>& bytes, const VoxelBox& box, int level) {
  CountingExecutor ex;
  decode_volume_box(bytes, "wmag", box, level, ex, DecodeLimits{});
  return ex.tasks;
}

TEST(VolumeBoxDecode, DecodesOnlyTheBricksTheBoxTouches) {
  const auto bytes = encode(wmag91_grid(VoxelType::f32), VolumeRateMode::max_error, 1e-3);
  EXPECT_EQ(bricks_decoded(bytes, {{3, 5, 1}, {14, 15, 9}}, 0), 1u);
  EXPECT_EQ(bricks_decoded(bytes, {{3, 5, 1}, {14, 15, 9}}, 2), 1u);
  EXPECT_EQ(bricks_decoded(bytes, {{15, 5, 1}, {17, 15, 9}}, 0), 2u);     // straddles x = 16
  EXPECT_EQ(bricks_decoded(bytes, {{15, 15, 15}, {17, 17, 17}}, 1), 8u);  // a corner of 8
  EXPECT_EQ(bricks_decoded(bytes, {{60, 44, 36}, {61, 45, 37}}, 0), 1u);  // the last voxel
  EXPECT_EQ(bricks_decoded(bytes, {{0, 0, 0}, {61, 45, 37}}, 0), 36u);    // all of them
  // Sparse: bricks with no active voxel are not coded, so a box over x >= 48 decodes none.
  const auto sparse = encode(sparse_wmag91(), VolumeRateMode::max_error, 1e-3);
  EXPECT_EQ(bricks_decoded(sparse, {{48, 0, 0}, {61, 45, 37}}, 0), 0u);
}

// wmag91 as a sparse-native grid (as a .vdb gives): four blocks of it (8^3 and 16^3, on multiples
// of 8) with the states of sparse_wmag91's mask rule, an active tile and an inactive one.
VolumeGrid blocked_wmag91() {
  const std::vector<float> raw = read_wmag91();
  VolumeGrid g;
  g.name = "wmag";
  g.volume.type = VoxelType::f32;
  g.volume.background = 0.5;
  const auto block = [&](std::array<std::int64_t, 3> origin, std::size_t edge) {
    VolumeBlock b;
    b.origin = origin;
    b.volume = Volume({edge, edge, edge}, VoxelType::f32);
    b.volume.background = 0.5;
    b.volume.active.assign(b.volume.count(), 0);
    for (std::size_t z = 0; z < edge; ++z)
      for (std::size_t y = 0; y < edge; ++y)
        for (std::size_t x = 0; x < edge; ++x) {
          const std::size_t i = b.volume.index(x, y, z);
          const double v =
              raw[(x + std::size_t(origin[0] + 8)) + 91 * ((y + std::size_t(origin[1])) + 91 * z)];
          b.volume.samples[i] = v > 50.0 ? v : x % 7 == 0 ? -0.5 : x % 3 != 0 ? 0.5 : v;
          b.volume.active[i] = v > 50.0 ? 1 : 0;
        }
    g.blocks.push_back(std::move(b));
  };
  block({-8, 0, 16}, 16);
  block({8, 0, 16}, 8);
  block({24, 8, 24}, 16);
  block({56, 40, 16}, 8);
  g.tiles.push_back({{8, 8, 16}, 8, 1.5, true});
  g.tiles.push_back({{40, 0, 40}, 8, -0.5, false});
  g.origin = {-8, 0, 16};
  g.volume.dims = {72, 48, 32};  // the bounding box of the blocks and tiles
  return g;
}

TEST(VolumeBoxDecode, SparseNativeBoxEqualsCropOfItsDenseBoundingBox) {
  VolumeEncodeOptions o;
  o.target = 1e-2;
  o.brick = 8;
  o.levels = 2;
  const auto bytes = encode_volumes({blocked_wmag91()}, o).bytes;
  const std::vector<VoxelBox> boxes = {{{0, 0, 0}, {72, 48, 32}},
                                       {{3, 5, 1}, {30, 20, 9}},
                                       {{20, 10, 12}, {72, 48, 32}},
                                       {{40, 20, 0}, {48, 30, 8}}};
  for (int level = 0; level <= 2; ++level) {
    VolumeGrid whole = decode_volumes(bytes, level)[0];
    make_dense_box(whole, std::size_t(1) << 24);
    for (const VoxelBox& box : boxes) {
      const VolumeGrid expected = crop(whole, box, level);
      const VolumeGrid got = decode_volume_box(bytes, "", box, level, default_executor(), DecodeLimits{});
      const std::string where = "level " + std::to_string(level) + " box " + to_string(box);
      ASSERT_EQ(got.volume.dims, expected.volume.dims) << where;
      EXPECT_EQ(got.origin, expected.origin) << where;
      EXPECT_EQ(got.volume.active, expected.volume.active) << where;
      EXPECT_EQ(got.volume.samples, expected.volume.samples) << where;
    }
  }
  // Only the bricks of the blocks under the box: index space [32,40) x [12,20) x [24,32) meets
  // the 16^3 block at (24, 8, 24) in two of its eight 8^3 bricks and no other block.
  CountingExecutor ex;
  decode_volume_box(bytes, "", {{40, 12, 8}, {48, 20, 16}}, 0, ex, DecodeLimits{});
  EXPECT_EQ(ex.tasks, 2u);
}

TEST(VolumeBoxDecode, BadBoxesAreRefusedNamingTheBoxAndTheDims) {
  const auto bytes = encode(wmag91_grid(VoxelType::f32), VolumeRateMode::max_error, 1e-2);
  for (const VoxelBox& box : {VoxelBox{{5, 5, 5}, {5, 6, 6}}, VoxelBox{{9, 5, 5}, {4, 6, 6}},
                              VoxelBox{{0, 0, 0}, {61, 46, 37}}, VoxelBox{{61, 0, 0}, {65, 1, 1}}}) {
    try {
      decode_volume_box(bytes, "", box, 0, default_executor(), DecodeLimits{});
      ADD_FAILURE() << "box " << to_string(box) << " was decoded";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(to_string(box)), std::string::npos) << what;
      EXPECT_NE(what.find("61x45x37"), std::string::npos) << what;
    }
  }
  EXPECT_THROW(
      decode_volume_box(bytes, "other", {{0, 0, 0}, {1, 1, 1}}, 0, default_executor(), DecodeLimits{}),
      std::invalid_argument);
  EXPECT_THROW(decode_volume_box(bytes, "", {{0, 0, 0}, {1, 1, 1}}, 3, default_executor(), DecodeLimits{}),
               std::invalid_argument);
}

TEST(VolumeBoxDecode, DecodeLimitCountsTheBoxNotTheVolume) {
  const auto bytes = encode(wmag91_grid(VoxelType::f32), VolumeRateMode::max_error, 1e-2);
  const DecodeLimits limits{1000};
  EXPECT_THROW(decode_volumes(bytes, 0, default_executor(), limits), DecodeError);
  EXPECT_EQ(
      decode_volume_box(bytes, "", {{0, 0, 0}, {10, 10, 10}}, 0, default_executor(), limits).volume.count(),
      1000u);
  EXPECT_THROW(decode_volume_box(bytes, "", {{0, 0, 0}, {11, 10, 10}}, 0, default_executor(), limits),
               DecodeError);
}

// The bytes of the level-`level` voxels of a decoded grid whose footprint meets `box`.
std::vector<std::byte> crop_bytes(const api::Volume& whole, const VoxelBox& box, int level) {
  const std::size_t size = api::bytes_per_voxel(whole.type);
  std::vector<std::byte> out;
  for (std::size_t z = box.lo[2] >> level; z <= (box.hi[2] - 1) >> level; ++z)
    for (std::size_t y = box.lo[1] >> level; y <= (box.hi[1] - 1) >> level; ++y) {
      const auto row =
          whole.data.begin() +
          std::ptrdiff_t(size * ((box.lo[0] >> level) + whole.dims[0] * (y + whole.dims[1] * z)));
      out.insert(out.end(), row,
                 row + std::ptrdiff_t(size * (((box.hi[0] - 1) >> level) + 1 - (box.lo[0] >> level))));
    }
  return out;
}

// The C++ and C APIs give the crop of decompress_volume in the stored type, and refuse a bad box.
TEST(VolumeBoxDecode, CppAndCApisGiveTheCropOfTheWholeDecode) {
  const auto bytes = encode(wmag91_grid(VoxelType::f32), VolumeRateMode::max_error, 1e-3);
  const VoxelBox box{{10, 20, 5}, {40, 30, 33}};
  const api::VoxelBox api_box{{10, 20, 5}, {40, 30, 33}};
  for (int level : {0, 1}) {
    const api::Volume whole = api::decompress_volume(bytes, level)[0];
    const api::Volume part = api::decompress_volume_box(bytes, api_box, level);
    EXPECT_EQ(part.data, crop_bytes(whole, box, level)) << level;
    EXPECT_EQ(part.origin[0], whole.origin[0] + std::int64_t(box.lo[0] >> level)) << level;
    pupwave_decoded* d = nullptr;
    ASSERT_EQ(
        pupwave_decompress_volume_box(bytes.data(), bytes.size(), box.lo.data(), box.hi.data(), level, 1, &d),
        PUPWAVE_OK)
        << pupwave_last_error();
    const auto* data = static_cast<const std::byte*>(pupwave_decoded_data(d));
    EXPECT_EQ(std::vector<std::byte>(data, data + pupwave_decoded_size(d)), part.data) << level;
    EXPECT_EQ(pupwave_decoded_dim(d, 2), part.dims[2]) << level;
    pupwave_decoded_destroy(d);
  }
  // A sparse grid: values and mask, at full and half resolution.
  const auto sparse = encode(sparse_wmag91(), VolumeRateMode::max_error, 1e-3);
  for (int level : {0, 1}) {
    const api::Volume whole = api::decompress_volume(sparse, level)[0];
    const api::Volume part = api::decompress_volume_box(sparse, api_box, level);
    EXPECT_EQ(part.data, crop_bytes(whole, box, level)) << level;
    api::Volume mask = whole;  // the mask as one byte per voxel, cropped alike
    mask.type = api::VoxelType::u8;
    mask.data.assign(reinterpret_cast<const std::byte*>(whole.active.data()),
                     reinterpret_cast<const std::byte*>(whole.active.data() + whole.active.size()));
    const auto expected_mask = crop_bytes(mask, box, level);
    ASSERT_EQ(part.active.size(), expected_mask.size()) << level;
    EXPECT_EQ(std::memcmp(part.active.data(), expected_mask.data(), expected_mask.size()), 0) << level;
  }
  try {
    api::decompress_volume_box(bytes, {{0, 0, 0}, {62, 1, 1}});
    ADD_FAILURE() << "a box past x = 61 was decoded";
  } catch (const api::Error& e) {
    EXPECT_EQ(e.status(), api::Status::invalid_argument);
    EXPECT_NE(std::string(e.what()).find("61x45x37"), std::string::npos) << e.what();
  }
  const std::size_t lo[3] = {3, 3, 3}, hi[3] = {3, 9, 9};
  pupwave_decoded* d = nullptr;
  EXPECT_EQ(pupwave_decompress_volume_box(bytes.data(), bytes.size(), lo, hi, 0, 1, &d),
            PUPWAVE_ERROR_ARGUMENT);
  EXPECT_EQ(d, nullptr);
  EXPECT_NE(std::string(pupwave_last_error()).find("[3,3) x [3,9) x [3,9)"), std::string::npos)
      << pupwave_last_error();
}

}  // namespace
}  // namespace pupwave
