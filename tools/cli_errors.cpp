#include "tools/cli_errors.h"

#include <algorithm>
#include <vector>

namespace pupwave::cli {
namespace {

// Levenshtein edit distance.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The candidate nearest to `word`, if near enough to be a typo of it (empty otherwise).
std::string closest(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    const bool prefix = word.size() >= 3 && c.rfind(word, 0) == 0;  // "--thr" for "--threads"
    if (d < best_distance || (prefix && best.empty())) {
      best = c;
      best_distance = prefix ? 1 : d;
    }
  }
  return best;
}

// The innermost subcommand the command line selected (the app itself if none).
CLI::App* innermost(CLI::App& app) {
  CLI::App* at = &app;
  for (;;) {
    const auto parsed = at->get_subcommands();
    if (parsed.empty()) return at;
    at = parsed.back();
  }
}

std::vector<std::string> option_names(CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* opt : app.get_options()) {
    for (const std::string& n : opt->get_lnames()) names.push_back("--" + n);
    for (const std::string& n : opt->get_snames()) names.push_back("-" + n);
  }
  return names;
}

std::vector<std::string> subcommand_names(CLI::App& app) {
  std::vector<std::string> names;
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) names.push_back(sub->get_name());
  return names;
}

// A "did you mean" hint for the first unknown argument close to a known name.
std::string suggestion(CLI::App& app) {
  CLI::App* sub = innermost(app);
  std::vector<std::string> unknown = sub->remaining();
  for (const std::string& s : app.remaining()) unknown.push_back(s);
  for (std::string word : unknown) {
    if (word.size() > 1 && word[0] == '-') {
      word = word.substr(0, word.find('='));
      const std::string near = closest(word, option_names(*sub));
      if (!near.empty()) return "; did you mean " + near + "?";
    } else if (sub == &app) {
      const std::string near = closest(word, subcommand_names(app));
      if (!near.empty()) return "; did you mean '" + near + "'?";
    }
  }
  return {};
}

}  // namespace

std::string parse_error_message(CLI::App& app, const CLI::ParseError& error) {
  std::string message = error.what();
  if (message.empty()) message = error.get_name();
  return message + suggestion(app);
}

}  // namespace pupwave::cli
