#include "tools/tiff_io.h"

#include <tiffio.h>

#include <algorithm>
#include <cerrno>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "codec/image/image_view.h"
#include "tools/atomic_file.h"
#include "tools/strip_io.h"

namespace pupwave::cli {
namespace fs = std::filesystem;
namespace {

// libtiff's last error message for one open file (its handlers write here, not to stderr).
struct TiffMessage {
  char text[256] = "";
};

int on_tiff_error(TIFF*, void* user, const char* module, const char* format, va_list args) {
  auto* message = static_cast<TiffMessage*>(user);
  const int n = std::snprintf(message->text, sizeof message->text, "%s: ", module ? module : "libtiff");
  std::vsnprintf(message->text + n, sizeof message->text - std::size_t(n), format, args);
  return 1;  // handled: libtiff's default handler prints nothing
}

// Warnings (unknown tags and the like) are dropped, as OpenImageIO drops them.
int on_tiff_warning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

// Opens `path` ("r" or "w") with errors going to `message`; null when libtiff refuses.
TIFF* open_tiff(const fs::path& path, const char* mode, TiffMessage& message) {
  TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
  TIFFOpenOptionsSetErrorHandlerExtR(options, on_tiff_error, &message);
  TIFFOpenOptionsSetWarningHandlerExtR(options, on_tiff_warning, nullptr);
  TIFF* tif = TIFFOpenExt(path.c_str(), mode, options);
  TIFFOpenOptionsFree(options);
  return tif;
}

// Whether the file starts with a TIFF or BigTIFF signature.
bool has_tiff_magic(const fs::path& path) {
  unsigned char m[4] = {};
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(m), sizeof m)) return false;
  const bool intel = m[0] == 'I' && m[1] == 'I' && (m[2] == 42 || m[2] == 43) && m[3] == 0;
  const bool motorola = m[0] == 'M' && m[1] == 'M' && m[2] == 0 && (m[3] == 42 || m[3] == 43);
  return intel || motorola;
}

template <class T>
T tiff_field(TIFF* tif, ttag_t tag) {
  T value = 0;
  TIFFGetFieldDefaulted(tif, tag, &value);
  return value;
}

// The sample type of the file's samples, or nullopt for a kind left to OpenImageIO.
std::optional<SampleType> tiff_sample_type(TIFF* tif) {
  const auto bits = tiff_field<std::uint16_t>(tif, TIFFTAG_BITSPERSAMPLE);
  const auto format = tiff_field<std::uint16_t>(tif, TIFFTAG_SAMPLEFORMAT);
  if (format == SAMPLEFORMAT_UINT && bits == 8) return SampleType::u8;
  if (format == SAMPLEFORMAT_UINT && bits == 16) return SampleType::u16;
  if (format == SAMPLEFORMAT_IEEEFP && bits == 32) return SampleType::f32;
  return std::nullopt;
}

// The photometric interpretation, with OpenImageIO's default where the tag is missing.
std::uint16_t tiff_photometric(TIFF* tif, std::size_t channels) {
  std::uint16_t photometric = channels == 1 ? PHOTOMETRIC_MINISBLACK : PHOTOMETRIC_RGB;
  TIFFGetField(tif, TIFFTAG_PHOTOMETRIC, &photometric);
  return photometric;
}

// Whether the file's layout is read here: contiguous strips of grey or RGB samples without JPEG
// compression, and no tag that moves or renames what OpenImageIO reads (position, display size,
// texture format).
bool tiff_layout_read_here(TIFF* tif, std::size_t channels) {
  const std::uint16_t photometric = tiff_photometric(tif, channels);
  const auto compression = tiff_field<std::uint16_t>(tif, TIFFTAG_COMPRESSION);
  const auto planar = tiff_field<std::uint16_t>(tif, TIFFTAG_PLANARCONFIG);
  float position = 0.0f;
  std::uint32_t full_width = 0;
  char* texture_format = nullptr;
  const bool moved = (TIFFGetField(tif, TIFFTAG_XPOSITION, &position) && position != 0.0f) ||
                     (TIFFGetField(tif, TIFFTAG_YPOSITION, &position) && position != 0.0f) ||
                     TIFFGetField(tif, TIFFTAG_PIXAR_IMAGEFULLWIDTH, &full_width) ||
                     TIFFGetField(tif, TIFFTAG_PIXAR_TEXTUREFORMAT, &texture_format);
  return channels >= 1 && channels <= 4 && !TIFFIsTiled(tif) && !moved &&
         (planar == PLANARCONFIG_CONTIG || channels == 1) && compression != COMPRESSION_JPEG &&
         compression != COMPRESSION_OJPEG &&
         (photometric == PHOTOMETRIC_MINISBLACK || (photometric == PHOTOMETRIC_RGB && channels >= 3));
}

// OpenImageIO's channel names for the file: R, G, B, A, channelN (Y alone), then alpha and
// other extra samples as ExtraSamples says.
std::vector<std::string> oiio_tiff_channel_names(TIFF* tif, std::size_t channels) {
  std::vector<std::string> names;
  if (channels == 1) return {"Y"};
  static const char* rgba[] = {"R", "G", "B", "A"};
  for (std::size_t c = 0; c < channels; ++c)
    names.emplace_back(c < 4 ? rgba[c] : "channel" + std::to_string(c));
  int alpha = channels >= 4 ? 3 : -1;
  std::uint16_t count = 0;
  std::uint16_t* info = nullptr;
  if (!TIFFGetField(tif, TIFFTAG_EXTRASAMPLES, &count, &info) || count == 0) return names;
  const int colour = tiff_photometric(tif, channels) == PHOTOMETRIC_MINISBLACK ? 1 : 3;
  for (int i = 0, c = colour; i < count && c < int(channels); ++i, ++c) {
    if (info[i] == EXTRASAMPLE_ASSOCALPHA || info[i] == EXTRASAMPLE_UNASSALPHA) {
      alpha = c;
    } else if (alpha == c) {
      names[std::size_t(c)] = "channel" + std::to_string(c);
      alpha = -1;
    }
  }
  if (alpha >= 0) {
    names[std::size_t(alpha)] = "A";
    if (channels == 2 && alpha == 1) names[0] = "Y";  // grey + alpha
  }
  return names;
}

// The rows of a TIFF read with TIFFReadScanline, a strip at a time.
class TiffRows final : public StripReader {
 public:
  // Null when the file is not a TIFF of the kinds read here; throws for a corrupt one.
  static std::unique_ptr<TiffRows> open(const fs::path& path) {
    if (!is_readable_file(path) || !has_tiff_magic(path)) return nullptr;
    std::unique_ptr<TiffRows> rows(new TiffRows(path));
    rows->tif_ = open_tiff(path, "r", rows->message_);
    if (!rows->tif_) rows->fail();
    return rows->take_header() ? std::move(rows) : nullptr;
  }
  ~TiffRows() override {
    if (tif_) TIFFClose(tif_);
  }
  TiffRows(const TiffRows&) = delete;
  TiffRows& operator=(const TiffRows&) = delete;

 protected:
  void read_strip(std::size_t y0, Image& strip) override {
    for (std::size_t y = 0; y < strip.height; ++y) {
      if (TIFFReadScanline(tif_, row_.data(), std::uint32_t(y0 + y), 0) < 0) fail();
      const ImageView row = interleaved_view(row_.data(), width_, 1, channels_, type_);
      for (std::size_t c = 0; c < channels_; ++c) row.read_row(c, 0, strip.plane(c) + y * width_);
    }
  }

 private:
  explicit TiffRows(const fs::path& path) : path_(path) {}

  // Takes the header; false for a kind of TIFF left to OpenImageIO.
  bool take_header() {
    channels_ = tiff_field<std::uint16_t>(tif_, TIFFTAG_SAMPLESPERPIXEL);
    const auto type = tiff_sample_type(tif_);
    if (!type || !tiff_layout_read_here(tif_, channels_)) return false;
    type_ = *type;
    width_ = tiff_field<std::uint32_t>(tif_, TIFFTAG_IMAGEWIDTH);
    height_ = tiff_field<std::uint32_t>(tif_, TIFFTAG_IMAGELENGTH);
    check_image_samples(path_, width_, height_, channels_);
    const auto scanline = std::size_t(TIFFScanlineSize64(tif_));
    if (scanline < width_ * channels_ * std::size_t(bits_per_sample(type_) / 8))
      throw_read_error(path_, "its scanline size does not fit its header");
    row_.resize(scanline);
    metadata_.channel_names = kept_channel_names(oiio_tiff_channel_names(tif_, channels_));
    return true;
  }

  [[noreturn]] void fail() const {
    throw_read_error(path_, message_.text[0] ? message_.text : "not a TIFF file libtiff can read");
  }

  fs::path path_;
  TiffMessage message_;
  TIFF* tif_ = nullptr;
  std::vector<std::uint8_t> row_;  // one scanline as libtiff gives it
};

// The ASCII tags OpenImageIO 2.4's TIFF writer stores string attributes of these names in.
struct TiffTextTag {
  const char* name;
  ttag_t tag;
};
constexpr TiffTextTag kTiffTextTags[] = {{"Artist", TIFFTAG_ARTIST},
                                         {"Copyright", TIFFTAG_COPYRIGHT},
                                         {"DateTime", TIFFTAG_DATETIME},
                                         {"DocumentName", TIFFTAG_DOCUMENTNAME},
                                         {"ImageDescription", TIFFTAG_IMAGEDESCRIPTION},
                                         {"Software", TIFFTAG_SOFTWARE}};

// The ASCII tags for `attributes`, as OpenImageIO writes them (found by writing files through
// it): the strings of kTiffTextTags; Exif:ImageHistory, screenWindowWidth and a pixel aspect
// ratio of 1 dropped; Orientation 1, the one written here. nullopt for any other attribute (OpenImageIO
// writes many as tags or Exif blocks): the image goes to it.
std::optional<std::vector<std::pair<ttag_t, std::string>>> tiff_text_tags(
    const std::vector<ImageAttribute>& attributes) {
  using Kind = ImageAttribute::Kind;
  std::vector<std::pair<ttag_t, std::string>> tags;
  for (const ImageAttribute& a : attributes) {
    const auto known = std::find_if(std::begin(kTiffTextTags), std::end(kTiffTextTags),
                                    [&](const TiffTextTag& t) { return a.name == t.name; });
    if (known != std::end(kTiffTextTags) && a.kind == Kind::string)
      tags.emplace_back(known->tag, a.text);
    else if (!((a.name == "Exif:ImageHistory" && a.kind == Kind::string) ||
               (a.name == "screenWindowWidth" && a.kind == Kind::real) ||
               (a.name == "PixelAspectRatio" && a.kind == Kind::real && a.real == 1.0) ||
               (a.name == "Orientation" && a.kind == Kind::integer && a.integer == 1)))
      return std::nullopt;
  }
  return tags;
}

// Whether the image is one written here: 1 to 4 channels, a type TIFF stores, default names, no
// windows, attributes stored as OpenImageIO stores them.
bool tiff_holds(std::size_t channels, SampleType type, const ImageMetadata& metadata) {
  ImageMetadata rest = metadata;
  rest.attributes.clear();
  return channels >= 1 && channels <= 4 && type != SampleType::f16 && rest.empty() &&
         tiff_text_tags(metadata.attributes).has_value();
}

// A TIFF being written a scanline at a time.
class TiffWriter {
 public:
  TiffWriter(const fs::path& file, std::size_t width, std::size_t height, std::size_t channels,
             SampleType type, const ImageMetadata& metadata)
      : file_(file), type_(type) {
    errno = 0;
    tif_ = open_tiff(file, "w", message_);
    if (!tif_) fail();
    set_fields(width, height, channels);
    const auto tags = tiff_text_tags(metadata.attributes).value();
    for (const auto& [tag, text] : tags) TIFFSetField(tif_, tag, text.c_str());
    row_.resize(width * channels * std::size_t(bits_per_sample(type) / 8));
  }
  ~TiffWriter() {
    if (tif_) TIFFClose(tif_);
  }
  TiffWriter(const TiffWriter&) = delete;
  TiffWriter& operator=(const TiffWriter&) = delete;

  // Appends the rows of `strip`, rounded and clamped to the sample type's range.
  void put(const Image& strip) {
    for (std::size_t y = 0; y < strip.height; ++y) {
      switch (type_) {
        case SampleType::u8: interleave_row(strip, y, row_.data()); break;
        case SampleType::u16: interleave_row(strip, y, reinterpret_cast<std::uint16_t*>(row_.data())); break;
        default: interleave_row(strip, y, reinterpret_cast<float*>(row_.data())); break;
      }
      errno = 0;
      if (TIFFWriteScanline(tif_, row_.data(), std::uint32_t(next_row_++), 0) < 0) fail();
    }
  }

  // Ends the file; throws if any of it could not be written.
  void finish() {
    errno = 0;
    if (!TIFFFlush(tif_)) fail();
    TIFF* tif = tif_;
    tif_ = nullptr;
    TIFFClose(tif);
  }

 private:
  // OpenImageIO's default layout: deflate level 6 with a predictor, 32 rows a strip, grey below
  // three channels, alpha unassociated.
  void set_fields(std::size_t width, std::size_t height, std::size_t channels) {
    const bool is_float = type_ == SampleType::f32;
    TIFFSetField(tif_, TIFFTAG_IMAGEWIDTH, std::uint32_t(width));
    TIFFSetField(tif_, TIFFTAG_IMAGELENGTH, std::uint32_t(height));
    TIFFSetField(tif_, TIFFTAG_ROWSPERSTRIP, 32);
    TIFFSetField(tif_, TIFFTAG_SAMPLESPERPIXEL, int(channels));
    TIFFSetField(tif_, TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT);
    TIFFSetField(tif_, TIFFTAG_BITSPERSAMPLE, bits_per_sample(type_));
    TIFFSetField(tif_, TIFFTAG_SAMPLEFORMAT, is_float ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT);
    TIFFSetField(tif_, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
    TIFFSetField(tif_, TIFFTAG_PREDICTOR, is_float ? PREDICTOR_FLOATINGPOINT : PREDICTOR_HORIZONTAL);
    TIFFSetField(tif_, TIFFTAG_ZIPQUALITY, 6);
    TIFFSetField(tif_, TIFFTAG_PHOTOMETRIC, channels >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
    if (channels == 2 || channels == 4) {
      std::uint16_t alpha[] = {EXTRASAMPLE_UNASSALPHA};
      TIFFSetField(tif_, TIFFTAG_EXTRASAMPLES, 1, alpha);
    }
    TIFFSetField(tif_, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  }

  [[noreturn]] void fail() const {
    throw_write_failure(file_, message_.text[0] ? message_.text : "libtiff refused the image");
  }

  fs::path file_;
  SampleType type_;
  TiffMessage message_;
  TIFF* tif_ = nullptr;
  std::vector<std::uint8_t> row_;  // one interleaved row
  std::size_t next_row_ = 0;
};

}  // namespace

bool has_tiff_extension(const fs::path& path) { return has_extension(path, {".tif", ".tiff"}); }

std::unique_ptr<ImageRowReader> open_tiff_rows(const fs::path& path) { return TiffRows::open(path); }

std::optional<Image> read_tiff(const fs::path& path) { return read_whole(TiffRows::open(path)); }

bool tiff_writable(const fs::path& path, std::size_t channels, SampleType type,
                   const ImageMetadata& metadata) {
  return has_tiff_extension(path) && tiff_holds(channels, type, metadata);
}

void write_tiff(const Image& image, const fs::path& file) {
  if (!tiff_holds(image.channels, image.type, image.metadata))
    throw std::invalid_argument(
        "write_tiff: needs 1 to 4 channels of 8/16-bit or float samples, attributes TIFF holds");
  TiffWriter writer(file, image.width, image.height, image.channels, image.type, image.metadata);
  writer.put(image);
  writer.finish();
}

void write_tiff_rows(const fs::path& file, std::size_t width, std::size_t height, std::size_t channels,
                     SampleType type, const ImageMetadata& metadata,
                     const std::function<Image()>& next_strip) {
  if (!tiff_holds(channels, type, metadata))
    throw std::invalid_argument(
        "write_tiff_rows: needs 1 to 4 channels of 8/16-bit or float samples, attributes TIFF holds");
  TiffWriter writer(file, width, height, channels, type, metadata);
  write_strips(writer, width, height, channels, type, next_strip, "write_tiff_rows");
}

}  // namespace pupwave::cli
