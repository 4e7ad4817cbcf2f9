// Tests of pre-fractured blocks (paper 3.1, fig. 4): the block cut into parts with a tree of
// bonds, the mass properties summed over the parts, the skin without shared faces, the bond
// forces of the rigid motion (closed forms: centripetal force, a block held at one end, free
// fall), and the split's share of the motion.
#include "talus/rockfall/fracture.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace talus {
namespace {

constexpr int kSamples = 256;    // FullModelParameters::surface_samples
constexpr int kResolution = 32;  // FullModelParameters::mass_resolution

Rock make_rock(BlockShape shape, const Eigen::Vector3d& axes) {
  Rock rock;
  rock.shape = shape;
  rock.axes = axes;
  return rock;
}

// The 2 x 1 x 1 m box of the issue, cut in two across its long (x) axis.
FracturedBody two_part_box(double strength = 1.0e6) {
  return pre_fractured_block(make_rock(BlockShape::box, {2.0, 1.0, 1.0}), 2, strength, kSamples, kResolution);
}

// At the centre of the world, turned by `orientation`, spinning at w (rad/s, world).
RockState spinning(const RigidRock& body, const Eigen::Quaterniond& orientation, const Eigen::Vector3d& w) {
  return rock_state(body, Eigen::Vector3d(10.0, 20.0, 500.0), Eigen::Vector3d(3.0, 0.0, -2.0), orientation, w);
}

TEST(Fracture, BlockIsCutAcrossItsLongestAxesIntoPartsBondedInATree) {
  const Rock rock = make_rock(BlockShape::box, {1.0, 2.0, 1.5});  // longest y, then z, then x
  for (const int count : {1, 2, 4, 8}) {
    const FracturedBody block = pre_fractured_block(rock, count, 5.0e5, kSamples, kResolution);
    const std::vector<RockPart>& parts = block.body().parts();
    ASSERT_EQ(parts.size(), static_cast<std::size_t>(count));
    ASSERT_EQ(block.bonds().size(), parts.size() - 1);
    for (const Bond& bond : block.bonds()) {
      EXPECT_EQ(bond.strength, 5.0e5);
      // Bonded parts share a cut face: their centres differ on exactly one axis, the one cut.
      const Eigen::Vector3d apart = parts[bond.second].offset - parts[bond.first].offset;
      int axes_apart = 0;
      for (int i = 0; i < 3; ++i) axes_apart += std::abs(apart[i]) > 0.1 ? 1 : 0;  // m: centres of halves lie ~0.5 m apart
      EXPECT_EQ(axes_apart, 1);
    }
    // Part 1 is across the first cut from part 0: the longest axis (y).
    if (count >= 2) {
      EXPECT_GT(std::abs(parts[1].offset.y() - parts[0].offset.y()), 0.8);
    }
    if (count >= 4) {
      EXPECT_GT(std::abs(parts[2].offset.z() - parts[0].offset.z()), 0.6);
    }
    if (count >= 8) {
      EXPECT_GT(std::abs(parts[4].offset.x() - parts[0].offset.x()), 0.4);
    }
    // The parts' sums are the block's and match the uncut rock (integration: 0.5%).
    const RigidRock uncut(rock, kSamples, kResolution);
    EXPECT_NEAR(block.body().mass() / uncut.mass(), 1.0, 0.005);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(block.body().inertia()(i, i) / uncut.inertia()(i, i), 1.0, 0.005);
    // The body frame sits at the parts' centre of mass (rounding: 1e-12 m).
    EXPECT_LT(centre_of_mass(parts).norm(), 1e-12);
  }
  EXPECT_THROW(pre_fractured_block(rock, 3, 1.0, kSamples, kResolution), std::invalid_argument);
}

TEST(Fracture, BondsMustFormATreeOverTheParts) {
  const FracturedBody block = pre_fractured_block(make_rock(BlockShape::box, {2.0, 2.0, 2.0}), 4, 1.0, kSamples, 16);
  const RigidRock& body = block.body();
  EXPECT_THROW(FracturedBody(body, {{0, 1, 1.0}, {0, 2, 1.0}}), std::invalid_argument);  // part 3 unbonded
  EXPECT_THROW(FracturedBody(body, {{0, 1, 1.0}, {1, 0, 1.0}, {2, 3, 1.0}}), std::invalid_argument);  // a cycle
  EXPECT_THROW(FracturedBody(body, {{0, 1, 1.0}, {0, 2, 1.0}, {3, 3, 1.0}}), std::invalid_argument);
  EXPECT_NO_THROW(FracturedBody(body, {{0, 1, 1.0}, {1, 3, 1.0}, {3, 2, 1.0}}));
  // The tree of pre_fractured_block: 1 - 0, 2 - 0, 3 - 1; each bond's side is its second's subtree.
  EXPECT_EQ(block.side(0), 0b1010u);
  EXPECT_EQ(block.side(1), 0b0100u);
  EXPECT_EQ(block.side(2), 0b1000u);
}

// Air drag sees the outer surface only: the faces the parts share are not in the skin, so the
// cut block meets the uncut rock's drag (cut parts' samples give their area to 1-2%,
// implicit_shape.cpp: 3%; measured 1.9% and 1.3%). With the shared faces, the flow would also
// push on every internal face that faces it.
TEST(Fracture, SkinLeavesOutTheFacesThePartsShare) {
  const Rock rock = make_rock(BlockShape::box, {2.0, 1.0, 1.0});
  const RigidRock uncut(rock, kSamples, kResolution);
  const FracturedBody block = pre_fractured_block(rock, 8, 1.0, kSamples, kResolution);
  const Eigen::Quaterniond tilted(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1.0, 2.0, 0.5).normalized()));
  for (const Eigen::Vector3d& velocity : {Eigen::Vector3d(20.0, 0.0, 0.0), Eigen::Vector3d(3.0, -5.0, -15.0)}) {
    Eigen::Vector3d torque;
    const double expected = uncut.drag(tilted, velocity, 1.225, 0.1, torque).norm();
    const double cut = block.body().drag(tilted, velocity, 1.225, 0.1, torque).norm();
    EXPECT_NEAR(cut / expected, 1.0, 0.03);
  }
  EXPECT_EQ(uncut.skin().size(), static_cast<std::size_t>(kSamples));
  EXPECT_LT(block.body().skin().size(), static_cast<std::size_t>(8 * kSamples));
}

// docs/rockfall-full.md, section 3.5: a cut face is on a body's surface only where no other part
// of the body covers it. The uncut rock and the whole block have none (their pistons keep the
// paper's compression along the axis); a half has its cut face, and a point inside it lies as
// deep below that face as its distance to the plane, with the gradient pointing inwards.
TEST(Fracture, CutFacesOnTheSurfaceOnlyWhereNoPartCoversThem) {
  const Rock rock = make_rock(BlockShape::box, {2.0, 1.0, 1.0});
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  const RigidRock uncut(rock, kSamples, kResolution);
  EXPECT_FALSE(uncut.has_cut_faces());
  EXPECT_TRUE(std::isinf(uncut.depth_inside(Eigen::Vector3d::Zero(), gradient)));
  for (const int count : {2, 4, 8}) {
    const FracturedBody block = pre_fractured_block(rock, count, 1.0, kSamples, kResolution);
    EXPECT_FALSE(block.body().has_cut_faces()) << count << " parts";
    EXPECT_TRUE(std::isinf(block.body().depth_inside(Eigen::Vector3d::Zero(), gradient)));
  }
  const FracturedBody block = two_part_box();
  const RockPart& positive = block.body().parts()[1];  // x >= 0 in the uncut frame
  ASSERT_EQ(positive.cuts.size(), 1u);
  EXPECT_LT((positive.cuts[0].normal - Eigen::Vector3d(-1.0, 0.0, 0.0)).norm(), 1e-15);
  const RigidRock half(std::vector<RockPart>{positive}, block.body().inner_radius());
  ASSERT_TRUE(half.has_cut_faces());
  // The cut face lies at minus the half's offset from the uncut centre, in the half's frame: points
  // 1 and 5 cm inside it, near the face's middle, are that deep.
  const double face = -positive.cuts[0].offset;  // x of the face in the half's frame (m)
  for (const double inside : {0.01, 0.05}) {
    const double depth = half.depth_inside(Eigen::Vector3d(face + inside, 0.05, -0.1), gradient);
    EXPECT_NEAR(depth, inside, 1e-12);  // rounding
    EXPECT_LT((gradient - Eigen::Vector3d::UnitX()).norm(), 1e-15);
  }
  // Near the outer surface: at most the distance to it, within a factor inner_radius / 1 m = 0.5
  // along the long axis (-f x inner_radius, a lower bound).
  const double outer = half.depth_inside(Eigen::Vector3d(face + 0.4, 0.0, 0.45), gradient);
  EXPECT_GT(outer, 0.0);
  EXPECT_LE(outer, 0.05 + 1e-3);  // the top face is 0.05 m away (exponent 8: within 1 mm of flat there)
  EXPECT_GT(gradient.dot(-Eigen::Vector3d::UnitZ()), 0.0);  // inwards, away from the top face
}

// Issue 4: a 2 x 1 x 1 m box of two halves spinning in free flight at w about an axis across its
// long axis: the bond holds each half on its circle, F = m_S w^2 |r_S| towards the centre.
TEST(Fracture, SpinningBlockBondCarriesTheCentripetalForce) {
  const FracturedBody block = two_part_box();
  const RigidRock& body = block.body();
  const double w = 3.0;  // rad/s
  for (const Eigen::Quaterniond& orientation :
       {Eigen::Quaterniond::Identity(), Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()))}) {
    const Eigen::Vector3d spin = orientation * Eigen::Vector3d(0.0, 0.0, w);  // across the long axis
    const RockState state = spinning(body, orientation, spin);
    const std::vector<Eigen::Vector3d> forces = bond_forces(block, state, BodyLoads{});  // free flight, no drag
    ASSERT_EQ(forces.size(), 1u);
    const RockPart& half = body.parts()[1];
    const Eigen::Vector3d arm = orientation * half.offset;
    const double centripetal = half.mass * w * w * arm.norm();
    std::printf("centripetal %.6f N, bond %.6f N\n", centripetal, forces[0].norm());
    EXPECT_NEAR(forces[0].norm() / centripetal, 1.0, 1e-6);  // issue 4: 1e-6 relative
    EXPECT_NEAR(forces[0].dot(arm) / (forces[0].norm() * arm.norm()), -1.0, 1e-6);  // towards the centre
  }
}

// Gravity, like any force shared by mass, accelerates every part alike: no force in the bonds.
TEST(Fracture, GravityAloneLoadsNoBond) {
  const FracturedBody block = pre_fractured_block(make_rock(BlockShape::ellipsoid, {2.0, 1.4, 1.0}), 8, 1.0,
                                                  kSamples, kResolution);
  const Eigen::Quaterniond tilted(Eigen::AngleAxisd(1.1, Eigen::Vector3d(1.0, -1.0, 2.0).normalized()));
  const RockState state = spinning(block.body(), tilted, Eigen::Vector3d::Zero());
  for (const Eigen::Vector3d& force : bond_forces(block, state, BodyLoads{})) {
    EXPECT_LT(force.norm(), 1e-9 * block.body().mass());  // N, against m g ~ 1e4 N: exactly 0 up to rounding
  }
}

// A block at rest held up at one end only (a force m g under the centre of half 1): the force
// balance leaves a = 0, the torque r_1 x F turns it at alpha = d F / I_yy, and the bond pulls
// half 1 by F (m_1 d^2 / I_yy + m_1 / m - 1) along z (m_1 / m = 1/2: downwards, half 0 hangs
// from it), d the half's arm.
TEST(Fracture, BlockHeldAtOneEndLoadsItsBondByTheLeverRule) {
  const FracturedBody block = two_part_box();
  const RigidRock& body = block.body();
  const RockState state = spinning(body, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
  const RockPart& half = body.parts()[1];
  const double d = half.offset.x();
  const double lift = body.mass() * 9.81;  // N
  BodyLoads loads;
  const Eigen::Vector3d arm(d, 0.0, -0.5);  // under half 1's centre, on the bottom face
  loads.contacts.push_back({arm, Eigen::Vector3d(0.0, 0.0, lift)});
  loads.torque = arm.cross(loads.contacts.front().force);
  const std::vector<Eigen::Vector3d> forces = bond_forces(block, state, loads);
  const double expected = lift * (half.mass * d * d / body.inertia()(1, 1) + half.mass / body.mass() - 1.0);
  EXPECT_NEAR(forces[0].z(), expected, 1e-6 * lift);  // 1e-6 of the load: rounding and the parts' tiny asymmetry
  EXPECT_LT(forces[0].head<2>().norm(), 1e-6 * lift);
  // Held evenly at both ends, the same block carries nothing across its bond.
  loads.contacts = {{arm, Eigen::Vector3d(0.0, 0.0, 0.5 * lift)}, {{-d, 0.0, -0.5}, Eigen::Vector3d(0.0, 0.0, 0.5 * lift)}};
  loads.torque = arm.cross(loads.contacts[0].force) + loads.contacts[1].arm.cross(loads.contacts[1].force);
  EXPECT_LT(bond_forces(block, state, loads)[0].norm(), 1e-6 * lift);
}

// The split shares the block's rigid motion: each fragment at x + r_S with v + w x r_S, the
// block's orientation and spin; momentum and angular momentum are kept (rounding: 1e-12).
TEST(Fracture, SplitSharesTheRigidMotion) {
  const FracturedBody block = pre_fractured_block(make_rock(BlockShape::box, {1.6, 1.2, 0.8}), 8, 1.0, kSamples,
                                                  kResolution);
  const Eigen::Quaterniond orientation(Eigen::AngleAxisd(0.8, Eigen::Vector3d(2.0, 1.0, -1.0).normalized()));
  const RockState state = spinning(block.body(), orientation, Eigen::Vector3d(1.0, -2.0, 4.0));
  const Eigen::Vector3d w = angular_velocity(block.body(), state);
  // The tree 1-0, 2-0, 3-1, 4-0, 5-1, 6-2, 7-3 without bonds 0 (1-0) and 3 (4-0): groups
  // {0, 2, 6}, {1, 3, 5, 7} and {4}.
  std::vector<bool> broken(block.bonds().size(), false);
  broken[0] = broken[3] = true;
  const std::vector<Fragment> fragments = split(block, state, broken);
  ASSERT_EQ(fragments.size(), 3u);
  EXPECT_EQ(fragments[0].parts, (std::vector<std::size_t>{0, 2, 6}));
  EXPECT_EQ(fragments[1].parts, (std::vector<std::size_t>{1, 3, 5, 7}));
  EXPECT_EQ(fragments[2].parts, (std::vector<std::size_t>{4}));
  EXPECT_EQ(fragments[0].block.bonds().size(), 2u);
  EXPECT_EQ(fragments[1].block.bonds().size(), 3u);
  EXPECT_EQ(fragments[2].block.bonds().size(), 0u);
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  double mass = 0.0;
  for (const Fragment& fragment : fragments) {
    const RigidRock& body = fragment.block.body();
    const Eigen::Vector3d r = fragment.state.position - state.position;
    EXPECT_LT((fragment.state.velocity - state.velocity - w.cross(r)).norm(), 1e-12 * w.norm());
    EXPECT_LT((angular_velocity(body, fragment.state) - w).norm(), 1e-12 * w.norm());
    EXPECT_LT(centre_of_mass(body.parts()).norm(), 1e-12);
    mass += body.mass();
    momentum += body.mass() * fragment.state.velocity;
    angular += fragment.state.angular_momentum + r.cross(body.mass() * fragment.state.velocity);
  }
  EXPECT_NEAR(mass / block.body().mass(), 1.0, 1e-12);
  EXPECT_LT((momentum - block.body().mass() * state.velocity).norm(), 1e-12 * momentum.norm());
  EXPECT_LT((angular - state.angular_momentum).norm(), 1e-12 * state.angular_momentum.norm());
}

}  // namespace
}  // namespace talus
