#pragma once
// Validation of numeric command-line options, shared by every subcommand: a number must be
// finite (CLI11 reads "nan" and "inf" as doubles and its range checks let NaN through) and
// inside its range, and a refusal names the range in words, not as 309-digit limits.

#include <CLI/CLI.hpp>
#include <string>

namespace pupwave::cli {

// A number as messages print it: %.6g ("0.5", "1e-06").
std::string shortest(double v);

// A finite number > 0.
CLI::Validator positive_number();
// A finite number >= 0.
CLI::Validator non_negative_number();
// A finite number in [lo, hi].
CLI::Validator number_in(double lo, double hi);

// Adds a finite-number check to every floating-point option of `app` and its subcommands
// (the ones no range check above covers still refuse NaN and infinity).
void require_finite_numbers(CLI::App& app);

}  // namespace pupwave::cli
