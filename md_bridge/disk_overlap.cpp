#include "md_bridge/disk_overlap.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "md_bridge/particle_scene.hpp"

namespace granvv::md {

DiskOverlap deepest_overlap(const std::vector<double>& xyz, double box_length, double box_width) {
  if (!(box_length >= 2.0 && box_width >= 2.0))
    throw std::invalid_argument("deepest_overlap: a box of " + std::to_string(box_length) + " x " +
                                std::to_string(box_width) + " sigma (at least 2 along each side)");
  const std::size_t n = xyz.size() / 3;
  // Cells at least one diameter wide, so that overlapping disks are in one cell or neighbours;
  // wider where the box is large and the disks few (a few cells per disk at most).
  int columns = std::max(1, int(std::floor(box_length)));
  int rows = std::max(1, int(std::floor(box_width)));
  while (double(columns) * rows > 4.0 * double(n) + 64.0) {
    columns = std::max(1, columns / 2);
    rows = std::max(1, rows / 2);
  }
  const double cell_length = box_length / columns, cell_width = box_width / rows;
  std::vector<double> x(n), y(n);
  std::vector<int> cell(n);
  std::vector<std::size_t> start(std::size_t(columns) * rows + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(xyz[3 * i]) || !std::isfinite(xyz[3 * i + 1]))
      throw std::invalid_argument("deepest_overlap: disk " + std::to_string(i) +
                                  " has a non-finite coordinate");
    x[i] = periodic_image(xyz[3 * i], box_length);
    y[i] = periodic_image(xyz[3 * i + 1], box_width);
    const int c = std::min(columns - 1, int((x[i] + 0.5 * box_length) / cell_length));
    const int r = std::min(rows - 1, int((y[i] + 0.5 * box_width) / cell_width));
    cell[i] = r * columns + c;
    ++start[std::size_t(cell[i]) + 1];
  }
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<std::size_t> members(n), fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) members[fill[std::size_t(cell[i])]++] = i;

  const auto nearest = [](double d, double length) { return d - length * std::round(d / length); };
  DiskOverlap deepest;
  for (std::size_t i = 0; i < n; ++i) {
    const int c = cell[i] % columns, r = cell[i] / columns;
    int around[9], count = 0;  // the cells around i's, each once (a side of 1 or 2 cells wraps)
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const int k = ((r + dr + rows) % rows) * columns + (c + dc + columns) % columns;
        if (std::find(around, around + count, k) == around + count) around[count++] = k;
      }
    }
    for (int a = 0; a < count; ++a) {
      for (std::size_t m = start[std::size_t(around[a])]; m < start[std::size_t(around[a]) + 1];
           ++m) {
        const std::size_t j = members[m];
        if (j <= i) continue;
        const double dx = nearest(x[i] - x[j], box_length), dy = nearest(y[i] - y[j], box_width);
        const double depth = 1.0 - std::sqrt(dx * dx + dy * dy);
        if (depth > deepest.depth) deepest = {(long long)i, (long long)j, depth};
      }
    }
  }
  return deepest;
}

}  // namespace granvv::md
