#pragma once
// The deepest overlap of disks of diameter 1 (sigma) in the periodic box [-Lx/2, Lx/2) x
// [-Ly/2, Ly/2): how far a soft-contact state (LAMMPS's gran/hooke) has pressed two disks into
// each other. A state the contact itself made keeps every overlap near md.max_overlap (the
// contact is made so that a head-on collision at the fastest relative speed present reaches
// it); a far deeper one was not made by a run, and two disks on one spot make LAMMPS's contact
// force 0 * inf.
#include <vector>

namespace granvv::md {

struct DiskOverlap {
  long long first = -1, second = -1;  // rows of the two disks (first < second); -1: none overlap
  double depth = 0.0;                 // 1 - their centres' distance (sigma); 0: none overlap
};

// xyz: positions as triplets, z ignored; any real coordinates (they are taken modulo the box).
// Throws std::invalid_argument for a box shorter than 2 sigma along a side (the nearest image of
// an overlapping pair is then not unique) or for a non-finite coordinate. O(N) (a cell grid).
DiskOverlap deepest_overlap(const std::vector<double>& xyz, double box_length, double box_width);

}  // namespace granvv::md
