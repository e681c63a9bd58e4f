#include "transforms/transform1d.h"

#include <stdexcept>
#include <vector>

namespace pupwave {

void Transform1D::analyze(std::span<int32_t>) const {
  throw std::logic_error("transform " + spec() + " has no reversible integer form");
}

void Transform1D::synthesize(std::span<int32_t>) const {
  throw std::logic_error("transform " + spec() + " has no reversible integer form");
}

namespace {

// Copies each column of the block to a line, runs the 1-D transform, and copies it back.
template <class T, class Run>
void each_column(std::span<T> block, std::size_t width, Run&& run) {
  if (width == 0) return;
  const std::size_t n = block.size() / width;
  // Its own buffer: thread_scratch slots are the 1-D transforms' (Kobbelt uses both).
  thread_local std::vector<T> buffer;
  if (buffer.size() < n) buffer.resize(n);
  const std::span<T> line(buffer.data(), n);
  for (std::size_t c = 0; c < width; ++c) {
    for (std::size_t i = 0; i < n; ++i) line[i] = block[i * width + c];
    run(line);
    for (std::size_t i = 0; i < n; ++i) block[i * width + c] = line[i];
  }
}

}  // namespace

void Transform1D::analyze_columns(std::span<float> block, std::size_t width) const {
  each_column(block, width, [&](std::span<float> line) { analyze(line); });
}
void Transform1D::synthesize_columns(std::span<float> block, std::size_t width) const {
  each_column(block, width, [&](std::span<float> line) { synthesize(line); });
}
void Transform1D::analyze_columns(std::span<double> block, std::size_t width) const {
  each_column(block, width, [&](std::span<double> line) { analyze(line); });
}
void Transform1D::synthesize_columns(std::span<double> block, std::size_t width) const {
  each_column(block, width, [&](std::span<double> line) { synthesize(line); });
}
void Transform1D::analyze_columns(std::span<int32_t> block, std::size_t width) const {
  each_column(block, width, [&](std::span<int32_t> line) { analyze(line); });
}
void Transform1D::synthesize_columns(std::span<int32_t> block, std::size_t width) const {
  each_column(block, width, [&](std::span<int32_t> line) { synthesize(line); });
}

}  // namespace pupwave
