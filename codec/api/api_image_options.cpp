// The public image options resolved into the encoder's, and the encode with the coder choice
// (api_image_options.h).
#include "codec/api/api_image_options.h"

#include <cctype>
#include <cmath>
#include <string>

#include "codec/api/api_coder.h"
#include "codec/api/api_errors.h"
#include "codec/image/image_stream.h"

namespace pupwave::api {
namespace {

RateMode rate_mode(ImageRate rate) {
  switch (rate) {
    case ImageRate::psnr: return RateMode::psnr;
    case ImageRate::bpp: return RateMode::bpp;
    case ImageRate::step: return RateMode::step;
    case ImageRate::lossless: return RateMode::lossless;
  }
  detail::fail("unknown rate mode " + std::to_string(int(rate)));
}

// Never hand out a stream the decoder rejects: extreme targets (e.g. step 1e30, whose band
// steps overflow the header's floats) give one. Parsing costs a CRC pass.
void check_decodable(std::span<const std::uint8_t> bytes) {
  try {
    parse_container(bytes, 0);
  } catch (const DecodeError& e) {
    throw Error(Status::unsupported, std::string("these settings give a stream the decoder rejects (") +
                                         e.what() + "); use a less extreme target");
  }
}

}  // namespace

std::string_view tune_name(Tune tune) {
  return to_string(tune == Tune::visual ? pupwave::Tune::visual : pupwave::Tune::psnr);
}

std::optional<Tune> tune_from_name(std::string_view name) {
  std::string lower(name);
  for (char& ch : lower) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  const auto t = pupwave::tune_from_name(lower);
  if (!t) return std::nullopt;
  return *t == pupwave::Tune::visual ? Tune::visual : Tune::psnr;
}

EncodeOptions resolve_image_options(const ImageOptions& options) {
  EncodeOptions enc;
  enc.mode = rate_mode(options.rate);
  const bool lossless = options.rate == ImageRate::lossless;
  if (!lossless && !(options.target > 0.0 && std::isfinite(options.target)))
    detail::fail("rate target must be a positive finite number, got " + std::to_string(options.target));
  enc.target = lossless ? 1.0 : options.target;
  enc.transform = !options.transform.empty() ? options.transform : lossless ? "cdf53" : "cdf97";
  if (options.levels < -1 || options.levels > 32)
    detail::fail("levels must be -1 (default) or 0..32, got " + std::to_string(options.levels));
  enc.levels = options.levels;
  enc.entropy = entropy_coder(options.coder).value_or(EntropyCoder::ebcot);
  enc.effort = options.effort;
  if (options.tune != Tune::psnr && options.tune != Tune::visual)
    detail::fail("unknown tune " + std::to_string(int(options.tune)));
  enc.tune = options.tune == Tune::visual ? pupwave::Tune::visual : pupwave::Tune::psnr;
  enc.measure_psnr = false;
  return enc;
}

EncodeResult encode_resolved(const pupwave::ImageView& view, const EncodeOptions& options, Coder coder) {
  EncodeResult r =
      coder == Coder::automatic ? encode_image_default_coder(view, options) : encode_image(view, options);
  check_decodable(r.bytes);
  return r;
}

}  // namespace pupwave::api
