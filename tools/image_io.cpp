#include "tools/image_io.h"

#include <Imath/half.h>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "tools/atomic_file.h"
#include "tools/exr_io.h"
#include "tools/jpeg_io.h"
#include "tools/oiio_module.h"
#include "tools/png_io.h"
#include "tools/pnm_io.h"
#include "tools/strip_io.h"
#include "tools/tiff_io.h"

namespace pupwave::cli {
namespace fs = std::filesystem;

namespace {

// Sample types a file format can store, by OpenImageIO's format name; empty = anything.
std::vector<SampleType> format_types(const std::string& format) {
  using S = SampleType;
  if (format == "png") return {S::u8, S::u16};
  if (format == "tiff") return {S::u8, S::u16, S::f32};  // OpenImageIO stores TIFF half as float
  // 16-bit PGM/PPM are written by tools/pnm_io.cpp (OpenImageIO 2.4 writes PNM with 8 bits only).
  if (format == "pnm") return {S::u8, S::u16};
  if (format == "jpeg" || format == "bmp" || format == "targa") return {S::u8};
  if (format == "openexr") return {S::f16, S::f32};
  return {};
}

// OpenImageIO's name for the format a path's extension picks; the natively written formats
// without loading it.
std::string image_format_name(const fs::path& path) {
  if (has_pnm_extension(path)) return "pnm";
  if (has_png_extension(path)) return "png";
  if (has_exr_extension(path)) return "openexr";
  if (has_tiff_extension(path)) return "tiff";
  if (has_jpeg_extension(path)) return "jpeg";
  return oiio_module().format_name(path);
}

// Closest storable type: exact if possible, else the most precise of the kind allowed.
SampleType closest_type(SampleType type, const std::vector<SampleType>& allowed) {
  if (allowed.empty() || std::find(allowed.begin(), allowed.end(), type) != allowed.end()) return type;
  const bool has_f32 = std::find(allowed.begin(), allowed.end(), SampleType::f32) != allowed.end();
  if (has_f32 && type != SampleType::u8) return SampleType::f32;  // u16 and half fit in float
  if (type == SampleType::u8) return allowed.front();             // half holds 0..255 exactly
  return allowed.back();
}

// Rows of an image viewed in place: a mapped 8-bit PGM/PPM (whose pages are let go once read),
// or an image read whole.
class ViewRows final : public ImageRowReader {
 public:
  explicit ViewRows(std::unique_ptr<MappedPnm> mapped) : mapped_(std::move(mapped)), view_(mapped_->view()) {}
  explicit ViewRows(Image image) : image_(std::move(image)), view_(view_of(image_)) {}

  std::size_t width() const override { return view_.width; }
  std::size_t height() const override { return view_.height; }
  std::size_t channels() const override { return view_.channels; }
  SampleType type() const override { return view_.type; }
  const ImageMetadata& metadata() const override { return image_.metadata; }

  Image next(std::size_t rows) override {
    const std::size_t y0 = next_row_, y1 = std::min(view_.height, y0 + std::max<std::size_t>(rows, 1));
    next_row_ = y1;
    Image strip(view_.width, y1 - y0, view_.channels, view_.type);
    for (std::size_t c = 0; c < view_.channels; ++c)
      for (std::size_t y = y0; y < y1; ++y) view_.read_row(c, y, strip.plane(c) + (y - y0) * view_.width);
    if (view_.drop_rows && y1 > y0) view_.drop_rows(view_.drop_context, view_, y0, y1);
    return strip;
  }

 private:
  std::unique_ptr<MappedPnm> mapped_;
  Image image_;  // empty for a mapped file (whose metadata is none)
  ImageView view_;
  std::size_t next_row_ = 0;
};

// Rows written or converted at a time: a strip of a few hundred KiB at most.
constexpr std::size_t kStripRows = 64;

// The type write_image stores `type` as in the format `format` names.
SampleType stored_type(const fs::path& format, std::size_t channels, SampleType type) {
  if (binary_pnm_writable(format, channels, type)) return type;  // never loads OpenImageIO
  // OpenImageIO writes PNM with 8 bits only; the binary writer takes the 1- and 3-channel cases.
  if (image_format_name(format) == "pnm" && channels != 1 && channels != 3) return SampleType::u8;
  return storable_type(format, type);
}

// The rows of a file one of the native readers takes, and OpenImageIO's name of its format; null
// for a file left to OpenImageIO.
std::unique_ptr<ImageRowReader> open_native_rows(const fs::path& path, std::string& format) {
  std::unique_ptr<ImageRowReader> rows;
  if (auto mapped = MappedPnm::open(path))
    rows = std::make_unique<ViewRows>(std::move(mapped));
  else if (auto pnm = read_binary_pnm(path))
    rows = std::make_unique<ViewRows>(std::move(*pnm));
  if (rows) {
    format = "pnm";
    return rows;
  }
  const std::pair<const char*, std::unique_ptr<ImageRowReader> (*)(const fs::path&)> readers[] = {
      {"png", open_png_rows}, {"openexr", open_exr_rows}, {"tiff", open_tiff_rows}, {"jpeg", open_jpeg_rows}};
  for (const auto& [name, open] : readers) {
    if ((rows = open(path))) {
      format = name;
      return rows;
    }
  }
  return nullptr;
}

}  // namespace

std::unique_ptr<ImageRowReader> open_image_rows(const fs::path& path) {
  std::string format;
  if (auto rows = open_native_rows(path, format)) return rows;
  return oiio_module().open_rows(path);
}

Image read_image(const fs::path& path) {
  if (auto pnm = read_binary_pnm(path)) return std::move(*pnm);
  if (auto png = read_png(path)) return std::move(*png);
  if (auto exr = read_exr(path)) return std::move(*exr);
  if (auto tiff = read_tiff(path)) return std::move(*tiff);
  if (auto jpeg = read_jpeg(path)) return std::move(*jpeg);
  return oiio_module().read(path);
}

std::string describe_image_file(const fs::path& path) {
  std::string format;
  const auto rows = open_native_rows(path, format);
  if (!rows) return oiio_module().describe(path);
  const auto& given = rows->metadata().channel_names;
  const auto names = given.empty() ? default_channel_names(rows->channels()) : given;
  return describe_image(path, format, rows->width(), rows->height(), names, to_string(rows->type()),
                        alpha_channel_of(names), rows->metadata());
}

SampleType storable_type(const fs::path& path, SampleType type) {
  return closest_type(type, format_types(image_format_name(path)));
}

Image convert_sample_type(Image image, SampleType target) {
  if (image.type == target) return image;
  const double scale = nominal_max(target) / nominal_max(image.type);
  image.type = target;
  for (float& v : image.samples) {
    double x = double(v) * scale;
    if (is_integer(target)) {
      x = std::clamp(std::round(x), 0.0, nominal_max(target));
    } else if (target == SampleType::f16) {
      x = double(float(Imath::half(float(std::clamp(x, -65504.0, 65504.0)))));
    }
    v = float(x);
  }
  return image;
}

fs::path format_name_path(const fs::path& path, const std::string& format) {
  if (format.empty()) return path;
  return fs::path("output." + format);
}

fs::path stdout_image_format(SampleType type) { return is_integer(type) ? "-.png" : "-.exr"; }

void check_image_format(const fs::path& path, const fs::path& format_as) {
  if (has_pnm_extension(format_as) || has_png_extension(format_as) || has_exr_extension(format_as) ||
      has_tiff_extension(format_as) || has_jpeg_extension(format_as))
    return;
  try {
    (void)oiio_module().format_name(format_as);
  } catch (const std::exception&) {
    const std::string extension = format_as.extension().string();
    throw std::runtime_error("cannot write " + path.string() + ": " +
                             (extension.empty()
                                  ? std::string("its name has no extension to tell the image format")
                                  : "unsupported image format '" + extension + "'") +
                             " (name it .png, .tif, .exr, .pgm/.ppm, .jpg, or give --format)");
  }
}

void write_image(const Image& image, const fs::path& path, SampleType* stored_as, const fs::path& format_as) {
  if (image.channels < 1 || image.channels > kMaxImageChannels || image.width == 0 || image.height == 0 ||
      image.samples.size() != image.plane_size() * image.channels)
    throw std::invalid_argument("write_image: malformed image");
  const fs::path& format = format_as.empty() ? path : format_as;
  check_output_path(path);
  check_image_format(path, format);
  const SampleType target = stored_type(format, image.channels, image.type);
  std::optional<Image> converted;  // only when the type changes: a copy is 4 bytes per sample
  if (target != image.type) converted = convert_sample_type(image, target);
  const Image& stored = converted ? *converted : image;
  write_output(path, [&](const fs::path& tmp) {
    if (binary_pnm_writable(format, stored))
      write_binary_pnm(stored, tmp);
    else if (png_writable(format, stored.channels, stored.type, stored.metadata))
      write_png(stored, tmp);
    else if (exr_writable(format, stored.type, stored.metadata))
      write_exr(stored, tmp);
    else if (tiff_writable(format, stored.channels, stored.type, stored.metadata))
      write_tiff(stored, tmp);
    else if (jpeg_writable(format, stored.channels, stored.type, stored.metadata))
      write_jpeg(stored, tmp);
    else
      oiio_module().write(stored, format, tmp);
  });
  if (stored_as) *stored_as = stored.type;
}

SampleType write_image_rows(ImageRowReader& rows, const fs::path& path, const fs::path& format_as) {
  const fs::path& format = format_as.empty() ? path : format_as;
  check_output_path(path);
  check_image_format(path, format);
  const SampleType target = stored_type(format, rows.channels(), rows.type());
  const auto next = [&] { return convert_sample_type(rows.next(kStripRows), target); };
  write_output(path, [&](const fs::path& tmp) {
    if (binary_pnm_writable(format, rows.channels(), target))
      write_binary_pnm_rows(tmp, rows.width(), rows.height(), rows.channels(), target, next);
    else if (png_writable(format, rows.channels(), target, rows.metadata()))
      write_png_rows(tmp, rows.width(), rows.height(), rows.channels(), target, rows.metadata(), next);
    else if (exr_writable(format, target, rows.metadata()))
      write_exr_rows(tmp, rows.width(), rows.height(), rows.channels(), target, rows.metadata(), next);
    else if (tiff_writable(format, rows.channels(), target, rows.metadata()))
      write_tiff_rows(tmp, rows.width(), rows.height(), rows.channels(), target, rows.metadata(), next);
    else if (jpeg_writable(format, rows.channels(), target, rows.metadata()))
      write_jpeg_rows(tmp, rows.width(), rows.height(), rows.channels(), rows.metadata(), next);
    else
      oiio_module().write_rows(ImageShape{rows.width(), rows.height(), rows.channels(), target},
                               rows.metadata(), format, tmp, next);
  });
  return target;
}

}  // namespace pupwave::cli
