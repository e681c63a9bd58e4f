#include "tools/pnm_io.h"

#include <algorithm>
#include <cctype>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "tools/atomic_file.h"
#include "tools/image_io.h"

namespace pupwave::cli {
namespace fs = std::filesystem;
namespace {

// Rows are converted through a buffer of about this many bytes, not a whole-image copy.
constexpr std::size_t kChunkBytes = std::size_t(1) << 20;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

struct PnmHeader {
  std::size_t width = 0, height = 0, channels = 0;
  SampleType type = SampleType::u8;
};

// Next header integer, skipping whitespace and '#' comments; -1 if there is none.
long long next_number(std::FILE* f) {
  int ch = std::fgetc(f);
  while (ch == '#' || std::isspace(ch)) {
    if (ch == '#')
      while (ch != '\n' && ch != EOF) ch = std::fgetc(f);
    ch = std::fgetc(f);
  }
  if (!std::isdigit(ch)) return -1;
  long long v = 0;
  while (std::isdigit(ch)) {
    v = v * 10 + (ch - '0');
    if (v > (1ll << 40)) return -1;
    ch = std::fgetc(f);
  }
  // One whitespace character ends the number (after maxval it is the last header byte).
  return std::isspace(ch) ? v : -1;
}

std::runtime_error read_error(const fs::path& path, const std::string& why) {
  return std::runtime_error("cannot read " + path.string() + ": " + why);
}

// Parses a P5/P6 header; nullopt for anything else (the file is left to OpenImageIO).
std::optional<PnmHeader> read_header(std::FILE* f, const fs::path& path) {
  char magic[2] = {};
  if (std::fread(magic, 1, 2, f) != 2 || magic[0] != 'P' || (magic[1] != '5' && magic[1] != '6'))
    return std::nullopt;
  const long long w = next_number(f), h = next_number(f), maxval = next_number(f);
  if (w < 0 || h < 0 || maxval < 0) throw read_error(path, "malformed PNM header");
  if (maxval != 255 && maxval != 65535) return std::nullopt;
  PnmHeader hd;
  hd.width = std::size_t(w);
  hd.height = std::size_t(h);
  hd.channels = magic[1] == '5' ? 1 : 3;
  hd.type = maxval == 255 ? SampleType::u8 : SampleType::u16;
  if (hd.width == 0 || hd.height == 0) throw read_error(path, "empty image");
  if (hd.width > kMaxImageSamples || hd.height > kMaxImageSamples ||
      hd.width * hd.height > kMaxImageSamples / hd.channels)
    throw read_error(path, "image too large");
  return hd;
}

// Decodes n interleaved samples (whole pixels) from raster bytes into the planes, from sample `first`.
void unpack(const std::uint8_t* bytes, std::size_t n, std::size_t first, Image& image) {
  const std::size_t c = image.channels, pixel0 = first / c, pixels = n / c;
  const bool wide = image.type == SampleType::u16;
  for (std::size_t ch = 0; ch < c; ++ch) {
    float* dst = image.plane(ch) + pixel0;
    if (wide)
      for (std::size_t i = 0; i < pixels; ++i) {
        const std::uint8_t* b = bytes + 2 * (i * c + ch);
        dst[i] = float((unsigned(b[0]) << 8) | b[1]);
      }
    else
      for (std::size_t i = 0; i < pixels; ++i) dst[i] = float(bytes[i * c + ch]);
  }
}

// Encodes n interleaved samples (whole pixels) from sample `first`, rounded and clamped.
void pack(const Image& image, std::size_t first, std::size_t n, std::uint8_t* bytes) {
  const std::size_t c = image.channels, pixel0 = first / c, pixels = n / c;
  const bool wide = image.type == SampleType::u16;
  const float top = wide ? 65535.0f : 255.0f;
  for (std::size_t ch = 0; ch < c; ++ch) {
    const float* src = image.plane(ch) + pixel0;
    for (std::size_t i = 0; i < pixels; ++i) {
      const auto v = unsigned(std::clamp(src[i], 0.0f, top) + 0.5f);
      if (wide) {
        bytes[2 * (i * c + ch)] = std::uint8_t(v >> 8);
        bytes[2 * (i * c + ch) + 1] = std::uint8_t(v);
      } else {
        bytes[i * c + ch] = std::uint8_t(v);
      }
    }
  }
}

// A conversion buffer holding whole pixels.
std::vector<std::uint8_t> chunk_for(std::size_t bytes_per_pixel) {
  return std::vector<std::uint8_t>(kChunkBytes - kChunkBytes % bytes_per_pixel);
}

// Grey (P5) or RGB (P6) with 8- or 16-bit samples.
bool pnm_holds(const Image& image) {
  return (image.channels == 1 || image.channels == 3) && is_integer(image.type);
}

}  // namespace

bool has_pnm_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  return ext == ".pgm" || ext == ".ppm" || ext == ".pnm";
}

namespace {

// An opened binary PNM: its header and the raster's offset, checked against the file size.
struct OpenedPnm {
  File file;
  PnmHeader header;
  std::size_t offset = 0;
};

std::optional<OpenedPnm> open_binary_pnm(const fs::path& path) {
  if (!has_pnm_extension(path)) return std::nullopt;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;  // OpenImageIO's path reports why
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) return std::nullopt;
  const auto header = read_header(f.get(), path);
  if (!header) return std::nullopt;
  const std::size_t bytes_per_sample = header->type == SampleType::u16 ? 2 : 1;
  const std::size_t samples = header->width * header->height * header->channels;
  const long offset = std::ftell(f.get());
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec || offset < 0 || size < std::uintmax_t(offset) + samples * bytes_per_sample)
    throw read_error(path, "truncated PNM raster (" + std::to_string(samples * bytes_per_sample) +
                               " bytes expected after the header)");
  return OpenedPnm{std::move(f), *header, std::size_t(offset)};
}

}  // namespace

std::optional<Image> read_binary_pnm(const fs::path& path) {
  auto opened = open_binary_pnm(path);
  if (!opened) return std::nullopt;
  const PnmHeader& header = opened->header;
  const std::size_t bytes_per_sample = header.type == SampleType::u16 ? 2 : 1;
  const std::size_t samples = header.width * header.height * header.channels;
  Image image(header.width, header.height, header.channels, header.type);
  std::vector<std::uint8_t> chunk = chunk_for(bytes_per_sample * header.channels);
  for (std::size_t done = 0; done < samples;) {
    const std::size_t n = std::min(samples - done, chunk.size() / bytes_per_sample);
    if (std::fread(chunk.data(), bytes_per_sample, n, opened->file.get()) != n)
      throw read_error(path, "short read");
    unpack(chunk.data(), n, done, image);
    done += n;
  }
  return image;
}

// Bytes before a dropped range dropped with it (MappedPnm's drop_rows): a PMD-sized folio.
constexpr std::size_t kRemapBehind = std::size_t(2) << 20;

std::unique_ptr<MappedPnm> MappedPnm::open(const fs::path& path) {
  const auto opened = open_binary_pnm(path);
  if (!opened || opened->header.type != SampleType::u8) return nullptr;
  std::unique_ptr<MappedPnm> pnm(new MappedPnm(path));
  const PnmHeader& h = opened->header;
  pnm->view_ = interleaved_view(pnm->file_.bytes().data() + opened->offset, h.width, h.height, h.channels,
                                SampleType::u8);
  // The strip-wise encoder reads the rows a strip at a time: let it drop those it has read.
  pnm->view_.drop_context = &pnm->file_;
  pnm->view_.drop_rows = [](const void* context, const ImageView& v, std::size_t y0, std::size_t y1) {
    const auto* file = static_cast<const MappedFile*>(context);
    const auto* base = static_cast<const std::uint8_t*>(v.data);
    const std::size_t row = std::size_t(v.row_stride);  // u8 samples: elements are bytes
    const std::size_t offset = std::size_t(base - file->bytes().data()) + y0 * row;
    // From kRemapBehind before too: faulting in a large folio maps its pages already dropped
    // again (192 KiB of every 2 MiB, 3 MiB of a 16 MB PGM stayed resident after a pass).
    const std::size_t from = offset > kRemapBehind ? offset - kRemapBehind : 0;
    file->drop(from, offset - from + (y1 - y0) * row);
  };
  return pnm;
}

bool binary_pnm_writable(const fs::path& path, const Image& image) {
  return has_pnm_extension(path) && pnm_holds(image);
}

bool binary_pnm_writable(const fs::path& path, std::size_t channels, SampleType type) {
  return has_pnm_extension(path) && (channels == 1 || channels == 3) && is_integer(type);
}

namespace {

// Opens `file` and writes the P5/P6 header of an image of this shape.
File open_pnm(const fs::path& file, std::size_t width, std::size_t height, std::size_t channels, bool wide) {
  File f(std::fopen(file.c_str(), "wb"));
  if (!f) throw_write_error(file);
  const std::string header = std::string(channels == 1 ? "P5" : "P6") + "\n" + std::to_string(width) + " " +
                             std::to_string(height) + "\n" + (wide ? "65535" : "255") + "\n";
  if (std::fwrite(header.data(), 1, header.size(), f.get()) != header.size()) throw_write_error(file);
  return f;
}

// Appends the raster of `image` (all its rows) to f; false on a write error.
bool write_raster(const Image& image, std::FILE* f) {
  const std::size_t bytes_per_sample = image.type == SampleType::u16 ? 2 : 1;
  const std::size_t samples = image.plane_size() * image.channels;
  std::vector<std::uint8_t> chunk = chunk_for(bytes_per_sample * image.channels);
  for (std::size_t done = 0; done < samples;) {
    const std::size_t n = std::min(samples - done, chunk.size() / bytes_per_sample);
    pack(image, done, n, chunk.data());
    if (std::fwrite(chunk.data(), bytes_per_sample, n, f) != n) return false;
    done += n;
  }
  return true;
}

}  // namespace

void write_binary_pnm(const Image& image, const fs::path& file) {
  if (!pnm_holds(image))
    throw std::invalid_argument("write_binary_pnm: needs 1 or 3 channels of 8- or 16-bit samples");
  File f = open_pnm(file, image.width, image.height, image.channels, image.type == SampleType::u16);
  if (!write_raster(image, f.get()) || std::fclose(f.release()) != 0) throw_write_error(file);
}

namespace {

// Writes strips on its own thread while the caller decodes the next one: done inline, packing
// and the copy into the page cache would be a serial tenth of a strip decode's CPU, idle time
// for the decoder's other threads. One strip waits at most, so memory stays two strips.
class OverlappedStripWriter {
 public:
  explicit OverlappedStripWriter(std::FILE* f) : f_(f), thread_([this] { loop(); }) {}
  ~OverlappedStripWriter() {
    finish();
    thread_.join();
  }
  // Queues a strip once the previous one is written; false when a write has failed.
  bool put(Image strip) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return !pending_ || failed_; });
    if (failed_) return false;
    strip_ = std::move(strip);
    pending_ = true;
    changed_.notify_all();
    return true;
  }
  // Waits for the queued strip; false when any write failed.
  bool finish() {
    std::unique_lock lock(mutex_);
    done_ = true;
    changed_.notify_all();
    changed_.wait(lock, [&] { return !pending_ || failed_; });
    return !failed_;
  }

 private:
  void loop() {
    std::unique_lock lock(mutex_);
    for (;;) {
      changed_.wait(lock, [&] { return pending_ || done_; });
      if (!pending_) return;
      lock.unlock();
      const bool ok = write_raster(strip_, f_);
      lock.lock();
      strip_ = Image{};
      pending_ = false;
      failed_ = failed_ || !ok;
      changed_.notify_all();
      if (failed_) return;
    }
  }

  std::FILE* f_;
  std::mutex mutex_;
  std::condition_variable changed_;
  Image strip_;
  bool pending_ = false, done_ = false, failed_ = false;
  std::thread thread_;  // last: starts after the members it reads
};

}  // namespace

void write_binary_pnm_rows(const fs::path& file, std::size_t width, std::size_t height, std::size_t channels,
                           SampleType type, const std::function<Image()>& next_strip) {
  if ((channels != 1 && channels != 3) || !is_integer(type))
    throw std::invalid_argument("write_binary_pnm_rows: needs 1 or 3 channels of 8- or 16-bit samples");
  File f = open_pnm(file, width, height, channels, type == SampleType::u16);
  {
    OverlappedStripWriter writer(f.get());
    for (std::size_t rows = 0; rows < height;) {
      Image strip = next_strip();
      if (strip.height == 0 || strip.width != width || strip.channels != channels || strip.type != type ||
          rows + strip.height > height)
        throw std::runtime_error("write_binary_pnm_rows: a strip does not fit the image");
      rows += strip.height;
      if (!writer.put(std::move(strip))) throw_write_error(file);
    }
    if (!writer.finish()) throw_write_error(file);
  }
  if (std::fclose(f.release()) != 0) throw_write_error(file);
}

}  // namespace pupwave::cli
