#pragma once
// PUPs filter banks from weight functions: the full design (refinement + Algorithm 5.1),
// the named presets used by the seeds, and the text form of a design used in transform
// specs ("pups:<body>").

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "transforms/pups/filter_bank.h"
#include "transforms/pups/multiresolution.h"

namespace pupwave::pups {

// Refines the weight function of `params` (Eq. 17-22) and designs A, B, Q from the
// refinement (Algorithm 5.1). params.extension is ignored; the l used is stored in the
// result. Throws std::invalid_argument for bad parameters.
FilterBank design(const DesignParams& params, const ExtensionRule& rule);

// How the transform reads a line beyond its ends (docs/pups.md, Boundary rules). Either
// rule reconstructs perfectly; it is part of the transform spec, so it never changes for a
// given spec string (every stream naming it decodes the same).
enum class BoundaryRule : std::uint8_t {
  wire_hss,  // half-sample symmetric extension of each wire (the default; spec key absent)
  line_wss,  // whole-sample symmetric extension of the line, JPEG 2000's rule ("boundary=wss"):
             // exact symmetric extension for symmetric (odd-length) banks
};

// A named design.
struct Preset {
  std::string name;
  std::string description;
  DesignParams params;  // params.extension = the fixed l of the preset
  BoundaryRule boundary = BoundaryRule::wire_hss;
};

// All presets, in a stable order.
const std::vector<Preset>& presets();

// Designs the named preset (bank.name = name); throws std::invalid_argument if unknown.
FilterBank design_preset(std::string_view name);

// A parsed spec body: either a preset name or a weight with explicit parameters.
struct DesignSpec {
  std::string preset;  // non-empty for a preset
  DesignParams params;
  ExtensionRule rule;
  BoundaryRule boundary = BoundaryRule::wire_hss;  // the preset's for a preset
};

// Parses the text after "pups:": a preset name, or `<weight>(key=value,...)` with keys
//   bspline:         degree
//   polynomial:      coeffs=a0:a1:...:ak, domain=lo:hi
//   cinpact, cinpact-interp: c, sigma
// and for all: l=<even extension> or t=<orthogonality-error threshold> (default l=0),
// samples=<n> (default 100000), boundary=hss|wss (default hss, see BoundaryRule).
// Example: "cinpact-interp(c=5,sigma=4.79,l=32)".
// Throws std::invalid_argument with a clear message for anything else.
DesignSpec parse_design_spec(std::string_view body);

// Bounds on a design named in a stream (docs/bitstream.md, Decoder bounds): a header of a few
// bytes must not demand minutes and gigabytes of design work before any data is read.
inline constexpr int kStreamMaxWidth = 64;                 // support W of the weight
inline constexpr int kStreamMaxSamples = 1'000'000;        // samples of the refinement system
inline constexpr std::size_t kStreamMaxSystem = 1u << 23;  // samples x (W + 1): 64 MiB of doubles
inline constexpr std::size_t kStreamMaxCoeffs = 64;        // polynomial coefficients
inline constexpr int kStreamMaxExtension = 64;             // bandwidth extension l

// Checks those bounds without designing (presets always pass). Throws std::invalid_argument.
void check_stream_design_bounds(const DesignSpec& spec);

// Designs from a parsed spec (preset or explicit).
FilterBank design(const DesignSpec& spec);

// Canonical spec body of a designed bank: the preset name if bank.name is a preset, else
// `<weight>(...,l=<l used>)` with numbers in shortest round-trip form, so that
// parse_design_spec + design rebuild the same bank; ",boundary=wss" is added for line_wss
// (never for a preset, whose name fixes its rule). Throws for WeightKind::given.
std::string canonical_spec_body(const FilterBank& bank, BoundaryRule boundary = BoundaryRule::wire_hss);

}  // namespace pupwave::pups
