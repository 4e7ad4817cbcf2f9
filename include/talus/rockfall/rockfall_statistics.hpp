// The statistical map of paper 3.4 for rock fall, per DEM cell over all trajectories:
// passages, the release sources they came from, reach probability, deposits, kinetic energy
// (max, 95th percentile over passages), jump height (95th percentile over passages), velocity
// (max), and energy lost by friction and by ground deformation (docs/hazard-statistics.md).
// Built from per-cell accumulators in src/hazard whose merge is exact and order-independent
// (integer counts, source sets, maxima, fixed-point sums, logarithmic histograms), so merged
// statistics are bit-identical for any thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "talus/core/byte_stream.hpp"
#include "talus/core/grid.hpp"
#include "talus/rockfall/envelope_convergence.hpp"
#include "talus/rockfall/trajectory_observer.hpp"

namespace talus {

struct RockfallLayers {
  Grid<float> reach_probability;        // - : passages / rocks released from the sources in source_count
  Grid<float> passages;                 // count of trajectories through the cell
  Grid<float> source_count;             // count of release sources with at least one rock through the cell
  Grid<float> deposits;                 // count of rocks (fragments included) stopped in the cell
  Grid<float> energy_max;               // kJ
  Grid<float> energy_p95;               // kJ
  Grid<float> jump_height_p95;          // m
  Grid<float> velocity_max;             // m/s
  Grid<float> energy_loss_friction;     // kJ lost in the cell, mean per simulated rock
  Grid<float> energy_loss_deformation;  // kJ lost in the cell, mean per simulated rock
};

class RockfallStatistics {
 public:
  // valid: the DEM (cells that are nodata there are nodata in every layer).
  explicit RockfallStatistics(const Grid<double>& dem);
  ~RockfallStatistics();
  RockfallStatistics(RockfallStatistics&&) noexcept;
  RockfallStatistics& operator=(RockfallStatistics&&) noexcept;

  // Adds every statistic of `other` (same grid) into this one.
  void merge(const RockfallStatistics& other);
  // For MPI ranks (core/byte_stream.hpp): every accumulator; read() into a new one of the same DEM.
  void write(ByteWriter& out) const;
  void read(ByteReader& in);
  std::uint64_t rocks() const;          // trajectories recorded
  RockfallLayers layers() const;

  // Records one trajectory at a time: pass it to a TrajectoryModel, then commit(source).
  class Recorder;
  Recorder recorder();

 private:
  struct Accumulators;
  std::unique_ptr<Accumulators> accumulators_;
};

// Gathers one trajectory (cells crossed between consecutive samples by a grid walk, the
// largest energy, jump height and speed per crossed cell, losses per cell, the stop cells) and
// adds it to its statistics on commit(source). A trajectory whose rock broke (paper fig. 4)
// counts once per cell however many of its fragments crossed it (passages, source count, reach
// probability, one energy and jump height per passage: the largest over its fragments), and once
// in `rocks`; every fragment that comes to rest counts as a deposit.
class RockfallStatistics::Recorder final : public TrajectoryObserver {
 public:
  explicit Recorder(RockfallStatistics& statistics);
  ~Recorder() override;
  void on_sample(const TrajectorySample& sample) override;
  void on_energy_loss(double x, double y, double friction, double deformation) override;
  void on_stop(const TrajectorySample& last, StopReason reason) override;
  void on_fragment(const TrajectorySample& start) override;
  // Appends the cells of the DEM's valid area that the trajectory crossed, each as one passage
  // with its largest kinetic energy there (J), to `cells`: its envelope (envelope_convergence.hpp).
  // Before commit.
  void append_envelope(std::vector<EnvelopeCell>& cells) const;
  // Adds the trajectory, released from release source `source` (0-based, as run_rockfall numbers
  // them), and resets the recorder for the next one.
  void commit(std::uint64_t source);
  // Forgets the trajectory recorded so far (one that failed numerically adds nothing) and resets
  // the recorder for the next one.
  void discard();

 private:
  struct Passage;
  RockfallStatistics& statistics_;
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace talus
