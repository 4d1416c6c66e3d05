#pragma once
// A periodic grid of cells over the box [-Lx/2, Lx/2) x [-Ly/2, Ly/2) and which particles are in
// each. Cells are at least as wide as the largest interaction range, so every partner of a
// particle is in its own cell or one of the eight around it. A particle's cell changes only at
// its cell-crossing events, so its membership never depends on rounding of its position.
#include <array>
#include <vector>

#include "md_bridge/linked_lists.hpp"

namespace granvv::md {

class PeriodicCells {
 public:
  // Cells no narrower than min_width, and at least 3 along each side (std::invalid_argument
  // for a box narrower than 3 min_width).
  PeriodicCells(double box_length, double box_width, double min_width, int particles);

  int columns() const { return nx_; }
  int rows() const { return ny_; }
  double cell_length() const { return wx_; }
  double cell_width() const { return wy_; }
  // The cell of a position inside the box (clamped to the grid).
  int cell_at(double x, double y) const;
  // Lower edges of a particle's cell.
  double x_low(int particle) const { return -0.5 * lx_ + column_[std::size_t(particle)] * wx_; }
  double y_low(int particle) const { return -0.5 * ly_ + row_[std::size_t(particle)] * wy_; }
  // A cell next to another, and the periodic image in which its members lie next to it: seen
  // from the centre cell, a member at (x, y) is at (x + shift_x, y + shift_y), shift 0 or ±L.
  // The image is the cell's, not the nearest one: with 3 cells along a side, neighbours in
  // adjacent cells can be up to 2 cell widths = 2/3 of the box apart, farther than half the
  // box, and the nearest image of such a pair is not the one in which they can touch.
  struct Neighbour {
    int cell;
    double shift_x, shift_y;
  };
  // The nine cells around a particle's cell (itself included), periodic, row by row from
  // below; from its column and row, without a division (every prediction asks for it).
  static constexpr std::size_t kNeighbourhood = 9;
  std::array<Neighbour, kNeighbourhood> neighbourhood_of(int particle) const;
  // The three cells that join the neighbourhood of a particle that has just entered its cell
  // along axis 0 (x) or 1 (y) in `direction`: the far row or column of its new neighbourhood.
  std::array<Neighbour, 3> entering(int particle, int axis, int direction) const;
  // Moves a particle to the cell next to its own across a face (axis 0 (x) or 1 (y), direction
  // +1 or -1); true if that step wraps around the box (then its position moves by
  // -direction L).
  bool step(int particle, int axis, int direction);

  void clear();
  void insert(int particle, int cell);
  int cell_of(int particle) const {
    return row_[std::size_t(particle)] * nx_ + column_[std::size_t(particle)];
  }
  // The members of a cell as a list: first(cell), then next(particle) until -1; members() is
  // the array behind next() for loops that walk many lists.
  int first(int cell) const { return members_.first(std::size_t(cell)); }
  int next(int particle) const { return members_.next(particle); }
  const int* members() const { return members_.links(); }

 private:
  // The cell at column cx, row cy of the periodic grid (each at most one step outside it).
  Neighbour neighbour(int cx, int cy) const;
  void remove(int particle);
  double lx_, ly_, wx_, wy_;
  int nx_, ny_;
  // Doubly linked lists of the members (-1 ends them): a few integers per cell and particle,
  // so that the grid stays in cache beside the particles.
  LinkedLists members_;
  std::vector<int> column_, row_;  // per particle: its cell's, cell_of() = row nx + column
};

}  // namespace granvv::md
