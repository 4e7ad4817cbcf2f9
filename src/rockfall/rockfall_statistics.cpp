// The statistical map of paper 3.4 ("Gathering simulation data") for rock fall, with the layers
// of docs/architecture.md section 3: a Recorder walks the cells under each trajectory's segments, keeps
// per-trajectory maxima and losses per cell, and commits them into exact per-cell accumulators
// (src/hazard), so statistics merged across threads are bit-identical to a single run.
#include "talus/rockfall/rockfall_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "talus/core/errors.hpp"
#include "talus/hazard/cell_counts.hpp"
#include "talus/hazard/cell_maxima.hpp"
#include "talus/hazard/cell_quantiles.hpp"
#include "talus/hazard/cell_source_sets.hpp"
#include "talus/hazard/fixed_point_sums.hpp"
#include "talus/hazard/log_binning.hpp"
#include "talus/hazard/segment_cells.hpp"
#include "talus/hazard/zeroed_vector.hpp"

namespace talus {

namespace {
constexpr double kLayerNodata = -9999.0;
constexpr double kLossQuantum = 1e-3;        // J: energy losses are summed in millijoules
constexpr double kQuantile = 0.95;           // energy_p95, jump_height_p95
constexpr double kJoulesPerKilojoule = 1000.0;
// Quantile bins, 20 per decade (bin ratio 1.122): kinetic energy 0.01 J .. 1 TJ, jump height
// 1 mm .. 10 km; values below the range count as 0.
LogBinning energy_binning() { return LogBinning(1e-2, 1e12, 20); }
LogBinning jump_height_binning() { return LogBinning(1e-3, 1e4, 20); }
}  // namespace

struct RockfallStatistics::Accumulators {
  explicit Accumulators(const Grid<double>& dem)
      : spec(dem.spec()), valid(dem.size()), passages(dem.size()), sources(dem.size()), deposits(dem.size()),
        energy_max(dem.size()), velocity_max(dem.size()), energy(dem.size(), energy_binning()),
        jump_height(dem.size(), jump_height_binning()), friction(dem.size(), kLossQuantum),
        deformation(dem.size(), kLossQuantum) {
    spec.nodata = kLayerNodata;
    for (std::size_t i = 0; i < dem.size(); ++i) valid[i] = dem.is_valid(i) ? 1 : 0;
  }

  GridSpec spec;                        // the DEM's grid with the layers' nodata
  std::vector<std::uint8_t> valid;      // 1 where the DEM has an elevation
  std::uint64_t rocks = 0;
  std::vector<std::uint64_t> rocks_per_source;   // trajectories committed, by release source
  CellCounts passages;
  CellSourceSets sources;               // release sources with a passage through the cell
  CellCounts deposits;
  CellMaxima energy_max;                // J
  CellMaxima velocity_max;              // m/s
  CellQuantiles energy;                 // J, one value per passage
  CellQuantiles jump_height;            // m, one value per passage
  FixedPointSums friction;              // J
  FixedPointSums deformation;           // J
};

RockfallStatistics::RockfallStatistics(const Grid<double>& dem) : accumulators_(std::make_unique<Accumulators>(dem)) {}
RockfallStatistics::~RockfallStatistics() = default;
RockfallStatistics::RockfallStatistics(RockfallStatistics&&) noexcept = default;
RockfallStatistics& RockfallStatistics::operator=(RockfallStatistics&&) noexcept = default;

void RockfallStatistics::merge(const RockfallStatistics& other) {
  Accumulators& a = *accumulators_;
  const Accumulators& b = *other.accumulators_;
  require_same_grid(a.spec, b.spec, "merging rock-fall statistics");
  a.rocks += b.rocks;
  if (a.rocks_per_source.size() < b.rocks_per_source.size()) a.rocks_per_source.resize(b.rocks_per_source.size(), 0);
  for (std::size_t s = 0; s < b.rocks_per_source.size(); ++s) a.rocks_per_source[s] += b.rocks_per_source[s];
  a.passages.merge(b.passages);
  a.sources.merge(b.sources);
  a.deposits.merge(b.deposits);
  a.energy_max.merge(b.energy_max);
  a.velocity_max.merge(b.velocity_max);
  a.energy.merge(b.energy);
  a.jump_height.merge(b.jump_height);
  a.friction.merge(b.friction);
  a.deformation.merge(b.deformation);
}

void RockfallStatistics::write(ByteWriter& out) const {
  const Accumulators& a = *accumulators_;
  out.put(a.rocks);
  out.put_vector(a.rocks_per_source);
  a.passages.write(out);
  a.sources.write(out);
  a.deposits.write(out);
  a.energy_max.write(out);
  a.velocity_max.write(out);
  a.energy.write(out);
  a.jump_height.write(out);
  a.friction.write(out);
  a.deformation.write(out);
}

void RockfallStatistics::read(ByteReader& in) {
  Accumulators& a = *accumulators_;
  a.rocks = in.get<std::uint64_t>();
  in.get_vector(a.rocks_per_source);
  a.passages.read(in);
  a.sources.read(in);
  a.deposits.read(in);
  a.energy_max.read(in);
  a.velocity_max.read(in);
  a.energy.read(in);
  a.jump_height.read(in);
  a.friction.read(in);
  a.deformation.read(in);
}

std::uint64_t RockfallStatistics::rocks() const { return accumulators_->rocks; }

RockfallLayers RockfallStatistics::layers() const {
  const Accumulators& a = *accumulators_;
  if (a.friction.saturated() || a.deformation.saturated()) {
    throw NumericalFailure("rock-fall statistics: a cell's energy-loss sum left the range of 64-bit millijoules");
  }
  RockfallLayers out{Grid<float>(a.spec), Grid<float>(a.spec), Grid<float>(a.spec), Grid<float>(a.spec),
                     Grid<float>(a.spec), Grid<float>(a.spec), Grid<float>(a.spec),
                     Grid<float>(a.spec), Grid<float>(a.spec), Grid<float>(a.spec)};
  Grid<float>* const all[] = {&out.reach_probability, &out.passages, &out.source_count, &out.deposits,
                              &out.energy_max, &out.energy_p95, &out.jump_height_p95,
                              &out.velocity_max, &out.energy_loss_friction, &out.energy_loss_deformation};
  // rocks_before[s]: trajectories of the sources before s, so that the rocks released from the
  // sources first..last are rocks_before[last + 1] - rocks_before[first].
  std::vector<std::uint64_t> rocks_before(a.rocks_per_source.size() + 1, 0);
  for (std::size_t s = 0; s < a.rocks_per_source.size(); ++s) {
    rocks_before[s + 1] = rocks_before[s] + a.rocks_per_source[s];
  }
  const double rocks = static_cast<double>(a.rocks);
  const auto per_rock = [rocks](double value) { return rocks > 0 ? value / rocks : 0.0; };
  const auto f = [](double value) { return static_cast<float>(value); };
  for (std::size_t i = 0; i < a.valid.size(); ++i) {
    if (!a.valid[i]) {
      for (Grid<float>* layer : all) (*layer)[i] = static_cast<float>(kLayerNodata);
      continue;
    }
    // Passages over the rocks released from the sources that reached the cell (Rockyfor3D's
    // Reach_probability, as a share; docs/hazard-statistics.md, "Reach probability and the
    // sources that reach a cell").
    std::uint64_t contributing_rocks = 0;
    for (const SourceInterval& s : a.sources.intervals(i)) {
      contributing_rocks += rocks_before[std::size_t{s.last} + 1] - rocks_before[s.first];
    }
    const double passages = a.passages[i];
    out.reach_probability[i] = contributing_rocks > 0 ? f(passages / static_cast<double>(contributing_rocks)) : 0.0f;
    out.passages[i] = f(passages);
    out.source_count[i] = f(static_cast<double>(a.sources.count(i)));
    out.deposits[i] = f(a.deposits[i]);
    out.energy_max[i] = f(a.energy_max[i] / kJoulesPerKilojoule);
    out.energy_p95[i] = f(a.energy.quantile(i, kQuantile) / kJoulesPerKilojoule);
    out.jump_height_p95[i] = f(a.jump_height.quantile(i, kQuantile));
    out.velocity_max[i] = a.velocity_max[i];
    out.energy_loss_friction[i] = f(per_rock(a.friction.total(i)) / kJoulesPerKilojoule);
    out.energy_loss_deformation[i] = f(per_rock(a.deformation.total(i)) / kJoulesPerKilojoule);
  }
  return out;
}

RockfallStatistics::Recorder RockfallStatistics::recorder() { return Recorder(*this); }

// What one trajectory left in one cell.
struct RockfallStatistics::Recorder::Passage {
  std::uint32_t cell = 0;
  bool crossed = false;        // the path crossed the cell (false: only losses were reported there)
  double energy = 0;           // J, largest kinetic energy in the cell
  double jump_height = 0;      // m, largest jump height in the cell
  double speed = 0;            // m/s, largest speed in the cell
  double friction = 0;         // J lost in the cell
  double deformation = 0;      // J lost in the cell
};

// Per-trajectory scratch, reused from one trajectory to the next: the cells touched so far as
// a sparse set (entry_of_cell needs no clearing: an entry counts only if it points back).
struct RockfallStatistics::Recorder::State {
  explicit State(const GridSpec& spec) : frame(spec), entry_of_cell(spec.cell_count()) {}

  Passage& passage(std::size_t cell) {
    const std::uint32_t entry = entry_of_cell[cell];
    if (entry < passages.size() && passages[entry].cell == cell) return passages[entry];
    entry_of_cell[cell] = static_cast<std::uint32_t>(passages.size());
    Passage& added = passages.emplace_back();
    added.cell = static_cast<std::uint32_t>(cell);
    return added;
  }
  void cross(int col, int row, double energy, double jump_height, double speed) {
    Passage& p = passage(static_cast<std::size_t>(row) * static_cast<std::size_t>(frame.width()) +
                         static_cast<std::size_t>(col));
    p.crossed = true;
    p.energy = std::max(p.energy, energy);
    p.jump_height = std::max(p.jump_height, jump_height);
    p.speed = std::max(p.speed, speed);
  }
  // The cell holding (x, y), or -1 outside the grid.
  std::ptrdiff_t cell_of(double x, double y) const {
    const double u = frame.u(x);
    const double v = frame.v(y);
    if (!frame.inside(u, v)) return -1;
    return static_cast<std::ptrdiff_t>(floor_to_int(v)) * frame.width() + floor_to_int(u);
  }

  // Joins the sample to the previous one by a segment and updates every cell it crosses with
  // the largest of the energy, jump height and speed interpolated linearly along the segment
  // at the cell's entry and exit points.
  void sample(const TrajectorySample& s) {
    const double u = frame.u(s.position.x());
    const double v = frame.v(s.position.y());
    const double e = s.kinetic_energy;
    const double h = s.jump_height;
    const double w = s.velocity.norm();
    const bool inside = frame.inside(u, v);
    if (!has_previous || (inside && frame.inside(previous.u, previous.v) && floor_to_int(u) == floor_to_int(previous.u) &&
                          floor_to_int(v) == floor_to_int(previous.v))) {
      // The first sample, or a segment within one cell: the previous end is already counted.
      if (inside) cross(floor_to_int(u), floor_to_int(v), e, h, w);
    } else {
      const Point& p = previous;
      // Values are linear in t, so the larger of the entry and exit values is the cell's largest.
      const auto largest = [](double start, double change, double t0, double t1) {
        return start + change * (change >= 0 ? t1 : t0);
      };
      const double de = e - p.energy;
      const double dh = h - p.jump_height;
      const double dw = w - p.speed;
      walk_segment_cells(p.u, p.v, u, v, frame.width(), frame.height(), [&](int col, int row, double t0, double t1) {
        cross(col, row, largest(p.energy, de, t0, t1), largest(p.jump_height, dh, t0, t1), largest(p.speed, dw, t0, t1));
      });
    }
    previous = Point{u, v, e, h, w};
    has_previous = true;
  }

  void reset() {
    passages.clear();
    has_previous = false;
    deposit_cells.clear();
  }

  struct Point {
    double u, v, energy, jump_height, speed;
  };
  CellFrame frame;
  ZeroedVector<std::uint32_t> entry_of_cell;  // per grid cell: index in passages, if it points back
  std::vector<Passage> passages;              // cells touched by the current trajectory
  bool has_previous = false;
  Point previous{};
  std::vector<std::size_t> deposit_cells;     // where the trajectory's fragments came to rest
};

RockfallStatistics::Recorder::Recorder(RockfallStatistics& statistics)
    : statistics_(statistics), state_(std::make_unique<State>(statistics.accumulators_->spec)) {}
RockfallStatistics::Recorder::~Recorder() = default;

void RockfallStatistics::Recorder::on_sample(const TrajectorySample& sample) { state_->sample(sample); }

void RockfallStatistics::Recorder::on_energy_loss(double x, double y, double friction, double deformation) {
  const std::ptrdiff_t cell = state_->cell_of(x, y);
  if (cell < 0) return;
  Passage& p = state_->passage(static_cast<std::size_t>(cell));
  p.friction += friction;
  p.deformation += deformation;
}

void RockfallStatistics::Recorder::on_stop(const TrajectorySample& last, StopReason reason) {
  state_->sample(last);
  const std::ptrdiff_t cell = state_->cell_of(last.position.x(), last.position.y());
  if (reason == StopReason::at_rest && cell >= 0) state_->deposit_cells.push_back(static_cast<std::size_t>(cell));
}

// Paper fig. 4: a fragment's path starts anew at its first sample, not joined to the last one.
void RockfallStatistics::Recorder::on_fragment(const TrajectorySample& start) {
  state_->has_previous = false;
  state_->sample(start);
}

void RockfallStatistics::Recorder::append_envelope(std::vector<EnvelopeCell>& cells) const {
  const std::vector<std::uint8_t>& valid = statistics_.accumulators_->valid;
  for (const Passage& p : state_->passages) {
    if (p.crossed && valid[p.cell]) cells.push_back({p.cell, 1, static_cast<std::uint64_t>(std::llround(p.energy))});
  }
}

void RockfallStatistics::Recorder::commit(std::uint64_t source) {
  if (source >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("rock-fall statistics: release source " + std::to_string(source) +
                                " beyond 32-bit numbers");
  }
  Accumulators& a = *statistics_.accumulators_;
  const auto source_number = static_cast<std::uint32_t>(source);
  if (a.rocks_per_source.size() <= source) a.rocks_per_source.resize(source + 1, 0);
  ++a.rocks_per_source[source];
  for (const Passage& p : state_->passages) {
    const std::size_t cell = p.cell;
    if (!a.valid[cell]) continue;
    if (p.crossed) {
      a.passages.add(cell);
      a.sources.add(cell, source_number);
      a.energy_max.add(cell, p.energy);
      a.velocity_max.add(cell, p.speed);
      a.energy.add(cell, p.energy);
      a.jump_height.add(cell, p.jump_height);
    }
    if (p.friction != 0) a.friction.add(cell, p.friction);
    if (p.deformation != 0) a.deformation.add(cell, p.deformation);
  }
  for (const std::size_t deposit : state_->deposit_cells) {
    if (a.valid[deposit]) a.deposits.add(deposit);
  }
  ++a.rocks;
  state_->reset();
}

void RockfallStatistics::Recorder::discard() { state_->reset(); }

}  // namespace talus
