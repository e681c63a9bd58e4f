#include "tools/cli_numbers.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>

namespace pupwave::cli {
namespace {

// Parses the whole string as a double; false if it is not one.
bool parse_number(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

// A validator that accepts finite numbers for which `ok` holds; `what` names the range.
CLI::Validator numbers(const std::string& what, std::function<bool(double)> ok) {
  return CLI::Validator(
      [what, ok](std::string& text) -> std::string {
        double v = 0.0;
        if (!parse_number(text, v)) return "'" + text + "' is not a number";
        if (!std::isfinite(v)) return "'" + text + "' is not a finite number; expected " + what;
        if (!ok(v)) return text + " is out of range; expected " + what;
        return {};
      },
      what);
}

}  // namespace

std::string shortest(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

CLI::Validator positive_number() {
  return numbers("a number > 0", [](double v) { return v > 0.0; });
}

CLI::Validator non_negative_number() {
  return numbers("a number >= 0", [](double v) { return v >= 0.0; });
}

CLI::Validator number_in(double lo, double hi) {
  return numbers("a number in " + shortest(lo) + ".." + shortest(hi),
                 [lo, hi](double v) { return v >= lo && v <= hi; });
}

void require_finite_numbers(CLI::App& app) {
  for (CLI::Option* opt : app.get_options())
    if (opt->get_type_name().rfind("FLOAT", 0) == 0) {
      CLI::Validator finite = numbers("a finite number", [](double) { return true; });
      opt->check(finite.description(""));  // the range checks already name themselves in --help
    }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) require_finite_numbers(*sub);
}

}  // namespace pupwave::cli
