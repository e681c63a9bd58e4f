#pragma once
// What an image's attributes become in a JPEG written natively (tools/jpeg_io.cpp): the JFIF
// density and the markers after the JFIF one (comment, EXIF block made with libexif, Photoshop
// IPTC block), as OpenImageIO 2.4's JPEG writer makes them, so that a JPEG is the same whichever
// writes it.

#include <cstdint>
#include <string>
#include <vector>

#include "codec/image/image.h"

namespace pupwave::cli {

// The JFIF density fields (libjpeg's density_unit, X_density, Y_density).
struct JfifDensity {
  std::uint8_t unit = 0;
  std::uint16_t x = 1, y = 1;  // libjpeg's default
};

// A marker written after the JFIF one: its code (JPEG_COM, JPEG_APP0 + n) and contents.
struct JpegMarker {
  int code = 0;
  std::string bytes;
};
// Whether every attribute is one stored here as OpenImageIO stores it (jpeg_writable in
// jpeg_io.h lists them), once, with text that fits the blocks.
bool jpeg_attributes_held(const ImageMetadata& metadata);

// The JFIF density OpenImageIO writes for the attributes.
JfifDensity jfif_density(const ImageMetadata& metadata);

// The markers OpenImageIO writes after the JFIF one, in its order.
std::vector<JpegMarker> jpeg_markers(const ImageMetadata& metadata);

}  // namespace pupwave::cli
