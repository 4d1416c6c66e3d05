#include "md_bridge/periodic_cells.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace granvv::md {

PeriodicCells::PeriodicCells(double box_length, double box_width, double min_width, int particles)
    : lx_(box_length), ly_(box_width) {
  nx_ = int(std::floor(box_length / min_width));
  ny_ = int(std::floor(box_width / min_width));
  if (!(nx_ >= 3 && ny_ >= 3)) {
    throw std::invalid_argument("a periodic cell grid needs a box of at least 3 x " +
                                std::to_string(min_width) + " sigma on each side (box " +
                                std::to_string(box_length) + " x " + std::to_string(box_width) +
                                ")");
  }
  // Few enough cells that the grid costs no more memory than the particles.
  const long long most = std::max(9LL, 4LL * particles);
  while (double(nx_) * ny_ > double(most) && nx_ > 3 && ny_ > 3) {
    nx_ = std::max(3, nx_ / 2);
    ny_ = std::max(3, ny_ / 2);
  }
  wx_ = lx_ / nx_;
  wy_ = ly_ / ny_;
  first_.assign(std::size_t(nx_) * std::size_t(ny_), -1);
  cell_.assign(std::size_t(particles), -1);
  next_.assign(std::size_t(particles), -1);
  previous_.assign(std::size_t(particles), -1);
}

int PeriodicCells::cell_at(double x, double y) const {
  const int cx = std::clamp(int(std::floor((x + 0.5 * lx_) / wx_)), 0, nx_ - 1);
  const int cy = std::clamp(int(std::floor((y + 0.5 * ly_) / wy_)), 0, ny_ - 1);
  return cy * nx_ + cx;
}

namespace {

// Column (or row) c + offset of n, and the image of its members: +1 past the last, -1 before
// the first.
std::pair<int, int> wrapped(int c, int n) {
  if (c < 0) return {c + n, -1};
  if (c >= n) return {c - n, 1};
  return {c, 0};
}

}  // namespace

PeriodicCells::Neighbour PeriodicCells::neighbour(int cx, int cy) const {
  const auto [x, wrap_x] = wrapped(cx, nx_);
  const auto [y, wrap_y] = wrapped(cy, ny_);
  return {y * nx_ + x, wrap_x, wrap_y};
}

std::array<PeriodicCells::Neighbour, 9> PeriodicCells::neighbourhood(int cell) const {
  const int cx = cell % nx_, cy = cell / nx_;
  std::array<Neighbour, 9> around{};
  int k = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) around[std::size_t(k++)] = neighbour(cx + dx, cy + dy);
  }
  return around;
}

std::array<PeriodicCells::Neighbour, 3> PeriodicCells::entering(int cell, int axis,
                                                                int direction) const {
  const int cx = cell % nx_, cy = cell / nx_;
  std::array<Neighbour, 3> joined{};
  for (int k = -1; k <= 1; ++k) {
    const int x = axis == 0 ? cx + direction : cx + k;
    const int y = axis == 0 ? cy + k : cy + direction;
    joined[std::size_t(k + 1)] = neighbour(x, y);
  }
  return joined;
}

int PeriodicCells::across(int cell, int axis, int direction, bool& wraps) const {
  int cx = cell % nx_, cy = cell / nx_;
  int& c = axis == 0 ? cx : cy;
  const int n = axis == 0 ? nx_ : ny_;
  c += direction;
  wraps = c < 0 || c >= n;
  c = (c + n) % n;
  return cy * nx_ + cx;
}

void PeriodicCells::clear() {
  std::fill(first_.begin(), first_.end(), -1);
  std::fill(cell_.begin(), cell_.end(), -1);
  std::fill(next_.begin(), next_.end(), -1);
  std::fill(previous_.begin(), previous_.end(), -1);
}

void PeriodicCells::insert(int particle, int cell) {
  const std::size_t p = std::size_t(particle);
  int& head = first_[std::size_t(cell)];
  cell_[p] = cell;
  previous_[p] = -1;
  next_[p] = head;
  if (head >= 0) previous_[std::size_t(head)] = particle;
  head = particle;
}

void PeriodicCells::remove(int particle) {
  const std::size_t p = std::size_t(particle);
  const int before = previous_[p], after = next_[p];
  if (before >= 0) {
    next_[std::size_t(before)] = after;
  } else {
    first_[std::size_t(cell_[p])] = after;
  }
  if (after >= 0) previous_[std::size_t(after)] = before;
}

void PeriodicCells::move(int particle, int to) {
  remove(particle);
  insert(particle, to);
}

}  // namespace granvv::md
