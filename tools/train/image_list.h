#pragma once
// The image and list arguments of the prior trainers (train_priors.cpp, train_pc_priors.cpp).

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace pupwave::train {

// The .png files of a directory (sorted, so runs repeat) or the file itself.
inline void add_images(const std::filesystem::path& arg, std::vector<std::filesystem::path>& out) {
  if (!std::filesystem::is_directory(arg)) {
    out.push_back(arg);
    return;
  }
  std::vector<std::filesystem::path> found;
  for (const auto& e : std::filesystem::directory_iterator(arg))
    if (e.is_regular_file() && e.path().extension() == ".png") found.push_back(e.path());
  std::sort(found.begin(), found.end());
  out.insert(out.end(), found.begin(), found.end());
}

// The items of a comma-separated argument ("0.125,0.25,1").
inline std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

// A comma-separated list of numbers.
inline std::vector<double> number_list(const std::string& s) {
  std::vector<double> out;
  for (const std::string& item : split_list(s)) out.push_back(std::stod(item));
  return out;
}

}  // namespace pupwave::train
