#pragma once
// What `pupwave filters show|list|search` print about a bank: its filters, its figures of
// merit for coding (transforms/analysis/merit.h) and what it is good for.

#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "transforms/analysis/merit.h"
#include "transforms/pups/design.h"
#include "transforms/transform1d.h"

namespace pupwave::cli {

// Number with `digits` significant digits ("%.*g").
std::string fmt(double x, int digits = 9);

// Spec body (weight, errors, l, shift, P, A, B, Q) of a designed bank.
void print_bank(std::ostream& os, const pups::FilterBank& bank, pups::BoundaryRule boundary);

// The figures, one per line, for `filters show`.
void print_merit(std::ostream& os, const merit::Merit& m, const merit::MeritOptions& o);

// One line: "coding" or "curve/surface design only", with the reason from coding_verdict.
std::string use_line(const merit::Merit& m);

// The figures in one line for `filters list` and `filters search`.
std::string merit_summary(const merit::Merit& m);

// Registers `filters search` (tools/cmd_filters_search.cpp) under `filters`.
void add_search(CLI::App& filters);

}  // namespace pupwave::cli
