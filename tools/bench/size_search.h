#pragma once
// Rate targeting for anchor codecs that have no rate control of their own (JPEG XL, AVIF, HEVC,
// WebP): their quality parameter is bisected until the file is within 1% of the target size.

#include <filesystem>
#include <functional>
#include <string>

#include "tools/bench/codecs.h"

namespace pupwave::bench {

// The parameter searched and how the file size moves with it.
struct ParameterRange {
  double lo = 0.0, hi = 0.0;      // inclusive range of the parameter
  bool integer = false;           // only integer values are valid (quantisers, quality)
  bool larger_is_smaller = true;  // a larger value gives a smaller file (quantiser, distance)
  bool log_scale = false;         // bisect in log(value) (JPEG XL's distance)
};

// Runs the encoder with parameter `value` into `product` and returns its wall time in seconds.
using TrialEncoder = std::function<double(double value, const std::filesystem::path& product)>;

// Bisects `range` for the file size nearest the request's target (log ratio), starting at the
// end that gives the smallest file (when even that is too big, it is kept). The closest trial is
// renamed to q.output; `setting` is describe(value) plus the trial count. At most 16 trials.
EncodeOutcome search_parameter(const EncodeRequest& q, const ParameterRange& range,
                               const TrialEncoder& encode,
                               const std::function<std::string(double)>& describe);

}  // namespace pupwave::bench
