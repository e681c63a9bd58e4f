// The optional META and NFIN chunks: round trips, and hostile payloads refused with DecodeError.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_stream_extras.h"

namespace pupwave {
namespace {

ImageMetadata sample_metadata() {
  ImageMetadata m;
  m.channel_names = {"Y", "depth", "mask"};
  m.x = 100;
  m.y = -50;
  m.full_width = 800;
  m.full_height = 600;
  m.attributes.push_back({"myshow:shot", ImageAttribute::Kind::string, "sh010", 0, 0.0});
  m.attributes.push_back({"myshow:take", ImageAttribute::Kind::integer, "", -7, 0.0});
  m.attributes.push_back({"myshow:gain", ImageAttribute::Kind::real, "", 0, 1.25});
  return m;
}

std::uint32_t bits(float v) {
  std::uint32_t b = 0;
  std::memcpy(&b, &v, 4);
  return b;
}

TEST(ContainerExtras, MetadataRoundTrips) {
  const ImageMetadata m = sample_metadata();
  EXPECT_EQ(parse_metadata(metadata_payload(m), 3), m);
}

TEST(ContainerExtras, HostileMetadataIsRefused) {
  const auto p = metadata_payload(sample_metadata());
  EXPECT_THROW(parse_metadata(p, 4), DecodeError);  // names for 3 channels in a 4-channel stream
  for (std::size_t cut = 0; cut < p.size(); cut += 7)
    EXPECT_THROW(parse_metadata(std::span(p).first(cut), 3), DecodeError) << cut;
  auto bad_kind = p;
  // The first attribute's kind byte follows its name; corrupt it.
  const std::size_t at = p.size() - (2 + 11 + 1 + 8) - (2 + 11 + 1 + 8) - (2 + 5) - 1;
  ASSERT_EQ(bad_kind[at], 0);
  bad_kind[at] = 9;
  EXPECT_THROW(parse_metadata(bad_kind, 3), DecodeError);
}

TEST(ContainerExtras, NonFiniteListIsChecked) {
  StreamHeader h;
  h.dims = {10, 10, 1};
  h.channels = 2;
  h.type = SampleType::f32;
  const std::vector<NonFiniteSample> ok{{0, 5, bits(std::numeric_limits<float>::quiet_NaN())},
                                        {1, 99, bits(-std::numeric_limits<float>::infinity())}};
  const auto parsed = parse_nonfinite(nonfinite_payload(ok), h);
  ASSERT_EQ(parsed.size(), 2u);
  EXPECT_EQ(parsed[1].index, 99u);
  auto finite = ok;
  finite[0].bits = bits(1.0f);
  EXPECT_THROW(parse_nonfinite(nonfinite_payload(finite), h), DecodeError);
  auto outside = ok;
  outside[1].index = 100;
  EXPECT_THROW(parse_nonfinite(nonfinite_payload(outside), h), DecodeError);
  auto unordered = ok;
  std::swap(unordered[0], unordered[1]);
  EXPECT_THROW(parse_nonfinite(nonfinite_payload(unordered), h), DecodeError);
  auto p = nonfinite_payload(ok);
  p[0] = 0xFF;  // a count far beyond the payload
  EXPECT_THROW(parse_nonfinite(p, h), DecodeError);
}

TEST(ContainerExtras, MetadataTravelsThroughTheCodec) {
  Image img(40, 30, 3, SampleType::f16);
  for (std::size_t i = 0; i < img.samples.size(); ++i) img.samples[i] = float(i % 97) * 0.5f;
  img.metadata = sample_metadata();
  const Image out = decode_image(encode_image(img, EncodeOptions{}).bytes);
  EXPECT_EQ(out.metadata, img.metadata);
  img.metadata.channel_names.pop_back();  // names for 2 of 3 channels
  EXPECT_THROW(encode_image(img, EncodeOptions{}), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave
