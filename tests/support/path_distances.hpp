// Distances along the ground for the real-case validations (tests/cases): the shortest path
// through the passable cells of a grid, over cell centres with the 16 moves of a chess king and
// knight (at most 2.7% longer than straight). validation/avaalr_com1dfa/compare.py and
// validation/empirical_laws/empirical_laws.py measure runouts the same way.
#pragma once

#include <cstddef>
#include <vector>

namespace talus::test {

// Horizontal distance (m) from cell `start` to every cell of a width x height grid of cells
// `cell` m wide (row by row), infinity where no passable path leads.
std::vector<double> path_distances(const std::vector<char>& passable, int width, int height, double cell,
                                   std::size_t start);

}  // namespace talus::test
