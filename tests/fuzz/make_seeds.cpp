// fuzz_make_seeds OUT_DIR: the seeds tests/fuzz/make_corpus.sh cannot make with the CLI, from a
// real field (testimages/wmag91.float, a crop): a sparse box volume stream (MASK chunk; only the
// library API writes those) and HDF5 chunks (tools/hdf5 chunk codec). Writes
// OUT_DIR/volume/seed-sparse-box.pw and OUT_DIR/hdf5_chunk/seed-*.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "codec/volume/volume_codec.h"
#include "tools/hdf5/chunk_codec.h"

using namespace pupwave;
namespace fs = std::filesystem;

namespace {

// The crop [0, n)^3 of wmag91 (91^3 floats, x fastest).
std::vector<float> wmag_crop(const Extent& n) {
  std::ifstream in(PUPWAVE_TESTIMAGES_DIR "/wmag91.float", std::ios::binary);
  std::vector<float> all(91 * 91 * 91);
  in.read(reinterpret_cast<char*>(all.data()), std::streamsize(all.size() * 4));
  if (!in) throw std::runtime_error("cannot read wmag91.float");
  std::vector<float> out;
  for (std::size_t z = 0; z < n[2]; ++z)
    for (std::size_t y = 0; y < n[1]; ++y)
      for (std::size_t x = 0; x < n[0]; ++x) out.push_back(all[x + 91 * (y + 91 * z)]);
  return out;
}

void save(const fs::path& p, const std::vector<std::uint8_t>& bytes) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Active above the median; inactive voxels of every state; x >= 16 (whole bricks of 8) empty.
std::vector<std::uint8_t> sparse_box_stream() {
  const Extent n{24, 20, 12};
  const auto values = wmag_crop(n);
  std::vector<float> sorted = values;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
  VolumeGrid g;
  g.name = "wmag";
  g.volume = Volume(n, VoxelType::f32);
  g.volume.background = 0.5;
  g.volume.active.assign(g.volume.count(), 0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::size_t x = i % n[0];
    g.volume.samples[i] = values[i];
    if (x >= 16)
      g.volume.samples[i] = 0.5;
    else if (values[i] > sorted[sorted.size() / 2])
      g.volume.active[i] = 1;
    else if (x % 5 == 0)
      g.volume.samples[i] = -0.5;
    else if (x % 3 != 0)
      g.volume.samples[i] = 0.5;
  }
  VolumeEncodeOptions o;
  o.target = 1e-2;
  o.brick = 8;
  o.block = 16;
  o.executor = &serial_executor();
  return encode_volumes({g}, o).bytes;
}

std::vector<std::uint8_t> as_bytes(const std::vector<float>& v) {
  std::vector<std::uint8_t> out(v.size() * 4);
  std::memcpy(out.data(), v.data(), out.size());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_seeds OUT_DIR\n");
    return 2;
  }
  const fs::path out = argv[1];
  save(out / "volume" / "seed-sparse-box.pw", sparse_box_stream());
  h5::ChunkParams p;
  p.dims = {16, 16, 8};
  const auto crop = wmag_crop(p.dims);
  const auto field = as_bytes(crop);
  p.bound = 1e-2;
  save(out / "hdf5_chunk" / "seed-f32-max-error", h5::encode_chunk(p, field));
  p.mode = h5::Mode::bpv;
  p.bound = 2.0;
  save(out / "hdf5_chunk" / "seed-f32-bpv", h5::encode_chunk(p, field));
  std::vector<std::uint8_t> u16(p.count() * 2);
  for (std::size_t i = 0; i < p.count(); ++i) {
    const auto v = std::uint16_t(std::clamp(double(crop[i]) * 4000.0, 0.0, 65535.0));  // a 16-bit sensor
    std::memcpy(&u16[2 * i], &v, 2);
  }
  p.type = h5::ChunkType::u16;
  p.mode = h5::Mode::lossless;
  save(out / "hdf5_chunk" / "seed-u16-lossless", h5::encode_chunk(p, u16));
  // Trimmed chunks (kind 2): the crop zero-padded as HDF5 pads an edge chunk, a u16 one padded
  // with a fill value, and an all-constant chunk (no stream).
  h5::ChunkParams t;
  t.dims = {20, 18, 10};
  t.bound = 1e-2;
  std::vector<float> padded(t.count(), 0.0f);
  for (std::size_t i = 0; i < crop.size(); ++i)
    padded[i % 16 + 20 * (i / 16 % 16 + 18 * (i / 256))] = crop[i];
  save(out / "hdf5_chunk" / "seed-f32-trimmed", h5::encode_chunk(t, as_bytes(padded)));
  save(out / "hdf5_chunk" / "seed-f32-constant",
       h5::encode_chunk(t, as_bytes(std::vector<float>(t.count(), 2.5f))));
  t.type = h5::ChunkType::u16;
  t.mode = h5::Mode::lossless;
  std::vector<std::uint8_t> u16_padded(t.count() * 2, 0x7f);
  for (std::size_t i = 0; i < p.count(); ++i)
    std::memcpy(&u16_padded[2 * (i % 16 + 20 * (i / 16 % 16 + 18 * (i / 256)))], &u16[2 * i], 2);
  save(out / "hdf5_chunk" / "seed-u16-trimmed", h5::encode_chunk(t, u16_padded));
  p.dims = {3, 2, 1};  // too small to code: stored raw
  save(out / "hdf5_chunk" / "seed-raw",
       h5::encode_chunk(p, std::vector<std::uint8_t>(u16.begin(), u16.begin() + 12)));
  return 0;
}
