#pragma once
// A periodic grid of cells over the box [-Lx/2, Lx/2) x [-Ly/2, Ly/2) and which particles are in
// each. Cells are at least as wide as the largest interaction range, so every partner of a
// particle is in its own cell or one of the eight around it. A particle's cell changes only at
// its cell-crossing events, so its membership never depends on rounding of its position.
#include <array>
#include <vector>

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
  // Lower edges of a cell.
  double x_low(int cell) const { return -0.5 * lx_ + (cell % nx_) * wx_; }
  double y_low(int cell) const { return -0.5 * ly_ + (cell / nx_) * wy_; }
  // A cell next to another, and the periodic image in which its members lie next to it: seen
  // from the centre cell, a member at (x, y) is at (x + wrap_x Lx, y + wrap_y Ly). The image is
  // the cell's, not the nearest one: with 3 cells along a side, neighbours in adjacent cells can
  // be up to 2 cell widths = 2/3 of the box apart, farther than half the box, and the nearest
  // image of such a pair is not the one in which they can touch.
  struct Neighbour {
    int cell;
    int wrap_x, wrap_y;  // -1, 0 or +1
  };
  // The nine cells around a cell (itself included), periodic.
  std::array<Neighbour, 9> neighbourhood(int cell) const;
  // The three cells that join the neighbourhood of `cell` when a particle has just entered it
  // along axis 0 (x) or 1 (y) in `direction`: the far row or column of its new neighbourhood.
  std::array<Neighbour, 3> entering(int cell, int axis, int direction) const;
  // The cell next to `cell` across its face: axis 0 (x) or 1 (y), direction +1 or -1; and
  // whether that step wraps around the box (then the position moves by -direction L).
  int across(int cell, int axis, int direction, bool& wraps) const;

  void clear();
  void insert(int particle, int cell);
  void move(int particle, int to);
  int cell_of(int particle) const { return cell_[std::size_t(particle)]; }
  // The members of a cell as a list: first(cell), then next(particle) until -1.
  int first(int cell) const { return first_[std::size_t(cell)]; }
  int next(int particle) const { return next_[std::size_t(particle)]; }

 private:
  // The cell at column cx, row cy of the periodic grid (each at most one step outside it).
  Neighbour neighbour(int cx, int cy) const;
  void remove(int particle);
  double lx_, ly_, wx_, wy_;
  int nx_, ny_;
  // Doubly linked lists of the members (-1 ends them): a few integers per cell and particle,
  // so that the grid stays in cache beside the particles.
  std::vector<int> first_;
  std::vector<int> cell_, next_, previous_;  // per particle
};

}  // namespace granvv::md
