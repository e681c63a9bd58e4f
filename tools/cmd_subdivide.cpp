// `pupwave subdivide`: variational subdivision of a 2-D polyline (Kobbelt-Schroder schemes).
// Reads "x y" per line, writes "x y" per line to stdout or atomically to -o.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/atomic_file.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "transforms/kobbelt/subdivision.h"

namespace pupwave::cli {
namespace {

using kobbelt::Point2;

struct SubdivideOptions {
  std::string scheme = "k2";
  int levels = 1;
  bool closed = false;
  std::string parameterization = "uniform";
  std::string input;
  std::string output;
  Verbosity verbosity;  // accepted as on every command; the points are data, never silenced
};

// Parses one number of a point line; the whole token must be a finite number.
double parse_coordinate(const std::string& token, const std::string& where) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(token.c_str(), &end);
  if (token.empty() || end != token.c_str() + token.size() || errno == ERANGE || !std::isfinite(v)) {
    throw std::runtime_error(where + ": '" + token + "' is not a finite number");
  }
  return v;
}

// "x y" per line; blank lines and lines starting with '#' are skipped.
std::vector<Point2> read_points(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read points file " + path);
  std::vector<Point2> points;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string t; fields >> t;) tokens.push_back(t);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    const std::string where = path + ":" + std::to_string(number);
    if (tokens.size() != 2) throw std::runtime_error(where + ": expected 'x y', got '" + line + "'");
    points.push_back({parse_coordinate(tokens[0], where), parse_coordinate(tokens[1], where)});
  }
  if (in.bad()) throw std::runtime_error("error reading " + path);
  return points;
}

void write_points(std::ostream& out, const std::vector<Point2>& points) {
  char buf[64];
  for (const Point2& p : points) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g\n", p.x, p.y);
    out << buf;
  }
}

kobbelt::Parameterization parse_parameterization(const std::string& name) {
  if (name == "uniform") return kobbelt::Parameterization::uniform;
  if (name == "centripetal") return kobbelt::Parameterization::centripetal;
  throw std::invalid_argument("unknown parameterization '" + name + "' (valid: uniform, centripetal)");
}

void run_subdivide(const SubdivideOptions& opt) {
  if (!opt.output.empty() && !is_stdio(opt.output)) check_output_path(opt.output);
  kobbelt::SubdivisionOptions so;
  so.scheme = kobbelt::parse_scheme(opt.scheme);
  so.levels = opt.levels;
  so.closed = opt.closed;
  so.parameterization = parse_parameterization(opt.parameterization);
  const std::vector<Point2> points = read_points(InputPath(opt.input).path);
  if (points.size() < 2) {
    throw std::invalid_argument(opt.input + ": subdivision needs at least 2 points, found " +
                                std::to_string(points.size()));
  }
  const std::vector<Point2> refined = kobbelt::subdivide(points, so);
  if (opt.output.empty() || is_stdio(opt.output)) {
    write_points(std::cout, refined);
    return;
  }
  write_output(opt.output, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp);
    write_points(out, refined);
    out.close();
    if (!out) throw_write_error(temp);
  });
}

}  // namespace

void add_subdivide_command(CLI::App& app) {
  auto opt = std::make_shared<SubdivideOptions>();
  auto* cmd = app.add_subcommand(
      "subdivide", "Variational subdivision of a 2-D polyline (x y per line) with a Kobbelt scheme");
  cmd->add_option("--scheme", opt->scheme, "k2, k3, kspl or k4pt")->capture_default_str();
  cmd->add_option("--levels", opt->levels, "refinement levels, 0..12")->capture_default_str();
  cmd->add_flag("--closed", opt->closed, "treat the points as a closed polygon");
  cmd->add_option("--param", opt->parameterization, "uniform, or centripetal (k2 and k3 only)")
      ->capture_default_str();
  cmd->add_option("POINTS", opt->input, "input file, 'x y' per line, or - for stdin")->required();
  cmd->add_option("-o,--output", opt->output, "output file, or - for stdout (the default)");
  add_verbosity_flags(*cmd, opt->verbosity);
  cmd->callback([opt] { run_subdivide(*opt); });
}

}  // namespace pupwave::cli
