// The volume encoder reads its input in place: encoding a u8 volume from a typed view (the
// codec's VolumeView, or the public API's) never allocates a whole-volume buffer of doubles,
// floats or u16 (measured: 1.7 MB of heap at peak for a 2 MiB u8 volume). Live heap bytes are
// counted by replacing the global operator new/delete in this program (hence in tests/hostile,
// which is not built with the sanitizers, whose allocators this would bypass).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <span>
#include <string>
#include <vector>

#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_view.h"
#include "pupwave/pupwave.hpp"
#include "transforms/separable.h"

namespace {

std::atomic<std::size_t> live_bytes{0};
std::atomic<std::size_t> peak_bytes{0};
constexpr std::size_t kHeader = alignof(std::max_align_t);  // keeps the returned block aligned

void* counted_new(std::size_t n) {
  void* block = std::malloc(n + kHeader);
  if (block == nullptr) throw std::bad_alloc();
  *static_cast<std::size_t*>(block) = n;
  const std::size_t now = live_bytes.fetch_add(n) + n;
  std::size_t peak = peak_bytes.load();
  while (now > peak && !peak_bytes.compare_exchange_weak(peak, now)) {
  }
  return static_cast<char*>(block) + kHeader;
}

void counted_delete(void* p) noexcept {
  if (p == nullptr) return;
  char* block = static_cast<char*>(p) - kHeader;
  live_bytes.fetch_sub(*reinterpret_cast<std::size_t*>(block));
  std::free(block);
}

// Peak live heap bytes above those live when f starts.
template <class F>
std::size_t peak_during(F f) {
  const std::size_t before = live_bytes.load();
  peak_bytes.store(before);
  f();
  return peak_bytes.load() - before;
}

// A smooth u8 field (x fastest).
std::vector<std::uint8_t> smooth_u8(std::size_t n) {
  std::vector<std::uint8_t> v(n * n * n);
  for (std::size_t z = 0; z < n; ++z)
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x)
        v[x + n * (y + n * z)] = std::uint8_t(127.5 + 120.0 * std::sin(0.07 * double(x) + 0.05 * double(y)) *
                                                          std::cos(0.06 * double(z)));
  return v;
}

constexpr std::size_t kEdge = 128;  // 2 MiB of u8; 16 MiB as double

TEST(VolumeMemory, EncodingFromAU8ViewHoldsNoWholeVolumeCopy) {
  const auto voxels = smooth_u8(kEdge);
  const pupwave::VolumeView view =
      pupwave::contiguous_view(voxels.data(), {kEdge, kEdge, kEdge}, pupwave::VoxelType::u8);
  pupwave::VolumeEncodeOptions o;
  o.mode = pupwave::VolumeRateMode::lossless;
  o.transform = "cdf53";
  o.brick = 32;
  o.executor = &pupwave::serial_executor();
  const pupwave::VolumeView views[] = {view};
  std::size_t bytes = 0;
  const std::size_t peak = peak_during(
      [&] { bytes = pupwave::encode_volumes({pupwave::describe_view(view, "u8")}, views, o).bytes.size(); });
  EXPECT_GT(bytes, 0u);
  ::testing::Test::RecordProperty("peak_live_heap_bytes", std::to_string(peak));
  // A copy of the volume as double would be 8 bytes a voxel; the coded bricks and the stream
  // (~1.7 MB here) stay well below a u16 copy, a quarter of that.
  EXPECT_LT(peak, 2 * voxels.size()) << "peak live heap bytes " << peak << " for " << voxels.size()
                                     << " u8 voxels";
}

// Given a writer, the encoder hands each brick's chunk on as soon as the bricks before it are
// written: it holds the bricks in flight (per thread a brick's samples and transform, a few
// chunks waiting), never the whole coded volume. The field here is noisy, so the stream (most of
// the u8 voxels' size) dwarfs a brick.
TEST(VolumeMemory, EncodingToAWriterHoldsOnlyTheBricksInFlight) {
  auto voxels = smooth_u8(kEdge);
  std::uint32_t seed = 12345;
  for (auto& v : voxels) {
    seed = seed * 1664525u + 1013904223u;
    v = std::uint8_t(std::min(255u, v + (seed >> 26)));  // + 0..63
  }
  const pupwave::VolumeView view =
      pupwave::contiguous_view(voxels.data(), {kEdge, kEdge, kEdge}, pupwave::VoxelType::u8);
  const pupwave::VolumeView views[] = {view};
  for (const auto mode : {pupwave::VolumeRateMode::lossless, pupwave::VolumeRateMode::max_error}) {
    pupwave::VolumeEncodeOptions o;
    o.mode = mode;
    o.target = 1.0;
    o.transform = mode == pupwave::VolumeRateMode::lossless ? "cdf53" : "cdf97";
    o.brick = 32;
    const auto pool = pupwave::make_pool_executor(2);
    o.executor = pool.get();
    std::size_t stream = 0;
    pupwave::encode_volumes({pupwave::describe_view(view, "u8")}, views, o,
                            [&](std::span<const std::uint8_t> piece) { stream += piece.size(); });  // warm-up
    stream = 0;
    const std::size_t peak = peak_during([&] {
      pupwave::encode_volumes({pupwave::describe_view(view, "u8")}, views, o,
                              [&](std::span<const std::uint8_t> piece) { stream += piece.size(); });
    });
    const std::string name = mode == pupwave::VolumeRateMode::lossless ? "lossless" : "max_error";
    ::testing::Test::RecordProperty("peak_live_heap_bytes_" + name, std::to_string(peak));
    ::testing::Test::RecordProperty("stream_bytes_" + name, std::to_string(stream));
    EXPECT_GT(stream, voxels.size() / 2);
    EXPECT_LT(peak, stream / 2) << "peak live heap bytes " << peak << " for a stream of " << stream;
  }
}

TEST(VolumeMemory, PublicApiEncodesAU8ArrayInPlace) {
  const auto voxels = smooth_u8(kEdge);
  pupwave::api::VolumeOptions o;
  o.rate = pupwave::api::VolumeRate::max_error;
  o.target = 2.0;
  o.brick = 32;
  o.threads = 1;
  std::size_t bytes = 0;
  const std::size_t peak = peak_during([&] {
    bytes =
        pupwave::api::compress_volume({voxels.data(), {kEdge, kEdge, kEdge}, pupwave::api::VoxelType::u8}, o)
            .size();
  });
  EXPECT_GT(bytes, 0u);
  ::testing::Test::RecordProperty("peak_live_heap_bytes", std::to_string(peak));
  EXPECT_LT(peak, 2 * voxels.size()) << "peak live heap bytes " << peak << " for " << voxels.size()
                                     << " u8 voxels";
}

}  // namespace

void* operator new(std::size_t n) { return counted_new(n); }
void* operator new[](std::size_t n) { return counted_new(n); }
void operator delete(void* p) noexcept { counted_delete(p); }
void operator delete[](void* p) noexcept { counted_delete(p); }
void operator delete(void* p, std::size_t) noexcept { counted_delete(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_delete(p); }
