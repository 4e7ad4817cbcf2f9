// Shortest paths over cell centres (path_distances.hpp), by Dijkstra's algorithm.
#include "path_distances.hpp"

#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <utility>

namespace talus::test {

std::vector<double> path_distances(const std::vector<char>& passable, int width, int height, double cell,
                                   std::size_t start) {
  struct Move {
    int dr, dc;
    double length;  // m
  };
  std::vector<Move> moves;
  for (int dr = -2; dr <= 2; ++dr) {
    for (int dc = -2; dc <= 2; ++dc) {
      if ((dr != 0 || dc != 0) && std::gcd(std::abs(dr), std::abs(dc)) == 1) {
        moves.push_back({dr, dc, cell * std::hypot(dr, dc)});
      }
    }
  }
  std::vector<double> distance(passable.size(), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  distance[start] = 0.0;
  queue.push({0.0, start});
  const auto columns = static_cast<std::size_t>(width);
  while (!queue.empty()) {
    const auto [d, index] = queue.top();
    queue.pop();
    if (d > distance[index]) continue;
    const int row = static_cast<int>(index / columns), col = static_cast<int>(index % columns);
    for (const Move& m : moves) {
      const int r = row + m.dr, c = col + m.dc;
      if (r < 0 || r >= height || c < 0 || c >= width) continue;
      const std::size_t next = static_cast<std::size_t>(r) * columns + static_cast<std::size_t>(c);
      if (passable[next] && d + m.length < distance[next]) {
        distance[next] = d + m.length;
        queue.push({distance[next], next});
      }
    }
  }
  return distance;
}

}  // namespace talus::test
