#include "tools/strip_io.h"

#include <strings.h>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tools/atomic_file.h"

namespace pupwave::cli {
namespace fs = std::filesystem;

bool has_extension(const fs::path& path, std::initializer_list<std::string_view> extensions) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  return std::find(extensions.begin(), extensions.end(), ext) != extensions.end();
}

bool is_readable_file(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

void throw_read_error(const fs::path& path, const std::string& why) {
  throw std::runtime_error("cannot read " + path.string() + ": " + why);
}

void throw_write_refusal(const fs::path& path, const std::string& why) {
  throw std::runtime_error("cannot write " + path.string() + ": " + why);
}

void throw_write_failure(const fs::path& path, const char* library_message) {
  if (errno != 0) throw_write_error(path);
  throw_write_refusal(path, library_message);
}

void close_written_file(std::FILE*& file, const fs::path& path) {
  std::FILE* f = file;
  file = nullptr;
  if (std::fclose(f) != 0) throw_write_error(path);
}

bool is_encoding_attribute(const std::string& name) {
  return name.rfind("oiio:", 0) == 0 || name.rfind("openexr:", 0) == 0 || name == "compression" ||
         name == "planarconfig";
}

void check_image_samples(const fs::path& path, std::size_t width, std::size_t height, std::size_t channels) {
  if (width == 0 || height == 0) throw_read_error(path, "empty image");
  if (channels == 0 || width > kMaxImageSamples / height || width * height > kMaxImageSamples / channels)
    throw_read_error(path, "image too large");
}

std::vector<std::string> default_channel_names(std::size_t channels) {
  static const char* grey[] = {"Y", "A"};
  static const char* rgba[] = {"R", "G", "B", "A"};
  std::vector<std::string> names;
  for (std::size_t c = 0; c < channels; ++c)
    names.emplace_back(channels <= 2 ? grey[c] : c < 4 ? rgba[c] : "channel" + std::to_string(c));
  return names;
}

std::vector<std::string> kept_channel_names(std::vector<std::string> names) {
  if (names == default_channel_names(names.size())) names.clear();
  return names;
}

int alpha_channel_of(const std::vector<std::string>& channel_names) {
  for (std::size_t c = 0; c < channel_names.size(); ++c) {
    const std::string& name = channel_names[c];
    const std::size_t dot = name.find_last_of('.');
    const std::string suffix = dot == std::string::npos ? name : name.substr(dot + 1);
    if (strcasecmp(suffix.c_str(), "A") == 0 || strcasecmp(suffix.c_str(), "Alpha") == 0) return int(c);
  }
  return -1;
}

std::string describe_image(const fs::path& path, const std::string& format, std::size_t width,
                           std::size_t height, const std::vector<std::string>& channel_names,
                           const std::string& type, int alpha_channel, const ImageMetadata& m, int depth) {
  std::ostringstream s;
  const std::size_t n = channel_names.size();
  s << path.string() << ": " << format << " image, " << width << " x " << height << ", " << n << " channel"
    << (n == 1 ? "" : "s") << " (";
  for (std::size_t c = 0; c < n; ++c) s << (c ? "," : "") << channel_names[c];
  s << "), " << type;
  if (depth > 1) s << ", depth " << depth;
  if (alpha_channel >= 0) s << ", alpha in channel " << alpha_channel;
  if (m.x != 0 || m.y != 0) s << ", data window origin " << m.x << "," << m.y;
  if (m.full_width > 0)
    s << ", display window " << m.full_width << "x" << m.full_height << " at " << m.full_x << "," << m.full_y;
  if (!m.attributes.empty()) s << "\n  " << m.attributes.size() << " attribute(s) kept by compress:";
  for (std::size_t k = 0; k < m.attributes.size(); ++k) s << (k ? ", " : " ") << m.attributes[k].name;
  return s.str();
}

Image StripReader::next(std::size_t rows) {
  const std::size_t y0 = next_row_, y1 = std::min(height_, y0 + std::max<std::size_t>(rows, 1));
  next_row_ = y1;
  Image strip(width_, y1 - y0, channels_, type_);
  if (y1 > y0) read_strip(y0, strip);
  return strip;
}

std::optional<Image> read_whole(std::unique_ptr<ImageRowReader> rows) {
  if (!rows) return std::nullopt;
  Image image = rows->next(rows->height());
  image.metadata = rows->metadata();
  return image;
}

void for_each_strip(std::size_t width, std::size_t height, std::size_t channels, SampleType type,
                    const std::function<Image()>& next_strip, const std::function<void(const Image&)>& put,
                    const char* who) {
  for (std::size_t rows = 0; rows < height;) {
    const Image strip = next_strip();
    if (strip.height == 0 || strip.width != width || strip.channels != channels || strip.type != type ||
        rows + strip.height > height)
      throw std::runtime_error(std::string(who) + ": a strip does not fit the image");
    put(strip);
    rows += strip.height;
  }
}

template <class T>
void interleave_row(const Image& strip, std::size_t y, T* out) {
  const std::size_t c = strip.channels;
  for (std::size_t ch = 0; ch < c; ++ch) {
    const float* src = strip.plane(ch) + y * strip.width;
    for (std::size_t x = 0; x < strip.width; ++x) {
      if constexpr (std::is_integral_v<T>) {
        const float top = float(std::numeric_limits<T>::max());
        out[x * c + ch] = T(unsigned(std::clamp(src[x], 0.0f, top) + 0.5f));
      } else {
        out[x * c + ch] = T(src[x]);
      }
    }
  }
}

template void interleave_row<std::uint8_t>(const Image&, std::size_t, std::uint8_t*);
template void interleave_row<std::uint16_t>(const Image&, std::size_t, std::uint16_t*);
template void interleave_row<float>(const Image&, std::size_t, float*);

}  // namespace pupwave::cli
