#pragma once
// Transform spec strings: the one place that turns a name ("cdf97", "pups:...",
// "kobbelt:...") into a Transform1D, used by the codec (file header) and the CLI.

#include <string>
#include <string_view>
#include <vector>

#include "transforms/transform1d.h"

namespace pupwave {

// Builds the transform named by spec: "cdf97", "cdf53", "pups:<body>" (PUPs filter banks)
// or "kobbelt:<body>" (Kobbelt-Schroder variational wavelets); the body is interpreted by
// that family. Throws std::invalid_argument, listing the valid specs, for an unknown spec.
// The result's spec() is the canonical form of the argument.
Transform1DPtr make_transform(std::string_view spec);

// Checks a spec read from a stream without designing anything (docs/bitstream.md, Decoder
// bounds): the family and parameters must parse, and a PUPs design must stay within the
// stream bounds on support, samples, polynomial coefficients and extension (presets always
// do), so that make_transform on it costs bounded time and memory. Throws
// std::invalid_argument naming the bound.
void check_stream_spec(std::string_view spec);

// Every spec make_transform accepts by name (families with parameters list their presets).
std::vector<std::string> transform_specs();

}  // namespace pupwave
