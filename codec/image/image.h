#pragma once
// The plain in-memory image every layer exchanges: planar samples, no file-format knowledge.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pupwave {

// Sample type of the file an image came from (and is written back as).
enum class SampleType : std::uint8_t { u8 = 0, u16 = 1, f16 = 2, f32 = 3 };

std::string to_string(SampleType type);
// Bits per sample of the stored type (8, 16, 16, 32).
int bits_per_sample(SampleType type);
bool is_integer(SampleType type);
// Largest representable value for integer types (255, 65535); 1.0 for float types (nominal range).
double nominal_max(SampleType type);

// A named attribute of an image file kept through compression (EXR header attributes and the
// like): a string, an integer or a float.
struct ImageAttribute {
  enum class Kind : std::uint8_t { string = 0, integer = 1, real = 2 };
  std::string name;
  Kind kind = Kind::string;
  std::string text;          // Kind::string
  std::int64_t integer = 0;  // Kind::integer
  double real = 0.0;         // Kind::real

  bool operator==(const ImageAttribute&) const = default;
};

// What an image file says about its pixels besides the samples: channel names, the data
// window's origin and the display window (OpenEXR's dataWindow/displayWindow), attributes.
// Empty names / zero display size mean "not given" (the writer's defaults apply).
struct ImageMetadata {
  std::vector<std::string> channel_names;         // empty or one per channel
  std::int32_t x = 0, y = 0;                      // origin of the data window
  std::int32_t full_x = 0, full_y = 0;            // display window origin
  std::uint32_t full_width = 0, full_height = 0;  // display window size; 0: same as the data window
  std::vector<ImageAttribute> attributes;
  // Names (with their types) of attributes the reader found but the stream cannot hold (vectors,
  // matrices, timecodes); never stored, so the CLI can say what is not kept instead of dropping
  // it silently.
  std::vector<std::string> not_kept;

  bool empty() const {
    return channel_names.empty() && x == 0 && y == 0 && full_x == 0 && full_y == 0 && full_width == 0 &&
           full_height == 0 && attributes.empty();
  }
  bool operator==(const ImageMetadata& o) const {  // what the stream keeps (not not_kept)
    return channel_names == o.channel_names && x == o.x && y == o.y && full_x == o.full_x &&
           full_y == o.full_y && full_width == o.full_width && full_height == o.full_height &&
           attributes == o.attributes;
  }
};

// A planar image: channel c occupies samples[c*width*height, (c+1)*width*height), rows of
// `width` samples top to bottom. Every supported sample type is held exactly in float:
// integers up to 65535 and half floats are exact in binary32.
struct Image {
  std::size_t width = 0;
  std::size_t height = 0;
  std::size_t channels = 0;
  SampleType type = SampleType::u8;
  std::vector<float> samples;
  ImageMetadata metadata;

  Image() = default;
  Image(std::size_t w, std::size_t h, std::size_t c, SampleType t)
      : width(w), height(h), channels(c), type(t), samples(w * h * c, 0.0f) {}

  std::size_t plane_size() const { return width * height; }
  float* plane(std::size_t c) { return samples.data() + c * plane_size(); }
  const float* plane(std::size_t c) const { return samples.data() + c * plane_size(); }
  float& at(std::size_t c, std::size_t x, std::size_t y) { return plane(c)[y * width + x]; }
  float at(std::size_t c, std::size_t x, std::size_t y) const { return plane(c)[y * width + x]; }
};

}  // namespace pupwave
