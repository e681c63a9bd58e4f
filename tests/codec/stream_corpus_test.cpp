// The conformance corpus testimages/streams/ (described in testimages/README.md): every image and
// volume stream listed in MANIFEST.tsv, whatever format version and build wrote it, still
// decodes, to samples whose CRC32 (as the stored type, little endian, x fastest, channels
// interleaved; float samples as binary32) is the one recorded when it was written. A format change that
// breaks an older stream fails here.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "codec/format/crc32.h"
#include "codec/image/image_codec.h"
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

// An image's samples, channels interleaved, as its stored type, little endian (u8, u16; f16 and f32
// as binary32: f16 rounded to half first, as a file stores it).
std::vector<std::uint8_t> stored_bytes(const Image& image) {
  const std::size_t width = is_integer(image.type) ? std::size_t(bits_per_sample(image.type) / 8) : 4;
  std::vector<std::uint8_t> out(image.samples.size() * width);
  for (std::size_t i = 0; i < image.samples.size(); ++i) {
    std::uint8_t* at = out.data() + i * width;
    const float s = image.plane(i % image.channels)[i / image.channels];  // interleaved order
    switch (image.type) {
      case SampleType::u8: *at = std::uint8_t(s); break;
      case SampleType::u16: {
        const auto u = std::uint16_t(s);
        std::memcpy(at, &u, 2);
        break;
      }
      case SampleType::f16: {
        const float h = float(static_cast<_Float16>(s));  // the half a file of this type stores
        std::memcpy(at, &h, 4);
        break;
      }
      case SampleType::f32: std::memcpy(at, &s, 4); break;
    }
  }
  return out;
}

// The CRC32 of what a stream decodes to: an image, or a volume of one grid.
std::uint32_t decoded_crc(const std::vector<std::uint8_t>& bytes, const std::string& file) {
  if (is_volume_stream(bytes)) {
    const auto grids = decode_volumes(bytes);
    EXPECT_EQ(grids.size(), 1u) << file;
    return grids.empty() ? 0 : crc32(stored_bytes(grids[0].volume));
  }
  return crc32(stored_bytes(decode_image(bytes)));
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

TEST(StreamCorpus, EveryListedStreamDecodesToItsRecordedSamples) {
  const auto entries = manifest();
  ASSERT_GE(entries.size(), 12u);
  std::size_t images = 0, volumes = 0;
  for (const Entry& e : entries) {
    const auto bytes = read_bytes(kCorpus + e.file);
    ASSERT_GT(bytes.size(), 5u) << e.file;
    EXPECT_EQ(int(bytes[4]), e.version) << e.file;
    (is_volume_stream(bytes) ? volumes : images) += 1;
    EXPECT_EQ(decoded_crc(bytes, e.file), e.crc) << e.file << " (written by " << e.writer << ")";
  }
  EXPECT_GE(images, 6u);
  EXPECT_GE(volumes, 7u);
}

}  // namespace
}  // namespace pupwave
