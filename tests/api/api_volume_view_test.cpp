// The public API's volume views: a strided view (a sub-box of a larger u16 array, and the same
// voxels z fastest) gives exactly the stream of the contiguous array, and decompress_volume
// returns the voxels in their own type; sparse bricks of u8 keep their type too.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "pupwave/pupwave.hpp"

namespace {

namespace api = pupwave::api;

constexpr std::size_t kX = 37, kY = 29, kZ = 19;

std::uint16_t value(std::size_t x, std::size_t y, std::size_t z) {
  return std::uint16_t((x * 97 + y * 31 + z * 7 + (x * y) % 13) % 3000);
}

std::vector<std::uint16_t> dense() {
  std::vector<std::uint16_t> v(kX * kY * kZ);
  for (std::size_t z = 0; z < kZ; ++z)
    for (std::size_t y = 0; y < kY; ++y)
      for (std::size_t x = 0; x < kX; ++x) v[x + kX * (y + kY * z)] = value(x, y, z);
  return v;
}

api::VolumeOptions lossless() {
  api::VolumeOptions o;
  o.rate = api::VolumeRate::lossless;
  o.brick = 16;
  o.threads = 1;
  return o;
}

TEST(ApiVolumeView, StridedU16ViewsGiveTheContiguousStream) {
  const auto voxels = dense();
  const auto reference = api::compress_volume({voxels.data(), {kX, kY, kZ}, api::VoxelType::u16}, lossless());

  const std::size_t bx = kX + 5, by = kY + 3, bz = kZ + 2;  // a larger array holding the box at (2, 1, 1)
  std::vector<std::uint16_t> big(bx * by * bz, 60000);
  for (std::size_t z = 0; z < kZ; ++z)
    for (std::size_t y = 0; y < kY; ++y)
      for (std::size_t x = 0; x < kX; ++x) big[(x + 2) + bx * ((y + 1) + by * (z + 1))] = value(x, y, z);
  api::VolumeView sub{big.data() + (2 + bx * (1 + by * 1)), {kX, kY, kZ}, api::VoxelType::u16};
  sub.strides = {1, std::ptrdiff_t(bx), std::ptrdiff_t(bx * by)};
  EXPECT_EQ(api::compress_volume(sub, lossless()), reference);

  std::vector<std::uint16_t> zfast(voxels.size());
  for (std::size_t z = 0; z < kZ; ++z)
    for (std::size_t y = 0; y < kY; ++y)
      for (std::size_t x = 0; x < kX; ++x) zfast[z + kZ * (y + kY * x)] = value(x, y, z);
  api::VolumeView transposed{zfast.data(), {kX, kY, kZ}, api::VoxelType::u16};
  transposed.strides = {std::ptrdiff_t(kZ * kY), std::ptrdiff_t(kZ), 1};
  EXPECT_EQ(api::compress_volume(transposed, lossless()), reference);

  const auto grids = api::decompress_volume(reference);
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_EQ(grids[0].type, api::VoxelType::u16);
  ASSERT_EQ(grids[0].data.size(), voxels.size() * 2);
  EXPECT_EQ(std::memcmp(grids[0].data.data(), voxels.data(), grids[0].data.size()), 0);
}

TEST(ApiVolumeView, SparseU8BricksRoundTripInTheirType) {
  std::vector<std::uint8_t> a(8 * 8 * 8), b(8 * 8 * 8), mask(8 * 8 * 8);
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i] = std::uint8_t(i % 251);
    b[i] = std::uint8_t(255 - i % 200);
    mask[i] = (i % 3) != 0;
  }
  const api::BrickView bricks[] = {{{0, 0, 0}, {a.data(), {8, 8, 8}, api::VoxelType::u8}, nullptr},
                                   {{16, 0, 0}, {b.data(), {8, 8, 8}, api::VoxelType::u8}, mask.data()}};
  const auto grids = api::decompress_volume(api::compress_sparse_volume(bricks, 7.0, lossless()));
  ASSERT_EQ(grids.size(), 1u);
  const api::Volume& v = grids[0];
  EXPECT_EQ(v.type, api::VoxelType::u8);
  ASSERT_EQ(v.dims, (std::array<std::size_t, 3>{24, 8, 8}));
  ASSERT_EQ(v.active.size(), 24u * 8 * 8);
  for (std::size_t z = 0; z < 8; ++z)
    for (std::size_t y = 0; y < 8; ++y)
      for (std::size_t x = 0; x < 24; ++x) {
        const std::size_t i = x + 24 * (y + 8 * z), j = (x % 8) + 8 * (y + 8 * z);
        const auto got = std::uint8_t(v.data[i]);
        if (x < 8) {
          EXPECT_EQ(got, a[j]);
          EXPECT_EQ(v.active[i], 1);
        } else if (x >= 16) {
          EXPECT_EQ(v.active[i], mask[j]);
          EXPECT_EQ(got, mask[j] ? b[j] : 7);
        } else {
          EXPECT_EQ(v.active[i], 0);
          EXPECT_EQ(got, 7);
        }
      }
}

}  // namespace
