#include "tools/exr_io.h"

#include <Iex.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfEnvmapAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVecAttribute.h>
#include <OpenEXR/ImfVersion.h>

#include <Imath/half.h>
#include <strings.h>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "tools/atomic_file.h"
#include "tools/strip_io.h"

namespace pupwave::cli {
namespace fs = std::filesystem;
namespace {

bool iequals(const std::string& a, const std::string& b) { return strcasecmp(a.c_str(), b.c_str()) == 0; }

// OpenImageIO's names for the EXR header attributes it renames; "" for those it skips (the
// channels, windows and compression are read as such; the rest say nothing of the image).
const std::map<std::string, std::string>& oiio_attribute_names() {
  static const std::map<std::string, std::string> names = {
      {"cameraTransform", "worldtocamera"},
      {"capDate", "DateTime"},
      {"comments", "ImageDescription"},
      {"owner", "Copyright"},
      {"pixelAspectRatio", "PixelAspectRatio"},
      {"xDensity", "XResolution"},
      {"expTime", "ExposureTime"},
      {"aperture", "FNumber"},
      {"chunkCount", "openexr:chunkCount"},
      {"maxSamplesPerPixel", "openexr:maxSamplesPerPixel"},
      {"dwaCompressionLevel", "openexr:dwaCompressionLevel"},
      {"channels", ""},
      {"compression", ""},
      {"dataWindow", ""},
      {"displayWindow", ""},
      {"envmap", ""},
      {"tiledesc", ""},
      {"tiles", ""},
      {"openexr:lineOrder", ""},
      {"type", ""}};
  return names;
}

// Attribute types OpenImageIO reads as vectors, matrices and the like, which compress reports as
// not kept: files with them are left to OpenImageIO, whose names for those types are its own.
bool is_compound_type(const std::string& type) {
  static const std::set<std::string> types = {
      "m33f", "m44f", "v3f",  "v3i",   "v2f",   "v2i",      "stringvector", "floatvector",    "v2d",
      "v3d",  "m33d", "m44d", "box2i", "box2f", "timecode", "keycode",      "chromaticities", "rational"};
  return types.count(type) != 0;
}

// OpenImageIO's name for the compression, which it records as an attribute.
const char* compression_name(Imf::Compression c) {
  switch (c) {
    case Imf::NO_COMPRESSION: return "none";
    case Imf::RLE_COMPRESSION: return "rle";
    case Imf::ZIPS_COMPRESSION: return "zips";
    case Imf::ZIP_COMPRESSION: return "zip";
    case Imf::PIZ_COMPRESSION: return "piz";
    case Imf::PXR24_COMPRESSION: return "pxr24";
    case Imf::B44_COMPRESSION: return "b44";
    case Imf::B44A_COMPRESSION: return "b44a";
    case Imf::DWAA_COMPRESSION: return "dwaa";
    case Imf::DWAB_COMPRESSION: return "dwab";
    default: return nullptr;
  }
}

// The attribute list as OpenImageIO's reader builds it: a name set again (in any case) takes the
// first one's place. Entries marked not kept are those compress drops.
class OiioAttributes {
 public:
  void set(ImageAttribute a, bool kept = true) {
    for (Entry& e : entries_)
      if (iequals(e.attribute.name, a.name)) {
        e = Entry{std::move(a), kept};
        return;
      }
    entries_.push_back(Entry{std::move(a), kept});
  }
  void set_string(const std::string& name, const std::string& text) {
    set(ImageAttribute{name, ImageAttribute::Kind::string, text, 0, 0.0});
  }
  void set_real(const std::string& name, float value) {
    set(ImageAttribute{name, ImageAttribute::Kind::real, {}, 0, double(value)});
  }
  // OpenImageIO's get_float_attribute: a number's value, else 0.
  float get_float(const std::string& name) const {
    for (const Entry& e : entries_) {
      if (!iequals(e.attribute.name, name)) continue;
      if (e.attribute.kind == ImageAttribute::Kind::real) return float(e.attribute.real);
      if (e.attribute.kind == ImageAttribute::Kind::integer) return float(e.attribute.integer);
    }
    return 0.0f;
  }
  // What compress keeps: the image's attributes, not the encoding's.
  std::vector<ImageAttribute> kept() const {
    std::vector<ImageAttribute> out;
    for (const Entry& e : entries_)
      if (e.kept && !is_encoding_attribute(e.attribute.name)) out.push_back(e.attribute);
    return out;
  }

 private:
  struct Entry {
    ImageAttribute attribute;
    bool kept = true;
  };
  std::vector<Entry> entries_;
};

// Takes one header attribute as OpenImageIO does; false for a type it reads as a compound value.
bool take_attribute(const Imf::Header& header, const char* name, const Imf::Attribute& attribute,
                    OiioAttributes& out) {
  const auto renamed = oiio_attribute_names().find(name);
  const std::string oname = renamed != oiio_attribute_names().end() ? renamed->second : name;
  if (oname.empty()) return true;
  const std::string type = attribute.typeName();
  if (const auto* s = header.findTypedAttribute<Imf::StringAttribute>(name)) {
    if (!s->value().empty()) out.set_string(oname, s->value());  // OpenImageIO skips empty strings
  } else if (const auto* i = header.findTypedAttribute<Imf::IntAttribute>(name)) {
    out.set(ImageAttribute{oname, ImageAttribute::Kind::integer, {}, i->value(), 0.0});
  } else if (const auto* f = header.findTypedAttribute<Imf::FloatAttribute>(name)) {
    out.set_real(oname, f->value());
  } else if (const auto* d = header.findTypedAttribute<Imf::DoubleAttribute>(name)) {
    out.set_real(oname, float(d->value()));  // OpenImageIO's get_float
  } else if (const auto* v = header.findTypedAttribute<Imf::V2fAttribute>(name);
             v && oname == "screenWindowCenter" && v->value() == Imath::V2f(0.0f, 0.0f)) {
    // Every EXR file has it (the library's default): compress drops it, keeping its place.
    out.set(ImageAttribute{oname, ImageAttribute::Kind::real, {}, 0, 0.0}, false);
  } else if (is_compound_type(type)) {
    return false;
  }
  return true;  // other types (preview, lineOrder, opaque) OpenImageIO ignores
}

// The header's attributes as OpenImageIO's reader gives them; nullopt when one is of a type left
// to OpenImageIO.
std::optional<std::vector<ImageAttribute>> oiio_attributes(const Imf::Header& header) {
  OiioAttributes attributes;
  // Set by OpenImageIO before the header's own, so a header attribute of the same name takes
  // their places.
  attributes.set_string("oiio:ColorSpace", "Linear");
  if (const char* comp = compression_name(header.compression())) attributes.set_string("compression", comp);
  for (auto it = header.begin(); it != header.end(); ++it)
    if (!take_attribute(header, it.name(), it.attribute(), attributes)) return std::nullopt;
  // OpenImageIO derives the vertical resolution from xDensity and the pixel aspect ratio.
  if (const float xdensity = attributes.get_float("XResolution"); xdensity != 0.0f) {
    const float aspect = attributes.get_float("PixelAspectRatio");
    attributes.set_real("YResolution", xdensity * (aspect != 0.0f ? aspect : 1.0f));
    attributes.set_string("ResolutionUnit", "in");
  }
  return attributes.kept();
}

// OpenImageIO's rank of a channel name's suffix within its layer (R, G, B, then Y, A, depth...);
// with `xyz` (a layer holding X and Y or Z) X, Y, Z rank after B.
int channel_rank(const std::string& suffix, bool xyz) {
  static const char* plain[] = {"R",     "Red", "G",  "Green", "B",  "Blue", "Y",  "real", "imag",  "A",
                                "Alpha", "AR",  "RA", "AG",    "GA", "AB",   "BA", "Z",    "Depth", "Zback"};
  static const char* position[] = {"R",  "Red", "G",    "Green", "B",  "Blue",  "X",
                                   "Y",  "Z",   "real", "imag",  "A",  "Alpha", "AR",
                                   "RA", "AG",  "GA",   "AB",    "BA", "Depth", "Zback"};
  const auto find = [&](const auto& names) {
    for (std::size_t i = 0; i < std::size(names); ++i)
      if (iequals(suffix, names[i])) return int(i);
    return 10000;
  };
  return xyz ? find(position) : find(plain);
}

// The file's channel names in OpenImageIO's order: by layer (the name up to its last dot), then
// by channel_rank, then by name.
std::vector<std::string> oiio_channel_order(const Imf::ChannelList& list) {
  struct Channel {
    std::string name, layer, suffix;
    int rank = 0;
  };
  std::vector<Channel> channels;
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string name = it.name();
    const std::size_t dot = name.find_last_of('.');
    const std::size_t cut = dot == std::string::npos ? 0 : dot + 1;
    channels.push_back({name, name.substr(0, cut), name.substr(cut), 0});
  }
  const auto layer_has = [&](const std::string& layer, const char* suffix) {
    return std::any_of(channels.begin(), channels.end(),
                       [&](const Channel& c) { return c.layer == layer && iequals(c.suffix, suffix); });
  };
  for (Channel& c : channels) {
    const bool xyz = layer_has(c.layer, "X") && (layer_has(c.layer, "Y") || layer_has(c.layer, "Z"));
    c.rank = channel_rank(c.suffix, xyz);
  }
  std::sort(channels.begin(), channels.end(), [](const Channel& a, const Channel& b) {
    return std::tie(a.layer, a.rank, a.suffix) < std::tie(b.layer, b.rank, b.suffix);
  });
  std::vector<std::string> names;
  for (const Channel& c : channels) names.push_back(c.name);
  return names;
}

// Whether the file starts with OpenEXR's magic number.
bool has_exr_magic(const fs::path& path) {
  char magic[4] = {};
  std::ifstream in(path, std::ios::binary);
  return in.read(magic, sizeof magic) && Imf::isImfMagic(magic);
}

// The sample type of the file's channels (float if any is), or nullopt for a channel OpenImageIO
// refuses or reads otherwise (uint, subsampled).
std::optional<SampleType> exr_sample_type(const Imf::ChannelList& list) {
  SampleType type = SampleType::f16;
  for (auto it = list.begin(); it != list.end(); ++it) {
    const Imf::Channel& c = it.channel();
    if (c.type == Imf::UINT || c.xSampling != 1 || c.ySampling != 1) return std::nullopt;
    if (c.type == Imf::FLOAT) type = SampleType::f32;
  }
  return type;
}

// Whether the file is one part of one flat level (no mipmaps, no environment map).
bool is_single_flat_image(const Imf::InputFile& file) {
  const Imf::Header& header = file.header();
  if (Imf::isMultiPart(file.version()) || Imf::isNonImage(file.version()) ||
      header.find("envmap") != header.end())
    return false;
  if (header.hasType() && header.type() != Imf::SCANLINEIMAGE && header.type() != Imf::TILEDIMAGE)
    return false;
  return !header.hasTileDescription() || header.tileDescription().mode == Imf::ONE_LEVEL;
}

// The rows of an OpenEXR file, a strip at a time, each channel converted to float by the library
// straight into the strip's planes.
class ExrRows final : public StripReader {
 public:
  // Null when the file is not an EXR of the kinds read here; throws for a corrupt one.
  static std::unique_ptr<ExrRows> open(const fs::path& path) {
    if (!is_readable_file(path) || !has_exr_magic(path)) return nullptr;
    try {
      std::unique_ptr<ExrRows> rows(new ExrRows(path));
      return rows->take_header() ? std::move(rows) : nullptr;
    } catch (const Iex::BaseExc& e) {
      throw_read_error(path, e.what());
    }
  }

 protected:
  void read_strip(std::size_t y0, Image& strip) override {
    const int top = window_.min.y + int(y0);
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < channels_; ++c)
      frame.insert(names_[c], Imf::Slice::Make(Imf::FLOAT, strip.plane(c), Imath::V2i(window_.min.x, top),
                                               std::int64_t(width_), std::int64_t(strip.height)));
    try {
      file_.setFrameBuffer(frame);
      file_.readPixels(top, top + int(strip.height) - 1);
    } catch (const Iex::BaseExc& e) {
      throw_read_error(path_, e.what());
    }
  }

 private:
  explicit ExrRows(const fs::path& path) : path_(path), file_(path.c_str()) {}

  // Takes the header; false for a kind of file left to OpenImageIO.
  bool take_header() {
    const Imf::Header& header = file_.header();
    const auto type = exr_sample_type(header.channels());
    if (!type || !is_single_flat_image(file_)) return false;
    names_ = oiio_channel_order(header.channels());
    if (names_.empty() || names_.size() > std::size_t(kMaxImageChannels))
      return false;  // OpenImageIO says why
    auto attributes = oiio_attributes(header);
    if (!attributes) return false;
    window_ = header.dataWindow();
    const Imath::Box2i display = header.displayWindow();
    width_ = std::size_t(std::int64_t(window_.max.x) - window_.min.x + 1);
    height_ = std::size_t(std::int64_t(window_.max.y) - window_.min.y + 1);
    channels_ = names_.size();
    type_ = *type;
    check_image_samples(path_, width_, height_, channels_);
    metadata_.channel_names = kept_channel_names(names_);
    metadata_.attributes = std::move(*attributes);
    metadata_.x = window_.min.x;
    metadata_.y = window_.min.y;
    const std::int64_t full_width = std::int64_t(display.max.x) - display.min.x + 1;
    const std::int64_t full_height = std::int64_t(display.max.y) - display.min.y + 1;
    if (display.min.x != 0 || display.min.y != 0 || full_width != std::int64_t(width_) ||
        full_height != std::int64_t(height_)) {
      metadata_.full_x = display.min.x;
      metadata_.full_y = display.min.y;
      metadata_.full_width = std::uint32_t(std::max<std::int64_t>(full_width, 0));
      metadata_.full_height = std::uint32_t(std::max<std::int64_t>(full_height, 0));
    }
    return true;
  }

  fs::path path_;
  Imf::InputFile file_;
  Imath::Box2i window_;
  std::vector<std::string> names_;  // the file's channels in the order of the image's planes
};

// The EXR name OpenImageIO's writer gives an attribute of the image, for those written here as
// it writes them (renamed standard ones, and plain names stored as they are); empty for the
// others (its own, other formats', EXR's reserved names, those it converts), which leave the
// whole file to OpenImageIO.
std::string exr_attribute_name(const ImageAttribute& a) {
  using K = ImageAttribute::Kind;
  if (a.name == "DateTime") return a.kind == K::string ? "capDate" : "";
  if (a.name == "PixelAspectRatio" || a.name == "screenWindowWidth")
    return a.kind == K::string ? "" : a.name == "PixelAspectRatio" ? "pixelAspectRatio" : a.name;
  static const std::set<std::string> special = {
      // OpenImageIO renames, drops or derives these (and their EXR names)
      "worldtocamera", "worldtondc", "worldtoscreen", "capdate", "imagedescription", "description",
      "comments", "copyright", "owner", "pixelaspectratio", "xresolution", "yresolution", "resolutionunit",
      "xdensity", "exposuretime", "exptime", "fnumber", "aperture", "name", "dwacompressionlevel", "timecode",
      "keycode", "planarconfig", "type", "tiles", "chunkcount", "maxsamplesperpixel", "textureformat",
      "datetime",
      // EXR's own header fields
      "channels", "compression", "datawindow", "displaywindow", "lineorder", "screenwindowcenter",
      "screenwindowwidth", "envmap", "tiledesc", "version"};
  std::string lower = a.name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  const std::size_t colon = lower.find(':');
  if (lower.empty() || special.count(lower) ||
      (colon != std::string::npos && lower.compare(0, colon, "exif") != 0))
    return "";
  return a.name;
}

// Whether every attribute is one exr_attribute_name names.
bool exr_attributes_writable(const std::vector<ImageAttribute>& attributes) {
  return std::all_of(attributes.begin(), attributes.end(),
                     [](const ImageAttribute& a) { return !exr_attribute_name(a).empty(); });
}

// Stores an attribute as OpenImageIO's writer does: strings as strings, integers as int (as float
// where EXR's attribute is a float), reals as float.
void insert_exr_attribute(Imf::Header& header, const ImageAttribute& a) {
  const std::string name = exr_attribute_name(a);
  const bool as_float = name == "pixelAspectRatio" || name == "screenWindowWidth";
  switch (a.kind) {
    case ImageAttribute::Kind::string: header.insert(name, Imf::StringAttribute(a.text)); break;
    case ImageAttribute::Kind::integer:
      if (as_float)
        header.insert(name, Imf::FloatAttribute(float(a.integer)));
      else
        header.insert(name, Imf::IntAttribute(int(a.integer)));
      break;
    case ImageAttribute::Kind::real: header.insert(name, Imf::FloatAttribute(float(a.real))); break;
  }
}

// The channel names written: the image's, else OpenImageIO's defaults.
std::vector<std::string> written_channel_names(std::size_t channels, const ImageMetadata& m) {
  return m.channel_names.size() == channels ? m.channel_names : default_channel_names(channels);
}

// The header OpenImageIO writes for such an image: its windows and channel names, ZIP level 4.
Imf::Header exr_header(std::size_t width, std::size_t height, std::size_t channels, SampleType type,
                       const ImageMetadata& m) {
  const Imath::Box2i data(Imath::V2i(m.x, m.y), Imath::V2i(m.x + int(width) - 1, m.y + int(height) - 1));
  Imath::Box2i display = data;
  if (m.full_width > 0 && m.full_height > 0)
    display = Imath::Box2i(Imath::V2i(m.full_x, m.full_y),
                           Imath::V2i(m.full_x + int(m.full_width) - 1, m.full_y + int(m.full_height) - 1));
  Imf::Header header(display, data);
  header.compression() = Imf::ZIP_COMPRESSION;
  header.zipCompressionLevel() = 4;
  const Imf::PixelType pixel = type == SampleType::f16 ? Imf::HALF : Imf::FLOAT;
  for (const std::string& name : written_channel_names(channels, m))
    header.channels().insert(name, Imf::Channel(pixel));
  for (const ImageAttribute& a : m.attributes) insert_exr_attribute(header, a);
  return header;
}

// An OpenEXR file being written a strip at a time: the library's converter reads the strip's
// float planes and stores the header's pixel type.
class ExrWriter {
 public:
  ExrWriter(const fs::path& file, std::size_t width, std::size_t height, std::size_t channels,
            SampleType type, const ImageMetadata& metadata)
      : file_(file), names_(written_channel_names(channels, metadata)) {
    if (is_integer(type) || !exr_attributes_writable(metadata.attributes))
      throw std::invalid_argument("write_exr: needs half or float samples and attributes it can write");
    stream_.open(file, std::ios::binary | std::ios::trunc);
    if (!stream_) throw_write_error(file);
    guarded([&] {
      const Imf::Header header = exr_header(width, height, channels, type, metadata);
      origin_ = header.dataWindow().min;
      os_ = std::make_unique<Imf::StdOFStream>(stream_, file.c_str());
      out_ = std::make_unique<Imf::OutputFile>(*os_, header);
    });
  }

  // Appends the rows of `strip`. The library stores a channel only from a buffer of its own pixel
  // type: float planes are handed over as they are, half ones converted a few rows at a time.
  void put(const Image& strip) {
    if (strip.type == SampleType::f32) return write_rows(strip, 0, strip.height, Imf::FLOAT);
    constexpr std::size_t kRows = 64;
    for (std::size_t y0 = 0; y0 < strip.height; y0 += kRows)
      write_rows(strip, y0, std::min(strip.height, y0 + kRows), Imf::HALF);
  }

  // Ends the file (the library writes its table of line offsets then); throws if any of it could
  // not be written.
  void finish() {
    guarded([&] { out_.reset(); });
    errno = 0;
    stream_.close();
    if (!stream_) throw_write_error(file_);
  }

 private:
  // Writes rows [y0, y1) of `strip`: from its float planes, or through halves_ for half samples.
  void write_rows(const Image& strip, std::size_t y0, std::size_t y1, Imf::PixelType pixel) {
    const std::size_t n = (y1 - y0) * strip.width;
    if (pixel == Imf::HALF) {
      halves_.resize(n * strip.channels);
      for (std::size_t c = 0; c < strip.channels; ++c)
        std::copy_n(strip.plane(c) + y0 * strip.width, n, halves_.begin() + std::ptrdiff_t(c * n));
    }
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < strip.channels; ++c) {
      const void* plane = pixel == Imf::HALF ? static_cast<const void*>(halves_.data() + c * n)
                                             : static_cast<const void*>(strip.plane(c) + y0 * strip.width);
      frame.insert(names_[c], Imf::Slice::Make(pixel, plane, Imath::V2i(origin_.x, origin_.y + int(rows_)),
                                               std::int64_t(strip.width), std::int64_t(y1 - y0)));
    }
    guarded([&] {
      out_->setFrameBuffer(frame);
      out_->writePixels(int(y1 - y0));
    });
    rows_ += y1 - y0;
  }

  // Runs a library call, turning its exceptions into errors naming the file.
  template <class F>
  void guarded(const F& call) {
    try {
      call();
    } catch (const Iex::BaseExc& e) {
      throw_write_refusal(file_, e.what());
    }
  }

  fs::path file_;
  std::vector<std::string> names_;
  std::ofstream stream_;
  std::unique_ptr<Imf::StdOFStream> os_;
  std::unique_ptr<Imf::OutputFile> out_;  // declared after the streams it writes to
  Imath::V2i origin_;
  std::size_t rows_ = 0;             // rows written so far
  std::vector<Imath::half> halves_;  // a few rows of half samples, plane after plane
};

}  // namespace

bool has_exr_extension(const fs::path& path) { return has_extension(path, {".exr"}); }

std::unique_ptr<ImageRowReader> open_exr_rows(const fs::path& path) { return ExrRows::open(path); }

std::optional<Image> read_exr(const fs::path& path) { return read_whole(ExrRows::open(path)); }

bool exr_writable(const fs::path& path, SampleType type, const ImageMetadata& metadata) {
  return has_exr_extension(path) && !is_integer(type) && exr_attributes_writable(metadata.attributes);
}

void write_exr(const Image& image, const fs::path& file) {
  ExrWriter writer(file, image.width, image.height, image.channels, image.type, image.metadata);
  writer.put(image);
  writer.finish();
}

void write_exr_rows(const fs::path& file, std::size_t width, std::size_t height, std::size_t channels,
                    SampleType type, const ImageMetadata& metadata,
                    const std::function<Image()>& next_strip) {
  ExrWriter writer(file, width, height, channels, type, metadata);
  write_strips(writer, width, height, channels, type, next_strip, "write_exr_rows");
}

}  // namespace pupwave::cli
