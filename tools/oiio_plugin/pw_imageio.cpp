// pw.imageio.so: an OpenImageIO format plugin for .pw image streams, so any OIIO application
// (iinfo, oiiotool, ...) reads and writes Pupwave files. Reading with the config pupwave:mip = 1
// exposes every resolution level as a MIP level (level k = 1/2^k size, decoded from only the
// data it needs). Writing takes the rate from the attributes pupwave:bpp, pupwave:psnr,
// pupwave:step, pupwave:lossless (or "compression" = "lossless"), pupwave:transform,
// pupwave:levels, pupwave:entropy, pupwave:effort and pupwave:tune (the CLI's flags of those names); default
// PSNR 40 dB.
// It is built on the public C++ API (pupwave/pupwave.hpp). Not to be confused with
// tools/oiio/ (libpupwave_oiio.so), the CLI's own loader for PNG/TIFF/EXR input files.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "pupwave/pupwave.hpp"
#include "tools/atomic_file.h"

OIIO_PLUGIN_NAMESPACE_BEGIN

namespace {

namespace api = pupwave::api;
namespace cli = pupwave::cli;

TypeDesc oiio_type(api::SampleType type) {
  switch (type) {
    case api::SampleType::u8: return TypeDesc::UINT8;
    case api::SampleType::u16: return TypeDesc::UINT16;
    case api::SampleType::f16: return TypeDesc::HALF;
    case api::SampleType::f32: break;
  }
  return TypeDesc::FLOAT;
}

// A numeric attribute of any type (oiiotool --attrib stores "1" as int, "1.5" as float); 0 if
// absent. A float attribute is read as the shortest decimal that gives it back (35.3f as 35.3,
// not 35.2999992), the number that was written, so a target is the CLI's to the bit.
double number(const ImageSpec& spec, const char* name) {
  const ParamValue* p = spec.find_attribute(name);
  if (!p) return 0.0;
  if (p->type() == TypeInt) return *static_cast<const int*>(p->data());
  if (p->type() == TypeFloat) {
    char text[32];
    const char* end = std::to_chars(text, text + sizeof text, *static_cast<const float*>(p->data())).ptr;
    double value = 0.0;
    std::from_chars(text, end, value);
    return value;
  }
  if (p->type() == TypeString) return std::strtod(p->get_string().c_str(), nullptr);
  return 0.0;
}

// The coder of a pupwave:entropy name (the CLI's --entropy names, any case).
api::Coder coder(const std::string& name) {
  const auto found = api::coder_from_name(name);
  if (!found)
    throw std::invalid_argument("unknown pupwave:entropy " + name + " (one of " + api::coder_names() + ")");
  return *found;
}

api::Tune tune(const std::string& name) {
  const auto found = api::tune_from_name(name);
  if (!found) throw std::invalid_argument("unknown pupwave:tune " + name + " (psnr or visual)");
  return *found;
}

bool has_signature(const std::string& path) {
  char sig[4] = {};
  std::ifstream in(path, std::ios::binary);
  return in.read(sig, 4) && std::memcmp(sig, "PUPW", 4) == 0;
}

class PwInput final : public ImageInput {
 public:
  const char* format_name() const override { return "pw"; }
  int supports(string_view feature) const override { return feature == "mipmap" ? 1 : 0; }
  bool valid_file(const std::string& filename) const override { return has_signature(filename); }

  bool open(const std::string& name, ImageSpec& newspec) override {
    mip_ = false;
    return open_stream(name, newspec);
  }

  // Config "pupwave:mip" = 1 (oiiotool --iconfig pupwave:mip 1) exposes the reduced
  // resolutions as MIP levels. Off by default: oiiotool copies every MIP level of an input
  // to its output, which scanline EXR and PNG cannot hold (`oiiotool x.pw -o y.exr` fails).
  bool open(const std::string& name, ImageSpec& newspec, const ImageSpec& config) override {
    mip_ = number(config, "pupwave:mip") != 0.0;
    return open_stream(name, newspec);
  }

  bool close() override {
    bytes_.clear();
    levels_.clear();
    return true;
  }

  int current_subimage() const override { return 0; }
  int current_miplevel() const override { return miplevel_; }

  bool seek_subimage(int subimage, int miplevel) override {
    if (subimage != 0 || miplevel < 0 || miplevel > (mip_ ? info_.levels : 0)) return false;
    return miplevel == miplevel_ && m_spec.width > 0 ? true : seek_level(miplevel);
  }

  bool read_native_scanline(int subimage, int miplevel, int y, int /*z*/, void* data) override {
    if (!seek_subimage(subimage, miplevel) || y < 0 || y >= m_spec.height) return false;
    const api::Image& image = level(miplevel);
    const std::size_t row = image.width * image.channels * api::bytes_per_sample(image.type);
    std::memcpy(data, image.data.data() + std::size_t(y) * row, row);
    return true;
  }

 private:
  bool open_stream(const std::string& name, ImageSpec& newspec) {
    std::ifstream in(name, std::ios::binary);
    if (!in) return fail("cannot open " + name);
    bytes_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (bytes_.size() < 4 || std::memcmp(bytes_.data(), "PUPW", 4) != 0)
      return fail(name +
                  " is not a Pupwave image stream (volume streams are read with `pupwave decompress`)");
    try {
      info_ = api::info(bytes_);
    } catch (const std::exception& e) {
      return fail(name + ": " + e.what());
    }
    levels_.clear();
    if (!seek_level(0)) return false;
    newspec = spec();
    return true;
  }

  bool seek_level(int miplevel) {
    const api::Image& image = level(miplevel);
    if (image.width == 0) return false;
    miplevel_ = miplevel;
    m_spec = ImageSpec(int(image.width), int(image.height), int(image.channels), oiio_type(image.type));
    m_spec.attribute("oiio:BitsPerSample", int(api::bytes_per_sample(image.type) * 8));
    m_spec.attribute("pupwave:transform", info_.transform);
    m_spec.attribute("pupwave:levels", info_.levels);
    m_spec.attribute("pupwave:lossless", info_.lossless ? 1 : 0);
    m_spec.attribute("compression", info_.lossless ? "pupwave:lossless" : "pupwave");
    if (image.channels == 2 || image.channels == 4) m_spec.alpha_channel = int(image.channels) - 1;
    return true;
  }

  // The decoded image of a resolution level, decoded on first use (empty on failure).
  const api::Image& level(int miplevel) {
    auto it = levels_.find(miplevel);
    if (it != levels_.end()) return it->second;
    api::Image image;
    try {
      image = api::decompress_image(bytes_, miplevel);
    } catch (const std::exception& e) {
      fail(e.what());
    }
    return levels_.emplace(miplevel, std::move(image)).first->second;
  }

  bool fail(const std::string& message) const {
    errorfmt("{}", message);
    return false;
  }

  std::vector<std::uint8_t> bytes_;
  api::StreamInfo info_;
  std::map<int, api::Image> levels_;
  int miplevel_ = 0;
  bool mip_ = false;  // reduced resolutions exposed as MIP levels
};

class PwOutput final : public ImageOutput {
 public:
  ~PwOutput() override { close(); }
  const char* format_name() const override { return "pw"; }
  int supports(string_view feature) const override { return feature == "alpha" ? 1 : 0; }

  bool open(const std::string& name, const ImageSpec& newspec, OpenMode mode = Create) override {
    if (mode != Create) return fail("pw files hold one image: cannot append subimages or MIP levels");
    if (newspec.nchannels < 1 || newspec.nchannels > 4 || newspec.width < 1 || newspec.height < 1 ||
        newspec.depth > 1)
      return fail("pw images have 1 to 4 channels and are 2-D, got " + std::to_string(newspec.nchannels) +
                  " channel(s)");
    m_spec = newspec;
    // Keep the sample type when the format stores it; otherwise write float (OIIO converts).
    if (m_spec.format != TypeDesc::UINT8 && m_spec.format != TypeDesc::UINT16 &&
        m_spec.format != TypeDesc::HALF && m_spec.format != TypeDesc::FLOAT)
      m_spec.set_format(TypeDesc::FLOAT);
    filename_ = name;
    pixels_.assign(m_spec.image_bytes(), 0);
    open_ = true;
    return true;
  }

  bool write_scanline(int y, int z, TypeDesc format, const void* data, stride_t xstride) override {
    if (!open_ || y < m_spec.y || y >= m_spec.y + m_spec.height) return fail("scanline out of range");
    const void* native = to_native_scanline(format, data, xstride, scratch_);
    const std::size_t row = m_spec.scanline_bytes();
    std::memcpy(pixels_.data() + std::size_t(y - m_spec.y) * row, native, row);
    (void)z;
    return true;
  }

  bool close() override {
    if (!open_) return true;
    open_ = false;
    try {
      const auto bytes = api::compress_image(view(), options());
      // A file appears whole or not at all; a device or FIFO is written in place (write_output).
      cli::write_output_bytes(filename_, bytes);
      return true;
    } catch (const std::exception& e) {
      return fail(e.what());
    }
  }

 private:
  api::ImageView view() const {
    api::SampleType type = api::SampleType::f32;
    if (m_spec.format == TypeDesc::UINT8) type = api::SampleType::u8;
    if (m_spec.format == TypeDesc::UINT16) type = api::SampleType::u16;
    if (m_spec.format == TypeDesc::HALF) type = api::SampleType::f16;
    return api::interleaved_view(pixels_.data(), std::size_t(m_spec.width), std::size_t(m_spec.height),
                                 std::size_t(m_spec.nchannels), type);
  }

  api::ImageOptions options() const {
    api::ImageOptions o;
    const std::string compression = m_spec.get_string_attribute("compression");
    if (const double bpp = number(m_spec, "pupwave:bpp"); bpp != 0.0) {
      o.rate = api::ImageRate::bpp, o.target = bpp;
    } else if (const double psnr = number(m_spec, "pupwave:psnr"); psnr != 0.0) {
      o.rate = api::ImageRate::psnr, o.target = psnr;
    } else if (const double step = number(m_spec, "pupwave:step"); step != 0.0) {
      o.rate = api::ImageRate::step, o.target = step;
    } else if (number(m_spec, "pupwave:lossless") != 0.0 || compression == "lossless" ||
               compression == "pupwave:lossless") {
      o.rate = api::ImageRate::lossless;
    }
    o.transform = m_spec.get_string_attribute("pupwave:transform");
    o.levels = m_spec.find_attribute("pupwave:levels") ? int(number(m_spec, "pupwave:levels")) : -1;
    o.coder = coder(m_spec.get_string_attribute("pupwave:entropy", "auto"));
    if (m_spec.find_attribute("pupwave:effort")) o.effort = int(number(m_spec, "pupwave:effort"));
    o.tune = tune(m_spec.get_string_attribute("pupwave:tune", "psnr"));
    return o;
  }

  bool fail(const std::string& message) const {
    errorfmt("{}", message);
    return false;
  }

  std::string filename_;
  std::vector<std::uint8_t> pixels_;
  std::vector<unsigned char> scratch_;
  bool open_ = false;
};

}  // namespace

OIIO_PLUGIN_EXPORTS_BEGIN
OIIO_EXPORT int pw_imageio_version = OIIO_PLUGIN_VERSION;
OIIO_EXPORT const char* pw_imageio_library_version() { return "pupwave"; }
OIIO_EXPORT ImageInput* pw_input_imageio_create() { return new PwInput; }
OIIO_EXPORT const char* pw_input_extensions[] = {"pw", nullptr};
OIIO_EXPORT ImageOutput* pw_output_imageio_create() { return new PwOutput; }
OIIO_EXPORT const char* pw_output_extensions[] = {"pw", nullptr};
OIIO_PLUGIN_EXPORTS_END

OIIO_PLUGIN_NAMESPACE_END
