// The decoder treats every stream as hostile: empty, truncated, random, bit-flipped and
// crafted inputs must give DecodeError (never a crash, a hang or a huge allocation).
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "codec/error.h"
#include "codec/format/byte_io.h"
#include "codec/format/crc32.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_stream.h"
#include "test_images.h"

namespace pupwave {
namespace {

std::vector<std::uint8_t> sample_stream(EntropyCoder coder = EntropyCoder::ebcot) {
  EncodeOptions o;
  o.mode = RateMode::bpp;
  o.target = 2.0;
  o.entropy = coder;
  return encode_image(testing::synthetic_image(70, 50, 3, SampleType::u8), o).bytes;
}

// Offsets where chunks start (signature is 5 bytes; each chunk is 12 bytes + payload).
std::vector<std::size_t> chunk_starts(const std::vector<std::uint8_t>& bytes) {
  std::vector<std::size_t> starts;
  std::size_t pos = 5;
  while (pos + 8 <= bytes.size()) {
    starts.push_back(pos);
    ByteReader r(std::span<const std::uint8_t>(bytes).subspan(pos + 4, 4), "length");
    pos += 12 + r.u32();
  }
  return starts;
}

// Calls `decode` with `per_chunk` copies of the stream, each with one random bit of a DATA
// chunk's payload flipped and that chunk's CRC fixed, so the block decoder sees the damage;
// returns how many copies were made.
int for_each_data_flip(const std::vector<std::uint8_t>& bytes, unsigned seed, int per_chunk,
                       const std::function<void(const std::vector<std::uint8_t>&)>& decode) {
  std::mt19937 rng(seed);
  int trials = 0;
  for (std::size_t start : chunk_starts(bytes)) {
    if (std::string(bytes.begin() + std::ptrdiff_t(start), bytes.begin() + std::ptrdiff_t(start) + 4) !=
        "DATA")
      continue;
    ByteReader r(std::span<const std::uint8_t>(bytes).subspan(start + 4, 4), "length");
    const std::size_t length = r.u32();
    for (int k = 0; k < per_chunk && length > 0; ++k, ++trials) {
      auto bad = bytes;
      bad[start + 8 + rng() % length] ^= std::uint8_t(1u << (rng() % 8));
      const std::uint32_t crc = crc32(std::span<const std::uint8_t>(bad).subspan(start, 8 + length));
      for (int i = 0; i < 4; ++i) bad[start + 8 + length + std::size_t(i)] = std::uint8_t(crc >> (8 * i));
      decode(bad);
    }
  }
  return trials;
}

// Rewrites the HEAD chunk's payload through `edit` and fixes its CRC, so only the field
// validation can reject the stream.
std::vector<std::uint8_t> with_header_edit(std::vector<std::uint8_t> bytes,
                                           const std::function<void(std::uint8_t*)>& edit) {
  const std::size_t head = 5;
  const std::size_t length = bytes[head + 4] | (bytes[head + 5] << 8);
  edit(bytes.data() + head + 8);
  const std::uint32_t crc = crc32(std::span<const std::uint8_t>(bytes).subspan(head, 8 + length));
  for (int i = 0; i < 4; ++i) bytes[head + 8 + length + std::size_t(i)] = std::uint8_t(crc >> (8 * i));
  return bytes;
}

void put_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = std::uint8_t(v >> (8 * i));
}

TEST(HostileStream, EmptyAndTinyInputsAreRejected) {
  EXPECT_THROW(decode_image({}), DecodeError);
  const std::vector<std::uint8_t> sig{'P', 'U', 'P', 'W', 1};
  EXPECT_THROW(decode_image(sig), DecodeError);
  EXPECT_THROW(decode_image(std::vector<std::uint8_t>{'P', 'U', 'P', 'W', 9}), DecodeError);
  EXPECT_THROW(describe_stream({}), DecodeError);
}

TEST(HostileStream, EveryTruncationIsRejected) {
  for (EntropyCoder coder : {EntropyCoder::ebcot, EntropyCoder::ht}) {
    const auto bytes = sample_stream(coder);
    for (std::size_t cut : chunk_starts(bytes)) {
      const std::vector<std::uint8_t> head(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut));
      EXPECT_THROW(decode_image(head), DecodeError) << "cut at chunk boundary " << cut;
    }
    for (std::size_t cut = 0; cut < bytes.size(); cut += 1 + cut / 16) {
      const std::vector<std::uint8_t> head(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut));
      EXPECT_THROW(decode_image(head), DecodeError) << "cut at " << cut;
    }
  }
}

TEST(HostileStream, EveryFlippedBitIsDetected) {
  const auto bytes = sample_stream();
  std::mt19937 rng(5);
  // Every bit of the signature and header region, then random bits of the payloads.
  std::vector<std::size_t> bits;
  for (std::size_t b = 0; b < std::min<std::size_t>(bytes.size(), 200) * 8; ++b) bits.push_back(b);
  for (int k = 0; k < 400; ++k) bits.push_back(rng() % (bytes.size() * 8));
  const auto good = decode_image(bytes).samples;
  for (std::size_t b : bits) {
    auto bad = bytes;
    bad[b / 8] ^= std::uint8_t(1u << (b % 8));
    // A flip of the version byte that lands on an older version this coder's streams share (6 to 4
    // here): the same image, nothing lost (docs/bitstream.md); every other flip is an error.
    if (b / 8 == 4 && bad[4] >= kOldestStreamVersion && bad[4] < kStreamVersion) {
      EXPECT_EQ(decode_image(bad).samples, good);
      continue;
    }
    EXPECT_THROW(decode_image(bad), DecodeError) << "bit " << b;
  }
}

// ht code-blocks with flipped bits behind valid chunk CRCs reach the ht decoder: each decode
// gives an error or an image of the right shape (a flipped sign or magnitude bit of the last
// coefficients can be undetectable), never a crash or an overrun.
TEST(HostileStream, CorruptHtBlocksBehindValidCrcsAreContained) {
  const auto bytes = sample_stream(EntropyCoder::ht);
  int rejected = 0;
  const int trials = for_each_data_flip(bytes, 16, 60, [&](const std::vector<std::uint8_t>& bad) {
    try {
      const Image out = decode_image(bad);
      EXPECT_EQ(out.width, 70u);
    } catch (const DecodeError&) {
      ++rejected;
    }
  });
  EXPECT_GT(trials, 0);
  EXPECT_GT(rejected, trials / 2);
}

TEST(HostileStream, RandomBytesAreRejected) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::uint8_t> junk(rng() % 4000);
    for (auto& b : junk) b = std::uint8_t(rng());
    if (trial % 2 == 0 && junk.size() >= 5) {  // get past the signature check
      junk[0] = 'P', junk[1] = 'U', junk[2] = 'P', junk[3] = 'W', junk[4] = 1;
    }
    EXPECT_THROW(decode_image(junk), DecodeError);
  }
}

TEST(HostileStream, CraftedHeadersWithAbsurdFieldsAreRejected) {
  const auto bytes = sample_stream();
  EXPECT_NO_THROW(decode_image(with_header_edit(bytes, [](std::uint8_t*) {})));
  const std::vector<std::function<void(std::uint8_t*)>> edits = {
      [](std::uint8_t* p) { put_u32(p, 1u << 20); },                      // width over 2^16
      [](std::uint8_t* p) { put_u32(p, 0); },                             // zero width
      [](std::uint8_t* p) { put_u32(p, 65536), put_u32(p + 4, 65536); },  // 2^32 samples
      [](std::uint8_t* p) { put_u32(p + 8, 7); },                         // depth for an image
      [](std::uint8_t* p) { p[12] = 9; },                                 // channels
      [](std::uint8_t* p) { p[13] = 7; },                                 // sample type
      [](std::uint8_t* p) { p[14] = 2; },                                 // RCT in a lossy stream
      [](std::uint8_t* p) { p[15] = 5; },                                 // entropy coder
      [](std::uint8_t* p) { p[17] = 40; },                                // levels
      [](std::uint8_t* p) { p[18] = 1, p[19] = 1; },                      // 2x2 code-blocks
      [](std::uint8_t* p) { p[25] = 'x'; },                               // transform spec
  };
  for (std::size_t k = 0; k < edits.size(); ++k)
    EXPECT_THROW(decode_image(with_header_edit(bytes, edits[k])), DecodeError) << "edit " << k;
}

TEST(HostileStream, DescribeStreamSummarizesAValidStream) {
  const auto bytes = sample_stream();
  const std::string text = describe_stream(bytes);
  EXPECT_NE(text.find("70 x 50"), std::string::npos) << text;
  EXPECT_NE(text.find("cdf97"), std::string::npos) << text;
  EXPECT_NE(text.find("DATA 0"), std::string::npos) << text;
}

// A lossless stream of the lc coder (entropy coder 3), coarse band and detail bands.
std::vector<std::uint8_t> lc_stream(int levels) {
  EncodeOptions o;
  o.mode = RateMode::lossless;
  o.transform = "cdf53";
  o.levels = levels;
  o.entropy = EntropyCoder::lc;
  return encode_image(testing::synthetic_image(70, 50, 3, SampleType::u8), o).bytes;
}

TEST(HostileStream, LcTruncationsAreRejected) {
  for (int levels : {0, 2}) {
    const auto bytes = lc_stream(levels);
    for (std::size_t cut = 0; cut < bytes.size(); cut += 1 + cut / 16) {
      const std::vector<std::uint8_t> head(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut));
      EXPECT_THROW(decode_image(head), DecodeError) << "cut at " << cut;
    }
  }
}

// lc code-blocks with flipped bits behind valid chunk CRCs reach the lc decoder: each decode
// gives an error (the index's bit-plane count, the value bound) or an image of the right shape,
// never a crash, an overrun or a hang. An arithmetic codeword has no redundancy to check, so
// most such flips decode to wrong samples: the chunk CRC is what detects them.
TEST(HostileStream, CorruptLcBlocksBehindValidCrcsAreContained) {
  for (int levels : {0, 2}) {
    const int trials =
        for_each_data_flip(lc_stream(levels), 23, 40, [](const std::vector<std::uint8_t>& bad) {
          try {
            const Image out = decode_image(bad);
            EXPECT_EQ(out.width, 70u);
            EXPECT_EQ(out.height, 50u);
          } catch (const DecodeError&) {
          }
        });
    EXPECT_GT(trials, 0);
  }
}

TEST(HostileStream, LcCoderOnlyInReversibleStreams) {
  const auto bytes = lc_stream(0);
  EXPECT_EQ(decode_image(bytes).width, 70u);
  // Coder field (HEAD offset 15) beyond lc, and lc with the reversible flag (16) cleared.
  EXPECT_THROW(decode_image(with_header_edit(bytes, [](std::uint8_t* p) { p[15] = 4; })), DecodeError);
  EXPECT_THROW(decode_image(with_header_edit(bytes, [](std::uint8_t* p) { p[16] = 0; })), DecodeError);
}

// A lossy stream of the pc coder (entropy coder 4): every band one block, parents across levels.
std::vector<std::uint8_t> pc_stream() {
  EncodeOptions o;
  o.mode = RateMode::bpp;
  o.target = 2.0;
  o.levels = 3;
  o.entropy = EntropyCoder::pc;
  return encode_image(testing::synthetic_image(70, 50, 3, SampleType::u8), o).bytes;
}

TEST(HostileStream, PcTruncationsAreRejected) {
  const auto bytes = pc_stream();
  for (std::size_t cut = 0; cut < bytes.size(); cut += 1 + cut / 16) {
    const std::vector<std::uint8_t> head(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut));
    EXPECT_THROW(decode_image(head), DecodeError) << "cut at " << cut;
  }
}

// pc code-blocks with flipped bits behind valid chunk CRCs: an error (the index's plane count)
// or an image of the right shape, at every reduced level, never a crash, overrun or hang.
TEST(HostileStream, CorruptPcBlocksBehindValidCrcsAreContained) {
  int errors = 0;
  const int trials = for_each_data_flip(pc_stream(), 29, 40, [&](const std::vector<std::uint8_t>& bad) {
    for (int level : {0, 1}) {
      try {
        const Image out = decode_image(bad, level);
        EXPECT_EQ(out.width, level == 0 ? 70u : 35u);
      } catch (const DecodeError&) {
        ++errors;
      }
    }
  });
  EXPECT_GT(trials, 0);
  EXPECT_GT(errors, 0);  // some flips change a block's largest index: its plane count catches them
}

// The index's plane count P must be the bit length of the largest decoded index: the same
// codewords under an index that claims one plane more are refused.
TEST(HostileStream, PcPlaneCountMismatchIsCaught) {
  const auto bytes = pc_stream();
  const ParsedStream s = parse_container(bytes);
  std::vector<std::vector<std::uint8_t>> data;
  for (const auto& d : s.resolution_data) data.emplace_back(d.begin(), d.end());
  EXPECT_EQ(write_container(s.header, s.index, data), bytes);  // the rebuild itself is faithful
  int checked = 0;
  for (std::size_t i = 0; i < s.index.size(); ++i) {
    if (s.index[i].passes == 0 || s.index[i].planes >= 30) continue;
    auto index = s.index;
    ++index[i].planes;
    EXPECT_THROW(decode_image(write_container(s.header, index, data)), DecodeError) << "block " << i;
    ++checked;
  }
  EXPECT_GT(checked, 3);
}

TEST(HostileStream, PcCoderOnlyInLossyStreams) {
  const auto bytes = pc_stream();
  EXPECT_EQ(decode_image(bytes).width, 70u);
  // pc with the reversible flag (HEAD offset 16) set; lc (coder 3) in this lossy stream.
  EXPECT_THROW(decode_image(with_header_edit(bytes, [](std::uint8_t* p) { p[16] = 1; })), DecodeError);
  EXPECT_THROW(decode_image(with_header_edit(bytes, [](std::uint8_t* p) { p[15] = 3; })), DecodeError);
  EncodeOptions o;
  o.mode = RateMode::lossless;
  o.transform = "cdf53";
  o.entropy = EntropyCoder::pc;
  EXPECT_THROW(encode_image(testing::synthetic_image(20, 20, 1, SampleType::u8), o), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave
