// fuzz_spec: transform spec strings as a stream header carries them (`--transform` syntax,
// PUPs custom designs included): the bounded check, then the design it admits. Invariants:
// an admitted spec builds; its canonical spec() builds the same transform (same spec()); the
// transform reconstructs a short line.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_check.h"
#include "transforms/pups/design.h"
#include "transforms/pups/refinement.h"
#include "transforms/spec.h"

using namespace pupwave;

namespace {

// Explicit PUPs designs whose refinement system exceeds 2^18 entries are checked but not
// designed: under ASan such a design takes seconds (a release build: a fraction of one), which
// would stall the fuzzer; the same design code runs on smaller sample counts. The stream
// bounds themselves are tested by tests/hostile and tests/pups/stream_spec_bounds_test.cpp.
bool too_slow_to_design(const std::string& spec) {
  if (!spec.starts_with("pups:")) return false;
  const pups::DesignSpec d = pups::parse_design_spec(std::string_view(spec).substr(5));
  if (!d.preset.empty()) return false;
  return std::size_t(d.params.samples) * std::size_t(pups::make_weight(d.params).width + 1) > (1u << 18);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;  // a stream's spec is at most 4096 bytes
  const std::string spec(reinterpret_cast<const char*>(data), size);
  Transform1DPtr t;
  try {
    check_stream_spec(spec);
    if (too_slow_to_design(spec)) return 0;
    t = make_transform(spec);
  } catch (const std::invalid_argument&) {
    return 0;
  }
  FUZZ_CHECK(t != nullptr);
  FUZZ_CHECK(make_transform(t->spec())->spec() == t->spec());
  std::vector<double> line(23), orig(23);
  for (std::size_t i = 0; i < line.size(); ++i) line[i] = orig[i] = double((i * 7) % 5) - 2.0;
  t->analyze(std::span<double>(line));
  t->synthesize(std::span<double>(line));
  bool finite = true;
  for (double v : line) finite = finite && std::isfinite(v);
  if (finite)  // an ill-conditioned but bounded design may overflow; a finite result must match
    for (std::size_t i = 0; i < line.size(); ++i) FUZZ_CHECK(std::abs(line[i] - orig[i]) < 1e-3);
  return 0;
}
