// fuzz_spec: transform spec strings as a stream header carries them (`--transform` syntax,
// PUPs custom designs included): the bounded check, then the design it admits. Invariants:
// an admitted spec builds; its canonical spec() builds the same transform (same spec()); the
// transform reconstructs a short line.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_check.h"
#include "transforms/spec.h"

using namespace pupwave;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;  // a stream's spec is at most 4096 bytes
  const std::string spec(reinterpret_cast<const char*>(data), size);
  Transform1DPtr t;
  try {
    check_stream_spec(spec);
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
