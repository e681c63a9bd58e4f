#include "tools/image_io.h"

#include <Imath/half.h>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "tools/atomic_file.h"
#include "tools/oiio_module.h"
#include "tools/pnm_io.h"

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

// Closest storable type: exact if possible, else the most precise of the kind allowed.
SampleType closest_type(SampleType type, const std::vector<SampleType>& allowed) {
  if (allowed.empty() || std::find(allowed.begin(), allowed.end(), type) != allowed.end()) return type;
  const bool has_f32 = std::find(allowed.begin(), allowed.end(), SampleType::f32) != allowed.end();
  if (has_f32 && type != SampleType::u8) return SampleType::f32;  // u16 and half fit in float
  if (type == SampleType::u8) return allowed.front();             // half holds 0..255 exactly
  return allowed.back();
}

}  // namespace

Image read_image(const fs::path& path) {
  if (auto pnm = read_binary_pnm(path)) return std::move(*pnm);
  return oiio_module().read(path);
}

std::string describe_image_file(const fs::path& path) { return oiio_module().describe(path); }

SampleType storable_type(const fs::path& path, SampleType type) {
  return closest_type(type, format_types(oiio_module().format_name(path)));
}

Image convert_sample_type(const Image& image, SampleType target) {
  if (image.type == target) return image;
  Image out = image;
  out.type = target;
  const double scale = nominal_max(target) / nominal_max(image.type);
  for (float& v : out.samples) {
    double x = double(v) * scale;
    if (is_integer(target)) {
      x = std::clamp(std::round(x), 0.0, nominal_max(target));
    } else if (target == SampleType::f16) {
      x = double(float(Imath::half(float(std::clamp(x, -65504.0, 65504.0)))));
    }
    v = float(x);
  }
  return out;
}

fs::path format_name_path(const fs::path& path, const std::string& format) {
  if (format.empty()) return path;
  return fs::path("output." + format);
}

fs::path stdout_image_format(SampleType type) { return is_integer(type) ? "-.png" : "-.exr"; }

void check_image_format(const fs::path& path, const fs::path& format_as) {
  if (has_pnm_extension(format_as)) return;
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
  if (binary_pnm_writable(format, image)) {  // never loads OpenImageIO
    write_output(path, [&](const fs::path& tmp) { write_binary_pnm(image, tmp); });
    if (stored_as) *stored_as = image.type;
    return;
  }
  SampleType target = storable_type(format, image.type);
  // OpenImageIO writes PNM with 8 bits only; the binary writer takes the 1- and 3-channel cases.
  if (oiio_module().format_name(format) == "pnm" && image.channels != 1 && image.channels != 3)
    target = SampleType::u8;
  std::optional<Image> converted;  // only when the type changes: a copy is 4 bytes per sample
  if (target != image.type) converted = convert_sample_type(image, target);
  const Image& stored = converted ? *converted : image;
  write_output(path, [&](const fs::path& tmp) {
    if (binary_pnm_writable(format, stored))
      write_binary_pnm(stored, tmp);
    else
      oiio_module().write(stored, format, tmp);
  });
  if (stored_as) *stored_as = stored.type;
}

}  // namespace pupwave::cli
