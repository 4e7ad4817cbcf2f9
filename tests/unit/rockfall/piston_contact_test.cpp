// Tests of the rock against the piston carpet (paper 3.3, steps 1-4): pistons pushed to the
// rock's surface by bisection, the force as minus the gradient of the pistons' energy, pistons
// released to their footprint, the journal that undoes a press, friction and vegetation.
#include "talus/rockfall/piston_contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "../../validation/full_model_scenes.hpp"
#include "talus/rockfall/fracture.hpp"

namespace talus {
namespace {

constexpr double kSpacing = 0.125;  // m

struct Scene {
  GroundModel model;
  PerturbedGround ground{model, nullptr};
  PistonCarpet carpet{ground, kSpacing};
  PistonRange range;
  explicit Scene(double gradient, const GroundMaterial& soil)
      : model(full_model_scenes::inclined_plane(20, 20, 5.0, 10.0, gradient, soil)) {
    carpet.cover(47.9, 52.1, -52.1, -47.9);  // lattice 384..416 x -416..-384
    range.gather(carpet, carpet.window());
  }
};

RigidRock make_body(BlockShape shape, const Eigen::Vector3d& axes) {
  return RigidRock(full_model_scenes::block(shape, axes), 256, 32);
}

TEST(PistonContact, SpherePushesEachPistonToItsSurface) {
  Scene scene(0.0, full_model_scenes::talus_soil());
  const RigidRock body = make_body(BlockShape::sphere, Eigen::Vector3d::Constant(1.0));
  const Eigen::Vector3d centre(50.0, -50.0, 10.0 + 0.5 - 0.02);  // 2 cm into the ground
  NormalResponse response;
  std::vector<PistonChange> journal;
  press_carpet(scene.carpet, scene.range, body, centre, Eigen::Matrix3d::Identity(), {}, {}, response, journal);
  ASSERT_GT(response.touches.size(), 4u);
  double vertical = 0.0;
  for (const PistonTouch& touch : response.touches) {
    const Piston& piston = scene.carpet.at(touch.i, touch.j);
    const Eigen::Vector2d offset = piston.rest_top.head<2>() - centre.head<2>();
    // The sphere's underside above this piston: d = z_ground - (z_c - sqrt(r^2 - rho^2)).
    const double expected = 10.0 - (centre.z() - std::sqrt(0.25 - offset.squaredNorm()));
    EXPECT_NEAR(piston.state.compression, expected, 2e-9);  // bisection to 1e-9 m
    // Flat ground: the load's vertical part is p A.
    EXPECT_NEAR(touch.load * touch.normal.z(), pressure(piston.cycle, piston.state) * piston.area,
                1e-9 * touch.load);
    vertical += touch.load * touch.normal.z();
  }
  EXPECT_NEAR(response.force.z(), vertical, 1e-9 * vertical);
  // Centred over a lattice point: the horizontal parts and the torque cancel.
  EXPECT_LT(response.force.head<2>().norm(), 1e-9 * vertical);
  EXPECT_LT(response.torque.norm(), 1e-9 * vertical);
  EXPECT_GT(response.dissipated, 0.0);        // the talus yields at 8 mm
  EXPECT_EQ(journal.size(), response.touches.size());
}

// Paper 3.3, step 3: with elastic pistons (k3 = k1) the energy of the carpet depends on the rock's
// position only, and the force and torque are minus its gradient, for a tilted ellipsoid on a
// slope (pistons along the inclined normal). Central differences of 1e-4 m and 1e-4 rad: the
// bisection's 1e-9 m on each compression makes the energy noisy by ~1e-4 J, ~1 N over 2e-4 m,
// and the differences' own error is of order h^2; 2e-5 of the force bounds both.
TEST(PistonContact, ForceAndTorqueAreMinusTheGradientOfThePistonsEnergy) {
  const GroundMaterial soil = full_model_scenes::elastic_soil(1.0e8, 0.0);
  const RigidRock body = make_body(BlockShape::ellipsoid, {1.4, 1.0, 0.7});
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1.0, 0.5, -0.3).normalized()).toRotationMatrix();
  const Eigen::Vector3d centre(50.03, -49.96, 10.0 - 0.3 * 50.03 + 0.33);  // 3 cm or more into the slope
  const auto energy = [&](const Eigen::Vector3d& x, const Eigen::Matrix3d& r) {
    Scene fresh(0.3, soil);
    NormalResponse response;
    std::vector<PistonChange> journal;
    press_carpet(fresh.carpet, fresh.range, body, x, r, {}, {}, response, journal);
    return response.elastic_energy;
  };
  Scene scene(0.3, soil);
  NormalResponse response;
  std::vector<PistonChange> journal;
  press_carpet(scene.carpet, scene.range, body, centre, rotation, {}, {}, response, journal);
  ASSERT_GT(response.touches.size(), 10u);
  for (const PistonTouch& touch : response.touches) {
    EXPECT_GT(std::abs(touch.normal.dot(scene.carpet.at(touch.i, touch.j).axis)), 0.2);  // no grazing clamp here
  }
  const double h = 1e-4;
  double worst = 0.0;  // largest difference relative to |F| or |T|
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(k);
    const double force = -(energy(centre + h * e, rotation) - energy(centre - h * e, rotation)) / (2.0 * h);
    EXPECT_NEAR(response.force[k], force, 2e-5 * response.force.norm()) << "axis " << k;
    const Eigen::Matrix3d plus = Eigen::AngleAxisd(h, e).toRotationMatrix() * rotation;
    const Eigen::Matrix3d minus = Eigen::AngleAxisd(-h, e).toRotationMatrix() * rotation;
    const double torque = -(energy(centre, plus) - energy(centre, minus)) / (2.0 * h);
    EXPECT_NEAR(response.torque[k], torque, 2e-5 * response.torque.norm()) << "axis " << k;
    worst = std::max({worst, std::abs(response.force[k] - force) / response.force.norm(),
                      std::abs(response.torque[k] - torque) / response.torque.norm()});
  }
  std::printf("force and torque against the energy's gradient: largest relative difference %.1e\n", worst);
}

// docs/rockfall-full.md, section 3.5. The half of a 2 x 1 x 1 m box (fracture.hpp) stands on its
// outer face, sunk 2 cm into flat elastic ground, its vertical cut face leading towards -x over a
// row of pistons. Along the axis alone, a top that the face passes has the half's 2 cm below it at
// once: the carpet's energy jumps by k A (2 cm)^2 / 2 per piston of the row. The compression
// min(axial depth, depth below the surface / grazing cosine) makes it continuous: the largest
// change of the energy over a 0.25 mm move is a quarter of that over 1 mm (a jump would give the
// same), and the force is minus its gradient where the face has just passed the row.
class FragmentFaceSweep : public ::testing::Test {
 protected:
  FragmentFaceSweep() : half_(half_box()) {}
  static RigidRock half_box() {
    const FracturedBody block = pre_fractured_block(full_model_scenes::block(BlockShape::box, {2.0, 1.0, 1.0}), 2,
                                                    1.0e6, 256, 32);
    return RigidRock(std::vector<RockPart>{block.body().parts()[1]}, block.body().inner_radius());
  }
  // The half's centre with its cut face at x = face (m), 2 cm into the ground at z = 10 m.
  Eigen::Vector3d centre(double face) const {
    const double to_face = -half_.parts()[0].cuts[0].offset;  // m: the face's x in the half's frame
    return {face - to_face, -50.0, 10.0 + 0.5 - kSink};
  }
  NormalResponse press_at(double face) const {
    Scene fresh(0.0, full_model_scenes::elastic_soil(1.0e8, 0.0));
    NormalResponse response;
    std::vector<PistonChange> journal;
    press_carpet(fresh.carpet, fresh.range, half_, centre(face), Eigen::Matrix3d::Identity(), {}, {}, response, journal);
    return response;
  }
  // Largest change of the elastic energy (J) over moves of `step` m as the face crosses the row
  // of pistons at x = 50 m.
  double largest_change(double step) const {
    double largest = 0.0;
    double before = press_at(50.0 + 0.01).elastic_energy;
    for (double face = 50.0 + 0.01 - step; face > 50.0 - 0.02; face -= step) {
      const double energy = press_at(face).elastic_energy;
      largest = std::max(largest, std::abs(energy - before));
      before = energy;
    }
    return largest;
  }
  static constexpr double kSink = 0.02;  // m
  RigidRock half_;
};

TEST_F(FragmentFaceSweep, EnergyChangesContinuouslyAsTheCutFacePassesAPiston) {
  ASSERT_TRUE(half_.has_cut_faces());
  const double coarse = largest_change(1e-3);
  const double fine = largest_change(2.5e-4);
  const double row_jump = 1.0e8 * kSpacing * kSpacing * kSink * kSink / 2.0;  // J per piston, along the axis
  std::printf("face sweep: largest energy change %.1f J per mm, %.1f J per 0.25 mm (one piston's jump: %.0f J)\n",
              coarse, fine, row_jump);
  EXPECT_GT(coarse, 0.5 * row_jump);    // the row loads over these few millimetres
  EXPECT_LT(fine, 0.3 * coarse);        // continuous: a quarter, 0.3 allows the kinks of the min
}

// Central differences of 1e-5 m on elastic pistons: as in the test above, well inside the
// lateral branch (the face 1 mm past the row: 5 mm of compression out of 2 cm).
TEST_F(FragmentFaceSweep, LateralForceIsMinusTheGradientOfTheEnergy) {
  const NormalResponse response = press_at(50.0 - 1e-3);
  ASSERT_GT(response.touches.size(), 0u);
  const double h = 1e-5;
  const double force = -(press_at(50.0 - 1e-3 + h).elastic_energy - press_at(50.0 - 1e-3 - h).elastic_energy) / (2.0 * h);
  std::printf("face sweep: force along x %.1f N, energy gradient %.1f N\n", response.force.x(), force);
  EXPECT_GT(response.force.x(), 0.0);                                  // the row pushes the face back
  EXPECT_NEAR(response.force.x(), force, 1e-3 * std::abs(force));      // differences' h^2 error and bisection noise
}

TEST(PistonContact, PistonsTheRockLeftGoBackToTheirFootprint) {
  Scene scene(0.0, full_model_scenes::talus_soil());
  const RigidRock body = make_body(BlockShape::sphere, Eigen::Vector3d::Constant(1.0));
  NormalResponse first, second;
  std::vector<PistonChange> journal;
  press_carpet(scene.carpet, scene.range, body, {50.0, -50.0, 10.48}, Eigen::Matrix3d::Identity(), {}, {}, first,
               journal);
  ASSERT_FALSE(first.touches.empty());
  journal.clear();
  press_carpet(scene.carpet, scene.range, body, {50.0, -50.0, 11.0}, Eigen::Matrix3d::Identity(), {},
               first.touches, second, journal);
  EXPECT_TRUE(second.touches.empty());
  EXPECT_EQ(second.elastic_energy, 0.0);
  EXPECT_EQ(journal.size(), first.touches.size());
  for (const PistonTouch& touch : first.touches) {
    const Piston& piston = scene.carpet.at(touch.i, touch.j);
    EXPECT_EQ(pressure(piston.cycle, piston.state), 0.0);
    EXPECT_EQ(piston.state.compression, piston.cycle.residual_compression(piston.state.max_compression));
    EXPECT_GT(piston.state.compression, 0.0);  // a plastic footprint is left
  }
  // The journal undoes the release.
  for (auto change = journal.rbegin(); change != journal.rend(); ++change) {
    scene.carpet.at(change->i, change->j).state = change->before;
  }
  for (const PistonTouch& touch : first.touches) {
    const Piston& piston = scene.carpet.at(touch.i, touch.j);
    EXPECT_GT(pressure(piston.cycle, piston.state), 0.0);
  }
}

// Previous touches outside the range are released too (the rock moved on).
TEST(PistonContact, PreviousTouchesOutsideTheRangeAreReleased) {
  Scene scene(0.0, full_model_scenes::talus_soil());
  const RigidRock body = make_body(BlockShape::sphere, Eigen::Vector3d::Constant(1.0));
  NormalResponse first, second;
  std::vector<PistonChange> journal;
  press_carpet(scene.carpet, scene.range, body, {50.0, -50.0, 10.48}, Eigen::Matrix3d::Identity(), {}, {}, first,
               journal);
  ASSERT_FALSE(first.touches.empty());
  press_carpet(scene.carpet, PistonRange{}, body, {50.0, -50.0, 10.48}, Eigen::Matrix3d::Identity(), {},
               first.touches, second, journal);
  for (const PistonTouch& touch : first.touches) {
    EXPECT_EQ(pressure(scene.carpet.at(touch.i, touch.j).cycle, scene.carpet.at(touch.i, touch.j).state), 0.0);
  }
}

TEST(PistonContact, ActiveSlopeFollowsTheBranchOfTheCycle) {
  const StressCycle cycle = StressCycle::of(full_model_scenes::talus_soil());
  PistonState state;
  press(cycle, state, 0.004);  // below the yield compression of 8 mm
  EXPECT_EQ(active_slope(cycle, state), cycle.elastic_slope);
  press(cycle, state, 0.02);
  EXPECT_EQ(active_slope(cycle, state), cycle.plastic_slope);
  press(cycle, state, 0.019);
  EXPECT_EQ(active_slope(cycle, state), cycle.unloading_slope);
}

PistonTouch touch_at(const Eigen::Vector3d& arm, double load, double friction, double deperdition = 0.0) {
  PistonTouch touch;
  touch.arm = arm;
  touch.normal = Eigen::Vector3d::UnitZ();
  touch.load = load;
  touch.friction = friction;
  touch.rolling_friction = friction;
  touch.vegetation_deperdition = deperdition;
  return touch;
}

// A fast slip meets the full Coulomb force mu N: the impulse is mu N dt against it, as long as it
// does not stop the slip within the kick.
TEST(PistonContact, FastSlipMeetsCoulombFriction) {
  const std::vector<PistonTouch> touches{touch_at({0.0, 0.0, -0.5}, 1000.0, 0.5)};
  const Eigen::Matrix3d inertia = 100.0 * Eigen::Matrix3d::Identity();
  const FrictionImpulse impulse =
      friction_impulse(touches, {5.0, 0.0, 0.0}, Eigen::Vector3d::Zero(), 1000.0, inertia, 0.01, 0.0, 1e-3);
  // Implicit in the slip: c = mu N / |s*| and the slip after the kick is a little smaller, so the
  // impulse is just below mu N dt = 0.5 N s (1e-3 relative).
  EXPECT_NEAR(impulse.linear.x(), -0.5, 0.5e-3);
  EXPECT_NEAR(impulse.linear.y(), 0.0, 1e-12);
  EXPECT_NEAR(impulse.linear.z(), 0.0, 1e-12);
  // Applied at the contact point below the centre: it spins the rock (angular impulse r x J).
  EXPECT_NEAR((impulse.angular - Eigen::Vector3d(0.0, 0.0, -0.5).cross(impulse.linear)).norm(), 0.0, 1e-12);
  EXPECT_GT(impulse.angular.y(), 0.0);
}

// A slow slip is a stiff viscous stick, solved implicitly: a long kick stops the slip without
// reversing it (a sphere's contact point comes to rolling, the centre keeps moving).
TEST(PistonContact, SlowSlipSticksWithoutReversing) {
  const double mass = 1000.0;
  const Eigen::Matrix3d inertia = 0.4 * mass * 0.25 * Eigen::Matrix3d::Identity();  // sphere of radius 0.5 m
  const std::vector<PistonTouch> touches{touch_at({0.0, 0.0, -0.5}, mass * 9.81, 0.4)};
  const Eigen::Vector3d v(2.0, 0.0, 0.0);
  const Eigen::Vector3d w(0.0, 3.99, 0.0);  // rolling would be 4 rad/s: slip 5 mm/s
  const FrictionImpulse impulse = friction_impulse(touches, v, w, mass, inertia, 0.01, 0.0, 0.05);
  const Eigen::Vector3d v_after = v + impulse.linear / mass;
  const Eigen::Vector3d w_after = w + inertia.inverse() * impulse.angular;
  const double slip_before = (v + w.cross(Eigen::Vector3d(0.0, 0.0, -0.5))).x();
  const double slip_after = (v_after + w_after.cross(Eigen::Vector3d(0.0, 0.0, -0.5))).x();
  EXPECT_GT(slip_before, 0.0);
  EXPECT_GE(slip_after, 0.0);                   // not reversed
  // Stuck to m_eff / (m_eff + c dt) = 1.4% of the slip, m_eff = 2/7 m, c = mu N / 0.01 m/s.
  EXPECT_LT(slip_after, 0.02 * slip_before);
  EXPECT_LT(std::abs(impulse.linear.x()), 0.4 * mass * 9.81 * 0.05);  // below Coulomb
}

TEST(PistonContact, VegetationGivesTheFastModesDecelerationShared) {
  const std::vector<PistonTouch> touches{touch_at({0.1, 0.0, -0.5}, 3000.0, 0.4, 0.02),
                                         touch_at({-0.1, 0.0, -0.5}, 1000.0, 0.4, 0.06)};
  const Eigen::Vector3d v(3.0, 4.0, 0.0);
  // Load-weighted c = (0.02 x 3 + 0.06 x 1) / 4 = 0.03 1/m: F = -0.03 m |v| v.
  const Eigen::Vector3d force = vegetation_force(touches, v, 200.0);
  EXPECT_NEAR((force - (-0.03 * 200.0 * 5.0) * v).norm(), 0.0, 1e-9);
  EXPECT_EQ(vegetation_force({}, v, 200.0), Eigen::Vector3d::Zero());
}

// The touches' Coulomb forces (for the bond forces of pre-fractured blocks, fracture.hpp) add up
// to the kick's linear impulse over its duration, each against its own slip.
TEST(PistonContact, TouchForcesAddUpToTheFrictionImpulse) {
  const double mass = 1000.0;
  const Eigen::Matrix3d inertia = Eigen::Vector3d(100.0, 120.0, 150.0).asDiagonal();
  std::vector<PistonTouch> touches{touch_at({0.3, 0.1, -0.5}, 4000.0, 0.5), touch_at({-0.3, 0.0, -0.5}, 6000.0, 0.4)};
  touches[1].normal = Eigen::Vector3d(0.2, 0.0, 1.0).normalized();
  const Eigen::Vector3d v(2.0, -1.0, 0.1);
  const Eigen::Vector3d w(0.5, 1.0, -0.3);
  const double duration = 2e-3;  // s
  std::vector<Eigen::Vector3d> forces;
  const FrictionImpulse impulse = friction_impulse(touches, v, w, mass, inertia, 0.01, 1.0, duration, &forces);
  ASSERT_EQ(forces.size(), touches.size());
  // Rounding of the 6 x 6 solve: 1e-9 of the impulse.
  EXPECT_LT((forces[0] + forces[1] - impulse.linear / duration).norm(), 1e-9 * impulse.linear.norm() / duration);
  for (std::size_t i = 0; i < touches.size(); ++i) {
    const Eigen::Vector3d slip = v + w.cross(touches[i].arm);
    EXPECT_LT(std::abs(forces[i].dot(touches[i].normal)), 1e-9 * forces[i].norm());  // across the normal
    EXPECT_LT(forces[i].dot(slip), 0.0);                                               // against the slip
    EXPECT_LE(forces[i].norm(), touches[i].friction * touches[i].load * (1.0 + 1e-12));  // at most mu N
  }
  // Without the output the impulse is the same, bit for bit.
  const FrictionImpulse alone = friction_impulse(touches, v, w, mass, inertia, 0.01, 1.0, duration);
  EXPECT_EQ(alone.linear, impulse.linear);
  EXPECT_EQ(alone.angular, impulse.angular);
}

}  // namespace
}  // namespace talus
