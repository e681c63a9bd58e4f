// Hostile .pwm streams with valid checksums: every inconsistency is a DecodeError, never a
// crash, and random payload damage decodes to something or fails cleanly.
#include <gtest/gtest.h>

#include <zstd.h>

#include <random>

#include "codec/error.h"
#include "codec/format/chunks.h"
#include "codec/mesh/mesh_codec.h"
#include "tools/mesh_io.h"
#include "transforms/sqrt3/subdivide.h"

namespace pupwave::mesh {
namespace {

struct Parts {
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> chunks;
  std::vector<std::uint8_t> join() const {
    std::vector<std::uint8_t> out;
    write_signature(out, "PWMS", 1);
    for (const auto& [tag, payload] : chunks) {
      char t[5] = {tag[0], tag[1], tag[2], tag[3], 0};
      write_chunk(out, t, payload);
    }
    return out;
  }
};

Parts split(std::span<const std::uint8_t> bytes) {
  ChunkReader r(bytes, "PWMS", 1, "mesh stream");
  Parts p;
  while (!r.at_end()) {
    const Chunk c = r.next();
    p.chunks.push_back({c.name(), std::vector<std::uint8_t>(c.payload.begin(), c.payload.end())});
  }
  return p;
}

std::vector<std::uint8_t> valid_stream(bool quantised) {
  const sqrt3::TriMesh base = cli::read_mesh(std::string(PUPWAVE_TESTIMAGES_DIR) + "/pig.off");
  MeshEncodeOptions o;
  o.levels = 2;
  if (quantised) o.max_error = 1e-3;
  return encode_mesh(sqrt3::subdivide(base, 2), o).bytes;
}

std::vector<std::uint8_t> zstd(const std::vector<std::uint8_t>& raw) {
  std::vector<std::uint8_t> out(ZSTD_compressBound(raw.size()));
  out.resize(ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), 3));
  return out;
}

TEST(HostilePwm, InconsistentFieldsAreDecodeErrors) {
  const std::vector<std::uint8_t> good = valid_stream(true);
  ASSERT_NO_THROW(decode_mesh(good));
  std::vector<Parts> bad;
  Parts p = split(good);
  p.chunks[0].second[1] = 3;  // three levels claimed, two step kinds and chunks present
  bad.push_back(p);
  p = split(good);
  p.chunks[0].second[2] = 7;  // unknown step kind
  bad.push_back(p);
  p = split(good);
  p.chunks[0].second[2 + 2 + 8] ^= 1;  // finest vertex count off by one
  bad.push_back(p);
  p = split(good);
  for (int i = 0; i < 8; ++i) p.chunks[0].second[2 + 2 + 12 + 8 + i] = 0xff;  // coarsest step NaN
  bad.push_back(p);
  p = split(good);
  p.chunks.pop_back();  // a level's details missing
  bad.push_back(p);
  p = split(good);
  p.chunks.push_back(p.chunks.back());  // data after the last chunk
  bad.push_back(p);
  p = split(good);
  std::vector<std::uint8_t> raw(
      ZSTD_getFrameContentSize(p.chunks[1].second.data(), p.chunks[1].second.size()));
  ZSTD_decompress(raw.data(), raw.size(), p.chunks[1].second.data(), p.chunks[1].second.size());
  raw[4] = raw[0];  // face 0 repeats a vertex
  raw[5] = raw[1];
  raw[6] = raw[2];
  raw[7] = raw[3];
  p.chunks[1].second = zstd(raw);
  bad.push_back(p);
  p = split(good);
  raw.assign(raw.size() - 12, 0);  // one face fewer than the header says
  p.chunks[1].second = zstd(raw);
  bad.push_back(p);
  for (std::size_t i = 0; i < bad.size(); ++i) EXPECT_THROW(decode_mesh(bad[i].join()), DecodeError) << i;
}

TEST(HostilePwm, RandomPayloadDamageNeverCrashes) {
  for (bool quantised : {false, true}) {
    const std::vector<std::uint8_t> good = valid_stream(quantised);
    std::mt19937 rng(7);
    int failed = 0;
    for (int trial = 0; trial < 60; ++trial) {
      Parts p = split(good);
      auto& payload = p.chunks[2 + std::size_t(trial) % (p.chunks.size() - 2)].second;
      if (payload.empty()) continue;
      for (int k = 0; k < 4; ++k) payload[rng() % payload.size()] = std::uint8_t(rng());
      try {
        const sqrt3::TriMesh m = decode_mesh(p.join());
        EXPECT_EQ(m.faces.size() % 3, 0u);
      } catch (const DecodeError&) {
        ++failed;
      }
    }
    // float64 damage decodes (to other points) unless a value becomes non-finite.
    EXPECT_LT(failed, 60) << quantised;
  }
}

}  // namespace
}  // namespace pupwave::mesh
