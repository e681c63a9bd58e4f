// The conformance corpus testimages/streams/ (described in testimages/README.md): every stream
// listed in MANIFEST.tsv, whatever format version and build wrote it, still decodes, to voxels
// whose CRC32 (as the stored type, little endian, x fastest) is the one recorded when it was
// written. A format change that breaks an older stream fails here.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "codec/format/crc32.h"
#include "codec/volume/volume_codec.h"

namespace pupwave {
namespace {

const std::string kCorpus = PUPWAVE_TESTIMAGES_DIR "/streams/";

std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << "cannot open " << path;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A grid's voxels as its stored type, little endian (the raw form `pupwave decompress` writes).
std::vector<std::uint8_t> stored_bytes(const Volume& v) {
  std::vector<std::uint8_t> out(v.count() * bytes_per_voxel(v.type));
  for (std::size_t i = 0; i < v.count(); ++i) {
    std::uint8_t* at = out.data() + i * bytes_per_voxel(v.type);
    const double s = v.samples[i];
    switch (v.type) {
      case VoxelType::u8: *at = std::uint8_t(s); break;
      case VoxelType::u16: {
        const auto u = std::uint16_t(s);
        std::memcpy(at, &u, 2);
        break;
      }
      case VoxelType::f32: {
        const auto f = float(s);
        std::memcpy(at, &f, 4);
        break;
      }
      case VoxelType::f64: std::memcpy(at, &s, 8); break;
    }
  }
  return out;
}

struct Entry {
  std::string file;
  int version = 0;
  std::string writer;
  std::uint32_t crc = 0;
};

std::vector<Entry> manifest() {
  std::ifstream in(kCorpus + "MANIFEST.tsv");
  EXPECT_TRUE(in.good()) << "cannot open " << kCorpus << "MANIFEST.tsv";
  std::vector<Entry> entries;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Entry e;
    std::string version, crc;
    std::getline(fields, e.file, '\t');
    std::getline(fields, version, '\t');
    std::getline(fields, e.writer, '\t');
    std::getline(fields, crc, '\t');
    e.version = std::stoi(version);
    e.crc = std::uint32_t(std::stoul(crc, nullptr, 16));
    entries.push_back(e);
  }
  return entries;
}

TEST(StreamCorpus, EveryListedStreamDecodesToItsRecordedVoxels) {
  const auto entries = manifest();
  ASSERT_GE(entries.size(), 4u);
  bool version6 = false, version7 = false;
  for (const Entry& e : entries) {
    const auto bytes = read_bytes(kCorpus + e.file);
    ASSERT_GT(bytes.size(), 5u) << e.file;
    EXPECT_EQ(int(bytes[4]), e.version) << e.file;
    version6 = version6 || e.version == 6;
    version7 = version7 || e.version == 7;
    const auto grids = decode_volumes(bytes);
    ASSERT_EQ(grids.size(), 1u) << e.file;
    EXPECT_EQ(crc32(stored_bytes(grids[0].volume)), e.crc) << e.file << " (written by " << e.writer << ")";
  }
  EXPECT_TRUE(version6 && version7);
}

}  // namespace
}  // namespace pupwave
