#include "md_bridge/periodic_cells.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

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
  for (auto* per_particle : {&column_, &row_}) per_particle->assign(std::size_t(particles), -1);
  members_.reset(std::size_t(nx_) * std::size_t(ny_), std::size_t(particles));
}

int PeriodicCells::cell_at(double x, double y) const {
  const int cx = std::clamp(int(std::floor((x + 0.5 * lx_) / wx_)), 0, nx_ - 1);
  const int cy = std::clamp(int(std::floor((y + 0.5 * ly_) / wy_)), 0, ny_ - 1);
  return cy * nx_ + cx;
}

namespace {

// Column (or row) c of n, at most one step outside the grid, and the shift of its members'
// image: +length past the last, -length before the first.
struct Wrapped {
  int index;
  double shift;
};
Wrapped wrapped(int c, int n, double length) {
  if (c < 0) return {c + n, -length};
  if (c >= n) return {c - n, length};
  return {c, 0.0};
}

}  // namespace

PeriodicCells::Neighbour PeriodicCells::neighbour(int cx, int cy) const {
  const Wrapped x = wrapped(cx, nx_, lx_), y = wrapped(cy, ny_, ly_);
  return {y.index * nx_ + x.index, x.shift, y.shift};
}

std::array<PeriodicCells::Neighbour, PeriodicCells::kNeighbourhood> PeriodicCells::neighbourhood_of(
    int particle) const {
  const int cx = column_[std::size_t(particle)], cy = row_[std::size_t(particle)];
  std::array<Neighbour, kNeighbourhood> around{};
  int k = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) around[std::size_t(k++)] = neighbour(cx + dx, cy + dy);
  }
  return around;
}

std::array<PeriodicCells::Neighbour, 3> PeriodicCells::entering(int particle, int axis,
                                                                int direction) const {
  const int cx = column_[std::size_t(particle)], cy = row_[std::size_t(particle)];
  std::array<Neighbour, 3> joined{};
  for (int k = -1; k <= 1; ++k) {
    const int x = axis == 0 ? cx + direction : cx + k;
    const int y = axis == 0 ? cy + k : cy + direction;
    joined[std::size_t(k + 1)] = neighbour(x, y);
  }
  return joined;
}

bool PeriodicCells::step(int particle, int axis, int direction) {
  const std::size_t p = std::size_t(particle);
  int cx = column_[p], cy = row_[p];
  int& c = axis == 0 ? cx : cy;
  const int n = axis == 0 ? nx_ : ny_;
  c += direction;
  const bool wraps = c < 0 || c >= n;
  if (c < 0) c += n;
  if (c >= n) c -= n;
  remove(particle);
  column_[p] = cx;
  row_[p] = cy;
  members_.push_front(std::size_t(cell_of(particle)), particle);
  return wraps;
}

void PeriodicCells::clear() {
  for (auto* per_particle : {&column_, &row_})
    std::fill(per_particle->begin(), per_particle->end(), -1);
  members_.reset(std::size_t(nx_) * std::size_t(ny_), column_.size());
}

void PeriodicCells::insert(int particle, int cell) {
  column_[std::size_t(particle)] = cell % nx_;
  row_[std::size_t(particle)] = cell / nx_;
  members_.push_front(std::size_t(cell), particle);
}

void PeriodicCells::remove(int particle) {
  members_.remove(std::size_t(cell_of(particle)), particle);
}

}  // namespace granvv::md
