// Typed strided views as the volume encoder's input and typed outputs of the decoder: a u8 or
// u16 sub-box of a larger array (non-contiguous, and in a transposed layout) gives exactly the
// stream of the contiguous copy and decodes back to it; decode_volume_into fills a buffer of
// the stored type with the values decode_volumes gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_view.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

VolumeEncodeOptions options(VolumeRateMode mode, double target, const char* spec) {
  VolumeEncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.transform = spec;
  o.brick = 16;
  o.block = 16;
  o.executor = &serial_executor();
  return o;
}

std::vector<std::uint8_t> encode_copy(const Volume& v, const VolumeEncodeOptions& o) {
  VolumeGrid g;
  g.name = "view";
  g.volume = v;
  return encode_volumes({g}, o).bytes;
}

std::vector<std::uint8_t> encode_view(const VolumeView& view, const VolumeEncodeOptions& o) {
  const VolumeView views[] = {view};
  return encode_volumes({describe_view(view, "view")}, views, o).bytes;
}

template <class T>
constexpr VoxelType storage_of() {
  if constexpr (std::is_same_v<T, std::uint8_t>) return VoxelType::u8;
  if constexpr (std::is_same_v<T, std::uint16_t>) return VoxelType::u16;
  if constexpr (std::is_same_v<T, float>) return VoxelType::f32;
  return VoxelType::f64;
}

// `inner` embedded at `at` in a larger array of T (x fastest, padding filled with junk), and
// the strided view of the embedded box.
template <class T>
struct Embedded {
  std::vector<T> big;
  VolumeView view;
};

template <class T>
Embedded<T> embed(const Volume& inner, const Extent& big, const Extent& at) {
  Embedded<T> e;
  e.big.assign(big[0] * big[1] * big[2], T(99));
  for (std::size_t z = 0; z < inner.dims[2]; ++z)
    for (std::size_t y = 0; y < inner.dims[1]; ++y)
      for (std::size_t x = 0; x < inner.dims[0]; ++x)
        e.big[(at[0] + x) + big[0] * ((at[1] + y) + big[1] * (at[2] + z))] = T(inner.at(x, y, z));
  e.view = sub_view(contiguous_view(e.big.data(), big, storage_of<T>()), at, inner.dims);
  e.view.type = inner.type;
  return e;
}

// The same voxels laid out z fastest (strides permuted).
template <class T>
Embedded<T> transposed(const Volume& inner) {
  Embedded<T> e;
  const Extent& d = inner.dims;
  e.big.resize(inner.count());
  for (std::size_t z = 0; z < d[2]; ++z)
    for (std::size_t y = 0; y < d[1]; ++y)
      for (std::size_t x = 0; x < d[0]; ++x) e.big[z + d[2] * (y + d[1] * x)] = T(inner.at(x, y, z));
  e.view = contiguous_view(e.big.data(), d, storage_of<T>());
  e.view.type = inner.type;
  e.view.strides = {std::ptrdiff_t(d[2] * d[1]), std::ptrdiff_t(d[2]), 1};
  return e;
}

template <class T>
void check_integer_round_trip(VoxelType type, double scale) {
  const Volume v = test::smooth_volume({21, 17, 9}, type, scale);
  const auto o = options(VolumeRateMode::lossless, 0, "cdf53");
  const auto reference = encode_copy(v, o);
  const auto inside = embed<T>(v, {40, 30, 20}, {3, 5, 2});
  EXPECT_NE(inside.view.strides[1], std::ptrdiff_t(v.dims[0]));  // really non-contiguous
  EXPECT_EQ(encode_view(inside.view, o), reference);
  EXPECT_EQ(encode_view(transposed<T>(v).view, o), reference);
  const auto lossy = options(VolumeRateMode::max_error, 2.0, "cdf97");
  EXPECT_EQ(encode_view(inside.view, lossy), encode_copy(v, lossy));
  const auto decoded = decode_volumes(encode_view(inside.view, o), 0, serial_executor());
  ASSERT_EQ(decoded.size(), 1u);
  EXPECT_EQ(decoded[0].volume.type, type);
  EXPECT_EQ(decoded[0].volume.samples, v.samples);
}

TEST(VolumeView, U8SubBoxGivesTheStreamOfItsContiguousCopy) {
  check_integer_round_trip<std::uint8_t>(VoxelType::u8, 255.0);
}

TEST(VolumeView, U16SubBoxGivesTheStreamOfItsContiguousCopy) {
  check_integer_round_trip<std::uint16_t>(VoxelType::u16, 4000.0);
}

// The encoder gathers a brick as the view's storage type (u8, u16, float, to bound
// memory), not as double: lossless, fixed-step and max-error coding give the stream of the
// double path (a Volume, held as double), also for integer voxels in a wider storage.
template <class T>
void check_storage_gives_the_double_stream(VoxelType type, double scale) {
  const Volume v = test::smooth_volume({21, 17, 9}, type, scale);
  const bool integer = type != VoxelType::f32;
  std::vector<VolumeEncodeOptions> modes = {options(VolumeRateMode::max_error, 0.01 * scale, "cdf97"),
                                            options(VolumeRateMode::step, 0.02 * scale, "cdf97")};
  if (integer) modes.push_back(options(VolumeRateMode::lossless, 0, "cdf53"));
  const auto inside = embed<T>(v, {40, 30, 20}, {3, 5, 2});
  for (const auto& o : modes)
    EXPECT_EQ(encode_view(inside.view, o), encode_copy(v, o))
        << to_string(type) << " in " << to_string(storage_of<T>()) << ", mode " << int(o.mode);
}

TEST(VolumeView, EveryStorageTypeGivesTheStreamOfTheDoublePath) {
  check_storage_gives_the_double_stream<std::uint8_t>(VoxelType::u8, 255.0);
  check_storage_gives_the_double_stream<std::uint16_t>(VoxelType::u8, 255.0);
  check_storage_gives_the_double_stream<float>(VoxelType::u8, 255.0);
  check_storage_gives_the_double_stream<std::uint16_t>(VoxelType::u16, 4000.0);
  check_storage_gives_the_double_stream<float>(VoxelType::u16, 4000.0);
  check_storage_gives_the_double_stream<float>(VoxelType::f32, 50.0);
}

// gather_box gives a box's voxels in any type that holds the storage exactly, and refuses a
// narrower one rather than round.
TEST(VolumeView, GatherBoxHoldsTheStorageExactlyAndRefusesNarrowing) {
  std::vector<std::uint16_t> data(6 * 5 * 4);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = std::uint16_t((i * 7919u) % 65536u);
  const VolumeView view =
      sub_view(contiguous_view(data.data(), {6, 5, 4}, VoxelType::u16), {1, 1, 1}, {4, 3, 2});
  std::vector<double> wide;
  std::vector<std::uint16_t> own;
  std::vector<float> single;
  std::vector<std::uint8_t> active, narrow;
  const Extent at{1, 0, 1}, size{3, 3, 1};
  gather_box(view, at, size, wide, active);
  gather_box(view, at, size, own, active);
  gather_box(view, at, size, single, active);
  ASSERT_EQ(wide.size(), 9u);
  ASSERT_EQ(own.size(), 9u);
  ASSERT_EQ(single.size(), 9u);
  EXPECT_TRUE(active.empty());
  for (std::size_t y = 0, k = 0; y < 3; ++y)
    for (std::size_t x = 0; x < 3; ++x, ++k) {
      EXPECT_EQ(wide[k], view.at(1 + x, y, 1));
      EXPECT_EQ(double(own[k]), wide[k]);
      EXPECT_EQ(double(single[k]), wide[k]);
    }
  EXPECT_GT(*std::max_element(wide.begin(), wide.end()), 255.0);  // u8 could not hold them
  EXPECT_THROW(gather_box(view, at, size, narrow, active), std::invalid_argument);
  const std::vector<float> floats(8, 0.5f);
  const VolumeView float_view = contiguous_view(floats.data(), {2, 2, 2}, VoxelType::f32);
  EXPECT_THROW(gather_box(float_view, {0, 0, 0}, {2, 2, 2}, own, active), std::invalid_argument);
  const std::vector<double> doubles(8, 0.1);
  const VolumeView double_view = contiguous_view(doubles.data(), {2, 2, 2}, VoxelType::f64);
  EXPECT_THROW(gather_box(double_view, {0, 0, 0}, {2, 2, 2}, single, active), std::invalid_argument);
  gather_box(double_view, {0, 0, 0}, {2, 2, 2}, wide, active);
  EXPECT_EQ(wide, doubles);
}

TEST(VolumeView, SparseViewReadsItsStridedMask) {
  const Volume v = test::sphere_level_set({24, 24, 24}, 7.0, 2.5, 0.3);
  const auto o = options(VolumeRateMode::max_error, 1e-3, "cdf97");
  auto e = embed<double>(v, {30, 27, 26}, {4, 1, 2});  // f32 voxels held as double (background 0.3)
  std::vector<std::uint8_t> mask(e.big.size(), 1);     // junk outside the box
  for (std::size_t z = 0; z < 24; ++z)
    for (std::size_t y = 0; y < 24; ++y)
      for (std::size_t x = 0; x < 24; ++x)
        mask[(4 + x) + 30 * ((1 + y) + 27 * (2 + z))] = v.active[v.index(x, y, z)];
  e.view.active = mask.data() + (4 + 30 * (1 + 27 * 2));  // the mask of the same sub-box
  e.view.background = v.background;
  EXPECT_EQ(encode_view(e.view, o), encode_copy(v, o));
}

TEST(VolumeView, ViewThatDoesNotFitItsGridIsRefused) {
  const Volume v = test::smooth_volume({8, 8, 8}, VoxelType::u8, 255.0);
  std::vector<std::uint8_t> bytes(v.samples.begin(), v.samples.end());
  const VolumeView view = contiguous_view(bytes.data(), v.dims, VoxelType::u8);
  VolumeGrid wrong = describe_view(view, "x");
  wrong.volume.type = VoxelType::u16;
  const VolumeView views[] = {view};
  const auto o = options(VolumeRateMode::lossless, 0, "cdf53");
  EXPECT_THROW(encode_volumes({wrong}, views, o), std::invalid_argument);
  VolumeView float_in_u8 = view;
  float_in_u8.type = VoxelType::f32;  // u8 elements cannot hold float voxels
  const VolumeView bad[] = {float_in_u8};
  EXPECT_THROW(encode_volumes({describe_view(float_in_u8, "x")}, bad, o), std::invalid_argument);
}

// decode_volume_into a buffer of the stored type gives decode_volumes' values in that type (and
// its mask).
template <class T>
void check_typed_decode(const Volume& v, const VolumeEncodeOptions& o, int level) {
  const auto bytes = encode_copy(v, o);
  const auto reference = decode_volumes(bytes, level, serial_executor());
  std::vector<T> out;
  std::vector<std::uint8_t> mask;
  const auto grid =
      decode_volume_into(bytes, "", level, serial_executor(), DecodeLimits{}, [&](const VolumeGrid& g) {
        out.resize(g.volume.count());
        VolumeOutput target = contiguous_output(out.data(), g.volume.dims, g.volume.type);
        if (g.volume.is_sparse()) mask.resize(g.volume.count()), target.active = mask.data();
        return target;
      });
  ASSERT_TRUE(grid.has_value());
  const Volume& r = reference[0].volume;
  EXPECT_EQ(grid->volume.dims, r.dims);
  ASSERT_EQ(out.size(), r.count());
  // decode_volumes keeps inactive values as the doubles the stream holds (a level set's 0.3);
  // an f32 output holds them as the raw writer always did, rounded to float.
  for (std::size_t i = 0; i < out.size(); ++i) ASSERT_EQ(out[i], T(r.samples[i])) << i;
  EXPECT_EQ(mask, r.active);
}

TEST(VolumeView, DecodeIntoStoredTypeMatchesDecodeVolumes) {
  check_typed_decode<std::uint8_t>(test::smooth_volume({21, 17, 9}, VoxelType::u8, 255.0),
                                   options(VolumeRateMode::max_error, 3.0, "cdf97"), 0);
  check_typed_decode<std::uint16_t>(test::smooth_volume({21, 17, 9}, VoxelType::u16, 4000.0),
                                    options(VolumeRateMode::lossless, 0, "cdf53"), 1);
  check_typed_decode<float>(test::sphere_level_set({24, 24, 24}, 7.0, 2.5, 0.3),
                            options(VolumeRateMode::max_error, 1e-3, "cdf97"), 0);
}

TEST(VolumeView, DecodeIntoLeavesCoarseSparseGridsToDecodeVolumes) {
  const auto bytes = encode_copy(test::sphere_level_set({24, 24, 24}, 7.0, 2.5, 0.3),
                                 options(VolumeRateMode::max_error, 1e-3, "cdf97"));
  bool called = false;
  const auto grid =
      decode_volume_into(bytes, "", 1, serial_executor(), DecodeLimits{}, [&](const VolumeGrid&) {
        called = true;
        return VolumeOutput{};
      });
  EXPECT_FALSE(grid.has_value());
  EXPECT_FALSE(called);
  EXPECT_FALSE(
      decode_volume_into(bytes, "other", 0, serial_executor(), DecodeLimits{}, [&](const VolumeGrid&) {
        return VolumeOutput{};
      }).has_value());
}

}  // namespace
}  // namespace pupwave
