#pragma once
// The image arguments of the bench tools (nonembedded_rd.cpp, train_priors.cpp).

#include <algorithm>
#include <filesystem>
#include <vector>

namespace pupwave::bench {

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

}  // namespace pupwave::bench
