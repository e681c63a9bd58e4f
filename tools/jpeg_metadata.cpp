#include "tools/jpeg_metadata.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>
#include <string_view>
#include <utility>
// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>
#include <libexif/exif-data.h>

namespace pupwave::cli {
namespace {

// What OpenImageIO 2.4's JPEG writer does with an image's attributes, found by writing files
// through it: text attributes go into its EXIF block (APP1), some also into a Photoshop IPTC block
// (APP13) and ImageDescription into a comment (COM); Orientation and whole X/YResolution into
// EXIF; resolution and pixel aspect ratio set the JFIF density; screenWindowWidth is dropped.
// An image with any other attribute, or one of these in another form, is left to OpenImageIO.

// A text attribute, its EXIF directory and tag, and its IPTC dataset (record 2; 0: none).
struct TextTag {
  const char* name;
  ExifIfd ifd;
  ExifTag tag;
  std::uint8_t iptc;
};
// TIFF/EP's ImageHistory, which libexif's tag list lacks.
constexpr ExifTag kImageHistoryTag = ExifTag(0x9213);
constexpr TextTag kTextTags[] = {
    {"ImageDescription", EXIF_IFD_0, EXIF_TAG_IMAGE_DESCRIPTION, 120},
    {"Make", EXIF_IFD_0, EXIF_TAG_MAKE, 0},
    {"Model", EXIF_IFD_0, EXIF_TAG_MODEL, 0},
    {"Software", EXIF_IFD_0, EXIF_TAG_SOFTWARE, 65},
    {"DateTime", EXIF_IFD_0, EXIF_TAG_DATE_TIME, 0},
    {"Artist", EXIF_IFD_0, EXIF_TAG_ARTIST, 80},
    {"Copyright", EXIF_IFD_0, EXIF_TAG_COPYRIGHT, 116},
    {"Exif:ImageHistory", EXIF_IFD_EXIF, kImageHistoryTag, 0},
};

// All text together stays under this, so that each block fits its marker's 65533 bytes.
constexpr std::size_t kMaxJpegText = 60000;

const TextTag* text_tag(const std::string& name) {
  for (const TextTag& t : kTextTags)
    if (name == t.name) return &t;
  return nullptr;
}

const ImageAttribute* find_attribute(const ImageMetadata& metadata, std::string_view name) {
  for (const ImageAttribute& a : metadata.attributes)
    if (a.name == name) return &a;
  return nullptr;
}

// A resolution OpenImageIO stores as the EXIF rational v/1 and a JFIF density of v.
bool whole_density(double v) { return v >= 1.0 && v <= 65535.0 && v == std::floor(v); }

// Whether this one attribute is stored as OpenImageIO stores it (see above).
bool jpeg_attribute_held(const ImageAttribute& a) {
  using Kind = ImageAttribute::Kind;
  if (text_tag(a.name))
    return a.kind == Kind::string && !a.text.empty() && a.text.find('\0') == std::string::npos;
  if (a.name == "XResolution" || a.name == "YResolution")
    return a.kind == Kind::real && whole_density(a.real);
  if (a.name == "PixelAspectRatio") return a.kind == Kind::real && a.real > 0.0;
  if (a.name == "Orientation") return a.kind == Kind::integer && a.integer >= 1 && a.integer <= 8;
  if (a.name == "ResolutionUnit") return a.kind == Kind::string;  // names only the JFIF unit
  return a.name == "screenWindowWidth" && a.kind == Kind::real;
}

}  // namespace

// Whether every attribute is held, once (OpenImageIO keeps the last of a repeated name), their
// text fits the blocks, and the density is one whose rule was seen: a pixel aspect ratio with a
// YResolution but no XResolution was not.
bool jpeg_attributes_held(const ImageMetadata& metadata) {
  std::size_t text = 0;
  for (const ImageAttribute& a : metadata.attributes) {
    if (!jpeg_attribute_held(a) || find_attribute(metadata, a.name) != &a) return false;
    text += a.text.size();
  }
  const bool aspect_from_y = find_attribute(metadata, "PixelAspectRatio") &&
                             find_attribute(metadata, "YResolution") &&
                             !find_attribute(metadata, "XResolution");
  return text <= kMaxJpegText && !aspect_from_y;
}

namespace {

// OpenImageIO's rounding of a density: to nearest, within 1..65535 (clamped as a float, so that
// the extreme ratios' values never overflow the conversion).
std::uint16_t density_of(float v) { return std::uint16_t(std::clamp(v + 0.5f, 1.0f, 65535.0f)); }

}  // namespace

// The JFIF density OpenImageIO 2.4 writes: the unit named by ResolutionUnit ("in", "cm", else
// none); with a pixel aspect ratio, XResolution by XResolution / ratio, or 72 and 72 x ratio
// (the larger side 72's); without, the resolutions given (one standing for both); else 1 x 1.
JfifDensity jfif_density(const ImageMetadata& metadata) {
  JfifDensity d;
  if (const ImageAttribute* unit = find_attribute(metadata, "ResolutionUnit")) {
    const auto is = [&](std::string_view name) {
      return unit->text.size() == name.size() &&
             std::equal(name.begin(), name.end(), unit->text.begin(),
                        [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); });
    };
    d.unit = is("in") ? 1 : is("cm") ? 2 : 0;
  }
  const ImageAttribute* xres = find_attribute(metadata, "XResolution");
  const ImageAttribute* yres = find_attribute(metadata, "YResolution");
  const ImageAttribute* aspect = find_attribute(metadata, "PixelAspectRatio");
  // OpenImageIO receives the attributes as float (tools/oiio/oiio_module.cpp) and computes in float.
  if (aspect) {
    const float ratio = float(aspect->real);
    if (xres) {
      d.x = density_of(float(xres->real));
      d.y = density_of(float(xres->real) / ratio);
    } else {
      d.x = density_of(ratio >= 1.0f ? 72.0f : 72.0f * ratio);
      d.y = density_of(ratio >= 1.0f ? 72.0f * ratio : 72.0f);
    }
  } else if (xres || yres) {
    d.x = density_of(float((xres ? xres : yres)->real));
    d.y = density_of(float((yres ? yres : xres)->real));
  }
  return d;
}

namespace {

// Adds an entry of `size` bytes to the directory; its bytes are to be filled in.
ExifEntry* add_exif_entry(ExifData& exif, ExifMem* mem, ExifIfd ifd, ExifTag tag, ExifFormat format,
                          unsigned long components, unsigned size) {
  ExifEntry* e = exif_entry_new_mem(mem);
  if (!e) throw std::bad_alloc();
  e->data = static_cast<unsigned char*>(exif_mem_alloc(mem, size));
  if (!e->data) {
    exif_entry_unref(e);
    throw std::bad_alloc();
  }
  e->tag = tag;
  e->format = format;
  e->components = components;
  e->size = size;
  exif_content_add_entry(exif.ifd[ifd], e);
  exif_entry_unref(e);  // the directory holds it
  return e;
}

void add_exif_bytes(ExifData& exif, ExifMem* mem, ExifIfd ifd, ExifTag tag, ExifFormat format,
                    std::string_view bytes) {
  ExifEntry* e = add_exif_entry(exif, mem, ifd, tag, format, bytes.size(), unsigned(bytes.size()));
  std::memcpy(e->data, bytes.data(), bytes.size());
}

// Adds the attributes OpenImageIO writes into EXIF, in its forms: text as ASCII with its NUL,
// Orientation as SHORT, X/YResolution as RATIONAL v/1; an EXIF sub-directory gets the
// ExifVersion, ComponentsConfiguration and FlashpixVersion OpenImageIO adds to it.
void add_exif_attributes(ExifData& exif, ExifMem* mem, const ImageMetadata& metadata) {
  const ExifByteOrder order = exif_data_get_byte_order(&exif);
  for (const ImageAttribute& a : metadata.attributes) {
    if (const TextTag* t = text_tag(a.name)) {
      add_exif_bytes(exif, mem, t->ifd, t->tag, EXIF_FORMAT_ASCII,
                     std::string_view(a.text.c_str(), a.text.size() + 1));
    } else if (a.name == "Orientation") {
      ExifEntry* e = add_exif_entry(exif, mem, EXIF_IFD_0, EXIF_TAG_ORIENTATION, EXIF_FORMAT_SHORT, 1, 2);
      exif_set_short(e->data, order, ExifShort(a.integer));
    } else if (a.name == "XResolution" || a.name == "YResolution") {
      const ExifTag tag = a.name == "XResolution" ? EXIF_TAG_X_RESOLUTION : EXIF_TAG_Y_RESOLUTION;
      ExifEntry* e = add_exif_entry(exif, mem, EXIF_IFD_0, tag, EXIF_FORMAT_RATIONAL, 1, 8);
      exif_set_rational(e->data, order, ExifRational{ExifLong(a.real), 1});
    }
  }
  if (exif.ifd[EXIF_IFD_EXIF]->count == 0) return;
  add_exif_bytes(exif, mem, EXIF_IFD_EXIF, EXIF_TAG_EXIF_VERSION, EXIF_FORMAT_UNDEFINED, "0230");
  add_exif_bytes(exif, mem, EXIF_IFD_EXIF, EXIF_TAG_COMPONENTS_CONFIGURATION, EXIF_FORMAT_UNDEFINED,
                 std::string_view("\1\2\3\0", 4));
  add_exif_bytes(exif, mem, EXIF_IFD_EXIF, EXIF_TAG_FLASH_PIX_VERSION, EXIF_FORMAT_UNDEFINED, "0100");
}

// The EXIF block ("Exif\0\0" and a little-endian TIFF structure) OpenImageIO writes into every
// JPEG, with no entries when no attribute goes there.
std::string exif_block(const ImageMetadata& metadata) {
  // libexif's reference counts, released however this returns.
  const auto unref_mem = [](ExifMem* m) { exif_mem_unref(m); };
  const auto unref_data = [](ExifData* d) { exif_data_unref(d); };
  const std::unique_ptr<ExifMem, decltype(unref_mem)> mem(exif_mem_new_default(), unref_mem);
  if (!mem) throw std::bad_alloc();
  const std::unique_ptr<ExifData, decltype(unref_data)> exif(exif_data_new_mem(mem.get()), unref_data);
  if (!exif) throw std::bad_alloc();
  exif_data_set_byte_order(exif.get(), EXIF_BYTE_ORDER_INTEL);
  add_exif_attributes(*exif, mem.get(), metadata);
  unsigned char* bytes = nullptr;
  unsigned int size = 0;
  exif_data_save_data(exif.get(), &bytes, &size);
  if (!bytes) throw std::bad_alloc();
  std::string block(reinterpret_cast<const char*>(bytes), size);
  exif_mem_free(mem.get(), bytes);
  return block;
}

// OpenImageIO's Photoshop IPTC block: "Photoshop 3.0", one 8BIM resource 0x0404 holding a
// record-2 dataset per attribute that has one, in dataset order; empty when none does.
std::string iptc_block(const ImageMetadata& metadata) {
  std::vector<std::pair<std::uint8_t, const std::string*>> sets;
  for (const ImageAttribute& a : metadata.attributes)
    if (const TextTag* t = text_tag(a.name); t && t->iptc) sets.emplace_back(t->iptc, &a.text);
  if (sets.empty()) return {};
  std::sort(sets.begin(), sets.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const auto be16 = [](std::size_t v) { return std::string{char(v >> 8 & 0xFF), char(v & 0xFF)}; };
  std::string data;
  for (const auto& [dataset, text] : sets)
    data += "\x1C\x02" + std::string(1, char(dataset)) + be16(text->size()) + *text;
  return std::string(
             "Photoshop 3.0\0"
             "8BIM\x04\x04\0\0\0\0",
             24) +
         be16(data.size()) + data;
}

}  // namespace

// The markers OpenImageIO writes after the JFIF one: ImageDescription as a comment with its NUL,
// the EXIF block, the IPTC block when there is one.
std::vector<JpegMarker> jpeg_markers(const ImageMetadata& metadata) {
  std::vector<JpegMarker> markers;
  if (const ImageAttribute* d = find_attribute(metadata, "ImageDescription"))
    markers.push_back({JPEG_COM, std::string(d->text.c_str(), d->text.size() + 1)});
  markers.push_back({JPEG_APP0 + 1, exif_block(metadata)});
  if (std::string iptc = iptc_block(metadata); !iptc.empty())
    markers.push_back({JPEG_APP0 + 13, std::move(iptc)});
  return markers;
}

}  // namespace pupwave::cli
