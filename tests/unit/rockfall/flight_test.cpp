// Tests of the flight integrator (paper 3.1, 3.2): the exact parabola without drag, fourth-order
// convergence of the RK4 step with drag, and the step-length bound.
#include "talus/rockfall/flight.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace talus {
namespace {

constexpr double kG = 9.81;

TEST(Flight, WithoutDragTheStepIsTheExactParabola) {
  const Flight flight(kG, AirDrag{1.225, 0.0, 1.0}, 100.0);
  EXPECT_FALSE(flight.has_drag());
  EXPECT_TRUE(std::isinf(flight.max_duration(Eigen::Vector3d(10, 0, 0))));
  const PointState start{{1.0, 2.0, 30.0}, {4.0, -3.0, 7.0}};
  for (const double t : {0.01, 0.5, 3.7}) {
    const PointState end = flight.advance(start, t);
    const Eigen::Vector3d x = start.position + t * start.velocity - 0.5 * kG * t * t * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d v = start.velocity - kG * t * Eigen::Vector3d::UnitZ();
    EXPECT_LT((end.position - x).norm(), 1e-12);
    EXPECT_LT((end.velocity - v).norm(), 1e-12);
  }
}

// Vertical fall from rest with drag: v(t) = v_t tanh(g t / v_t).
TEST(Flight, RungeKuttaStepConvergesAtFourthOrder) {
  const double mass = 2.0;
  const AirDrag drag{1.225, 0.5, 0.05};
  const Flight flight(kG, drag, mass);
  ASSERT_TRUE(flight.has_drag());
  const double terminal = std::sqrt(kG / drag.per_mass(mass));
  const auto error = [&](double t) {
    const PointState end = flight.advance({{0, 0, 0}, {0, 0, 0}}, t);
    return std::abs(-end.velocity.z() - terminal * std::tanh(kG * t / terminal));
  };
  // One step of h has a local error of order h^5: halving h divides it by about 32.
  const double ratio = error(0.4) / error(0.2);
  EXPECT_GT(ratio, 24.0);
  EXPECT_LT(ratio, 40.0);
  // At the longest step it allows, the relative error stays far below 1e-6.
  const double h = flight.max_duration(Eigen::Vector3d::Zero());
  EXPECT_LT(error(h) / (kG * h), 1e-8);
}

TEST(Flight, DurationForLengthSolvesTheQuadratic) {
  for (const double speed : {0.0, 0.3, 12.0}) {
    for (const double a : {0.0, 9.81, 40.0}) {
      if (speed == 0.0 && a == 0.0) continue;
      const double t = duration_for_length(speed, a, 1.5);
      EXPECT_NEAR(speed * t + 0.5 * a * t * t, 1.5, 1e-12) << speed << " " << a;
    }
  }
  const AirDrag drag{1.225, 0.1, 0.8};
  const Flight flight(kG, drag, 1400.0);
  const Eigen::Vector3d v(30.0, 0.0, -40.0);
  EXPECT_NEAR(flight.acceleration_bound(v), kG + drag.per_mass(1400.0) * 2500.0, 1e-12);
}

TEST(FlightArc, ReproducesTheParabolaAndFollowsTheDragStep) {
  // Without drag the cubic Hermite arc is the exact parabola (1e-12 m, rounding only).
  const Flight free_flight(kG, AirDrag{1.225, 0.0, 0.8}, 1400.0);
  const PointState start{{1.0, 2.0, 30.0}, {12.0, -3.0, 8.0}};
  const double duration = 1.7;
  const FlightArc arc(start, free_flight.advance(start, duration), duration);
  for (const double tau : {0.0, 0.3, 0.85, 1.2, 1.7}) {
    const PointState exact = free_flight.advance(start, tau);
    EXPECT_LT((arc.at(tau).position - exact.position).norm(), 1e-12) << tau;
    EXPECT_LT((arc.at(tau).velocity - exact.velocity).norm(), 1e-12) << tau;
  }
  // With strong drag (a light rock, k = 0.012 1/m) over the longest step flight allows at its
  // speed (max_duration, 0.03 s), the arc stays within 1e-7 m of the RK4 state at the same time.
  const Flight dragged(kG, AirDrag{1.225, 1.0, 0.02}, 1.0);
  const PointState fast{{0.0, 0.0, 0.0}, {25.0, 0.0, 10.0}};
  const double step = dragged.max_duration(fast.velocity);
  const FlightArc dragged_arc(fast, dragged.advance(fast, step), step);
  for (const double tau : {0.25 * step, 0.5 * step, 0.75 * step}) {
    EXPECT_LT((dragged_arc.at(tau).position - dragged.advance(fast, tau).position).norm(), 1e-7) << tau;
  }
}

TEST(FlightArc, PositionIsTheStatesPositionBitForBit) {
  // The crossing searches ask only for the position; it must be at(tau)'s exactly (tolerance
  // zero), so that a landing found with it lies where the state says.
  const Flight dragged(kG, AirDrag{1.225, 0.1, 0.8}, 1400.0);
  const PointState start{{612000.5, 5102000.25, 1830.0}, {11.0, -6.5, 4.0}};
  const double duration = 0.09;
  const FlightArc arc(start, dragged.advance(start, duration), duration);
  for (const double tau : {0.0, 1e-9, 0.013, 0.045, 0.0899999, 0.09}) {
    const PointState state = arc.at(tau);
    EXPECT_EQ(arc.position(tau), state.position) << tau;
  }
  const FlightArc instant(start, start, 0.0);
  EXPECT_EQ(instant.position(0.0), start.position);
}

}  // namespace
}  // namespace talus
