#pragma once
// The optional chunks of an image stream (docs/bitstream.md, version 2): META (channel names,
// data and display windows, attributes) and NFIN (non-finite samples kept exactly).

#include <cstdint>
#include <span>
#include <vector>

#include "codec/image/image_stream.h"

namespace pupwave {

// Caps that keep a hostile META or NFIN chunk from demanding unbounded memory.
inline constexpr std::size_t kMaxAttributes = 4096;
inline constexpr std::size_t kMaxNameLength = 4096;

std::vector<std::uint8_t> metadata_payload(const ImageMetadata& m);
// Throws DecodeError for a malformed payload (or channel names not matching `channels`).
ImageMetadata parse_metadata(std::span<const std::uint8_t> payload, std::uint32_t channels);

std::vector<std::uint8_t> nonfinite_payload(const std::vector<NonFiniteSample>& list);
// Throws DecodeError for a malformed payload or an entry outside the image, out of order or
// holding a finite value.
std::vector<NonFiniteSample> parse_nonfinite(std::span<const std::uint8_t> payload, const StreamHeader& h);

}  // namespace pupwave
