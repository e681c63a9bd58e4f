// The OpenImageIO plugin (see tools/oiio_module.h): reading, describing and writing image
// files through OpenImageIO. Built as a shared module; the CLI loads it on first use.
#include <OpenImageIO/imageio.h>

#include <Imath/half.h>
#include <algorithm>
#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <vector>

#include "tools/image_io.h"
#include "tools/oiio_module.h"
#include "tools/strip_io.h"

namespace pupwave::cli {
namespace fs = std::filesystem;
using OIIO::TypeDesc;

namespace {

TypeDesc oiio_type(SampleType type) {
  switch (type) {
    case SampleType::u8: return TypeDesc::UINT8;
    case SampleType::u16: return TypeDesc::UINT16;
    case SampleType::f16: return TypeDesc::HALF;
    case SampleType::f32: return TypeDesc::FLOAT;
  }
  return TypeDesc::UNKNOWN;
}

// Maps a file's sample format to ours; formats we cannot hold exactly are refused.
SampleType sample_type_of(const OIIO::ImageSpec& spec, const fs::path& path) {
  TypeDesc widest = spec.format;
  for (const TypeDesc& t : spec.channelformats)
    if (t.size() > widest.size() || (t.is_floating_point() && !widest.is_floating_point())) widest = t;
  switch (widest.basetype) {
    case TypeDesc::UINT8: return SampleType::u8;
    case TypeDesc::UINT16: return SampleType::u16;
    case TypeDesc::HALF: return SampleType::f16;
    case TypeDesc::FLOAT: return SampleType::f32;
    default:
      throw std::runtime_error("cannot read " + path.string() + ": unsupported sample type " +
                               std::string(widest.c_str()) + " (supported: uint8, uint16, half, float)");
  }
}

std::unique_ptr<OIIO::ImageInput> open_input(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw std::runtime_error("cannot read " + path.string() + ": no such file");
  if (fs::is_directory(path, ec))
    throw std::runtime_error("cannot read " + path.string() + ": it is a directory");
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // keep alpha as stored: no premultiplication
  auto in = OIIO::ImageInput::open(path.string(), &config);
  if (!in) {
    std::string why = OIIO::geterror();
    if (why.empty()) why = "not an image file in a supported format";
    throw std::runtime_error("cannot read " + path.string() + ": " + why);
  }
  return in;
}

void check_image_spec(const OIIO::ImageSpec& spec, const fs::path& path) {
  const std::string name = path.string();
  if (spec.width <= 0 || spec.height <= 0) throw std::runtime_error("cannot read " + name + ": empty image");
  if (spec.depth > 1) throw std::runtime_error("cannot read " + name + ": 3-D images are not supported");
  if (spec.nchannels < 1 || spec.nchannels > kMaxImageChannels)
    throw std::runtime_error("cannot read " + name + ": " + std::to_string(spec.nchannels) +
                             " channels (1 to " + std::to_string(kMaxImageChannels) + " supported)");
  // OpenImageIO turns CMYK into RGB on read; that would silently drop the file's colours.
  const bool cmyk = spec.get_int_attribute("tiff:PhotometricInterpretation", 0) == 5 ||
                    spec.get_string_attribute("tiff:ColorSpace") == "CMYK" ||
                    spec.get_string_attribute("jpeg:ColorSpace") == "CMYK";
  if (cmyk)
    throw std::runtime_error("cannot read " + name +
                             ": CMYK images are not supported (convert to RGB first, e.g. with oiiotool)");
  const auto samples = std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels);
  if (samples > kMaxImageSamples) throw std::runtime_error("cannot read " + name + ": image too large");
}

// Copies interleaved samples of type T into the strip's planes.
template <class T>
void deinterleave(const T* src, Image& strip) {
  const std::size_t n = strip.plane_size(), c = strip.channels;
  for (std::size_t ch = 0; ch < c; ++ch) {
    float* dst = strip.plane(ch);
    for (std::size_t i = 0; i < n; ++i) dst[i] = static_cast<float>(src[i * c + ch]);
  }
}

// Channel names, windows and (for EXR files) scalar string/int/float attributes.
ImageMetadata metadata_of(const OIIO::ImageSpec& spec, const std::string& format) {
  ImageMetadata m;
  std::vector<std::string> names(spec.channelnames.begin(), spec.channelnames.end());
  if (names.size() == std::size_t(spec.nchannels) && names != default_channel_names(names.size()))
    m.channel_names = names;
  m.x = spec.x;
  m.y = spec.y;
  if (spec.full_x != 0 || spec.full_y != 0 || spec.full_width != spec.width ||
      spec.full_height != spec.height) {
    m.full_x = spec.full_x;
    m.full_y = spec.full_y;
    m.full_width = std::uint32_t(std::max(spec.full_width, 0));
    m.full_height = std::uint32_t(std::max(spec.full_height, 0));
  }
  if (format != "openexr") return m;
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    const std::string name = p.name().string();
    if (is_encoding_attribute(name)) continue;
    // OpenEXR writes screenWindowCenter (0, 0) into every file by default: nothing is lost.
    if (name == "screenWindowCenter" && p.type() == TypeDesc(TypeDesc::FLOAT, TypeDesc::VEC2) &&
        static_cast<const float*>(p.data())[0] == 0.0f && static_cast<const float*>(p.data())[1] == 0.0f)
      continue;
    if (p.nvalues() != 1) {
      m.not_kept.push_back(name + " (" + p.type().c_str() + " x " + std::to_string(p.nvalues()) + ")");
      continue;
    }
    ImageAttribute a;
    a.name = name;
    const TypeDesc t = p.type();
    if (t == OIIO::TypeString) {
      a.kind = ImageAttribute::Kind::string;
      a.text = p.get_string();
    } else if (t == OIIO::TypeInt || t == OIIO::TypeUInt) {
      a.kind = ImageAttribute::Kind::integer;
      a.integer = p.get_int();
    } else if (t == OIIO::TypeFloat || t == TypeDesc::DOUBLE || t == TypeDesc::HALF) {
      a.kind = ImageAttribute::Kind::real;
      a.real = p.get_float();
    } else {
      m.not_kept.push_back(name + " (" + t.c_str() + ")");  // vectors, matrices, timecodes (README)
      continue;
    }
    m.attributes.push_back(std::move(a));
  }
  return m;
}

void apply_metadata(const ImageMetadata& m, OIIO::ImageSpec& spec) {
  spec.x = m.x;
  spec.y = m.y;
  if (m.full_width > 0 && m.full_height > 0) {
    spec.full_x = m.full_x;
    spec.full_y = m.full_y;
    spec.full_width = int(m.full_width);
    spec.full_height = int(m.full_height);
  } else {
    spec.full_x = m.x;
    spec.full_y = m.y;
  }
  for (const ImageAttribute& a : m.attributes) {
    switch (a.kind) {
      case ImageAttribute::Kind::string: spec.attribute(a.name, a.text); break;
      case ImageAttribute::Kind::integer: spec.attribute(a.name, int(a.integer)); break;
      case ImageAttribute::Kind::real: spec.attribute(a.name, float(a.real)); break;
    }
  }
}

std::string format_name_for(const fs::path& path) {
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) {
    (void)OIIO::geterror();
    throw std::runtime_error("cannot write " + path.string() + ": unsupported image format '" +
                             path.extension().string() + "'");
  }
  return out->format_name();
}

OIIO::ImageSpec output_spec(const ImageShape& shape, const ImageMetadata& metadata,
                            const std::string& format) {
  OIIO::ImageSpec spec(int(shape.width), int(shape.height), int(shape.channels), oiio_type(shape.type));
  const auto& given = metadata.channel_names;
  const auto names = given.size() == shape.channels ? given : default_channel_names(shape.channels);
  spec.channelnames.assign(names.begin(), names.end());
  spec.alpha_channel = -1;
  for (std::size_t c = 0; c < names.size(); ++c)
    if (names[c] == "A") spec.alpha_channel = int(c);
  apply_metadata(metadata, spec);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // our alpha is straight: the writer must not divide
  if (format == "jpeg") spec.attribute("Compression", "jpeg:95");  // TIFF would read it too
  return spec;
}

// Rows read or written through OpenImageIO at a time: the interleaved buffer stays small.
constexpr std::size_t kRows = 64;

// Writes `strip` as rows [y0, y0 + strip.height) of the image open in `out` (spec `spec`),
// interleaving kRows rows at a time.
template <class T>
void write_strip_as(OIIO::ImageOutput& out, const OIIO::ImageSpec& spec, const Image& strip, std::size_t y0,
                    const fs::path& tmp) {
  const std::size_t w = strip.width, c = strip.channels;
  std::vector<T> buffer(std::min(kRows, strip.height) * w * c);
  for (std::size_t r0 = 0; r0 < strip.height; r0 += kRows) {
    const std::size_t r1 = std::min(strip.height, r0 + kRows);
    for (std::size_t ch = 0; ch < c; ++ch) {
      const float* src = strip.plane(ch) + r0 * w;
      for (std::size_t i = 0; i < (r1 - r0) * w; ++i) buffer[i * c + ch] = static_cast<T>(src[i]);
    }
    const int y = spec.y + int(y0 + r0);
    if (!out.write_scanlines(y, y + int(r1 - r0), 0, oiio_type(strip.type), buffer.data()))
      throw std::runtime_error("cannot write " + tmp.string() + ": " + out.geterror());
  }
}

void write_strip(OIIO::ImageOutput& out, const OIIO::ImageSpec& spec, const Image& strip, std::size_t y0,
                 const fs::path& tmp) {
  switch (strip.type) {
    case SampleType::u8: return write_strip_as<std::uint8_t>(out, spec, strip, y0, tmp);
    case SampleType::u16: return write_strip_as<std::uint16_t>(out, spec, strip, y0, tmp);
    case SampleType::f16: return write_strip_as<Imath::half>(out, spec, strip, y0, tmp);
    case SampleType::f32: return write_strip_as<float>(out, spec, strip, y0, tmp);
  }
}

// Rows of a file through OpenImageIO: a scanline file is read a strip at a time; a tiled one is
// read whole on the first call (its tiles cross strips), in its own sample type.
class OiioRows final : public ImageRowReader {
 public:
  explicit OiioRows(const fs::path& path) : path_(path), in_(open_input(path)), spec_(in_->spec()) {
    check_image_spec(spec_, path);
    type_ = sample_type_of(spec_, path);
    metadata_ = metadata_of(spec_, in_->format_name());
  }

  std::size_t width() const override { return std::size_t(spec_.width); }
  std::size_t height() const override { return std::size_t(spec_.height); }
  std::size_t channels() const override { return std::size_t(spec_.nchannels); }
  SampleType type() const override { return type_; }
  const ImageMetadata& metadata() const override { return metadata_; }

  Image next(std::size_t rows) override {
    const std::size_t y0 = next_row_, y1 = std::min(height(), y0 + std::max<std::size_t>(rows, 1));
    next_row_ = y1;
    Image strip(width(), y1 - y0, channels(), type_);
    if (y1 == y0) return strip;
    const std::size_t row_bytes = width() * channels() * oiio_type(type_).size();
    const std::byte* src = nullptr;
    if (spec_.tile_width > 0) {
      if (whole_.empty()) {
        whole_.resize(height() * row_bytes);
        if (!in_->read_image(0, 0, 0, int(channels()), oiio_type(type_), whole_.data())) fail();
      }
      src = whole_.data() + y0 * row_bytes;
    } else {
      buffer_.resize((y1 - y0) * row_bytes);
      if (!in_->read_scanlines(0, 0, spec_.y + int(y0), spec_.y + int(y1), 0, 0, int(channels()),
                               oiio_type(type_), buffer_.data()))
        fail();
      src = buffer_.data();
    }
    switch (type_) {
      case SampleType::u8: deinterleave(reinterpret_cast<const std::uint8_t*>(src), strip); break;
      case SampleType::u16: deinterleave(reinterpret_cast<const std::uint16_t*>(src), strip); break;
      case SampleType::f16: deinterleave(reinterpret_cast<const Imath::half*>(src), strip); break;
      case SampleType::f32: deinterleave(reinterpret_cast<const float*>(src), strip); break;
    }
    return strip;
  }

 private:
  [[noreturn]] void fail() {
    throw std::runtime_error("cannot read " + path_.string() + ": " + in_->geterror());
  }

  fs::path path_;
  std::unique_ptr<OIIO::ImageInput> in_;
  OIIO::ImageSpec spec_;
  SampleType type_ = SampleType::u8;
  ImageMetadata metadata_;
  std::size_t next_row_ = 0;
  std::vector<std::byte> buffer_;  // the strip's interleaved samples
  std::vector<std::byte> whole_;   // a tiled file's interleaved samples
};

std::unique_ptr<ImageRowReader> open_rows(const fs::path& path) { return std::make_unique<OiioRows>(path); }

Image read(const fs::path& path) {
  OiioRows rows(path);
  Image image(rows.width(), rows.height(), rows.channels(), rows.type());
  for (std::size_t y0 = 0; y0 < image.height;) {
    const Image strip = rows.next(kRows);
    for (std::size_t c = 0; c < image.channels; ++c)
      std::copy_n(strip.plane(c), strip.plane_size(), image.plane(c) + y0 * image.width);
    y0 += strip.height;
  }
  image.metadata = rows.metadata();
  return image;
}

std::string describe(const fs::path& path) {
  auto in = open_input(path);
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<std::string> names;
  for (int c = 0; c < spec.nchannels; ++c) names.push_back(spec.channel_name(c));
  return describe_image(path, in->format_name(), std::size_t(spec.width), std::size_t(spec.height), names,
                        spec.format.c_str(), spec.alpha_channel, metadata_of(spec, in->format_name()),
                        spec.depth);
}

std::unique_ptr<OIIO::ImageOutput> open_output(const ImageShape& shape, const ImageMetadata& metadata,
                                               const fs::path& path, const fs::path& tmp,
                                               OIIO::ImageSpec& spec) {
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) throw std::runtime_error("cannot write " + path.string() + ": " + OIIO::geterror());
  spec = output_spec(shape, metadata, out->format_name());
  if (!out->open(tmp.string(), spec))
    throw std::runtime_error("cannot write " + path.string() + ": " + out->geterror());
  return out;
}

void close_output(OIIO::ImageOutput& out, const fs::path& path) {
  if (!out.close()) throw std::runtime_error("cannot write " + path.string() + ": " + out.geterror());
}

void write(const Image& stored, const fs::path& path, const fs::path& tmp) {
  OIIO::ImageSpec spec;
  auto out = open_output(ImageShape{stored.width, stored.height, stored.channels, stored.type},
                         stored.metadata, path, tmp, spec);
  write_strip(*out, spec, stored, 0, tmp);
  close_output(*out, path);
}

void write_rows(const ImageShape& shape, const ImageMetadata& metadata, const fs::path& path,
                const fs::path& tmp, const std::function<Image()>& next_strip) {
  OIIO::ImageSpec spec;
  auto out = open_output(shape, metadata, path, tmp, spec);
  for (std::size_t y0 = 0; y0 < shape.height;) {
    const Image strip = next_strip();
    if (strip.height == 0 || strip.width != shape.width || strip.channels != shape.channels ||
        strip.type != shape.type || y0 + strip.height > shape.height)
      throw std::runtime_error("write_rows: a strip does not fit the image");
    write_strip(*out, spec, strip, y0, tmp);
    y0 += strip.height;
  }
  close_output(*out, path);
}

const OiioModule kModule{read, describe, format_name_for, write, open_rows, write_rows};

}  // namespace
}  // namespace pupwave::cli

extern "C" const pupwave::cli::OiioModule* pupwave_oiio_module() { return &pupwave::cli::kModule; }
