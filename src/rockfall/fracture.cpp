// Pre-fractured blocks of paper fig. 4: the block cut into parts, the forces of the bonds that
// hold them while the block moves as one rigid body, and the split when bonds break.
#include "talus/rockfall/fracture.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace talus {
namespace {

constexpr std::size_t kMaxParts = 32;  // parts of one body: the sides of its bonds are 32-bit masks

// Paper fig. 4: the local axes a block is cut across, longest first (a sphere's in the order x,
// y, z; equal axes keep that order).
std::array<int, 3> cut_axes(const Rock& rock) {
  std::array<int, 3> order{0, 1, 2};
  if (rock.shape == BlockShape::sphere) return order;
  std::stable_sort(order.begin(), order.end(), [&rock](int a, int b) { return rock.axes[a] > rock.axes[b]; });
  return order;
}

// Label of each part's group when only the bonds not marked in `broken` join parts (empty: none
// broken): the smallest part index of its group, by relaxation over the bonds (at most 32 parts).
std::vector<std::size_t> group_labels(std::size_t parts, const std::vector<Bond>& bonds, const std::vector<bool>& broken) {
  std::vector<std::size_t> label(parts);
  std::iota(label.begin(), label.end(), std::size_t{0});
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t b = 0; b < bonds.size(); ++b) {
      if (!broken.empty() && broken[b]) continue;
      std::size_t& first = label[bonds[b].first];
      std::size_t& second = label[bonds[b].second];
      if (first == second) continue;
      first = second = std::min(first, second);
      changed = true;
    }
  }
  return label;
}

}  // namespace

// Paper fig. 4 (the constraints form a tree): each bond's side is the group of parts that its
// `second` part still reaches when the bond alone is removed.
FracturedBody::FracturedBody(RigidRock body, std::vector<Bond> bonds) : body_(std::move(body)), bonds_(std::move(bonds)) {
  const std::size_t parts = body_.parts().size();
  if (parts > kMaxParts) throw std::invalid_argument("FracturedBody: at most 32 parts");
  if (bonds_.size() + 1 != parts) throw std::invalid_argument("FracturedBody: a tree of bonds has one bond fewer than parts");
  for (const Bond& bond : bonds_) {
    if (bond.first >= parts || bond.second >= parts || bond.first == bond.second) {
      throw std::invalid_argument("FracturedBody: a bond must join two distinct parts of the body");
    }
  }
  const std::vector<std::size_t> joined = group_labels(parts, bonds_, {});
  if (std::any_of(joined.begin(), joined.end(), [](std::size_t label) { return label != 0; })) {
    throw std::invalid_argument("FracturedBody: the bonds must join every part (a tree)");
  }
  for (std::size_t b = 0; b < bonds_.size(); ++b) {
    std::vector<bool> without(bonds_.size(), false);
    without[b] = true;
    const std::vector<std::size_t> label = group_labels(parts, bonds_, without);
    std::uint32_t side = 0;
    for (std::size_t p = 0; p < parts; ++p) {
      if (label[p] == label[bonds_[b].second]) side |= std::uint32_t{1} << p;
    }
    sides_.push_back(side);
  }
}

// Paper fig. 4, the pre-fractured solid: each cut halves every part so far (part k and k + n are
// the negative and positive sides of part k's cut, n the parts before it), so bit i of a part's
// index tells its side of cut i; the cut planes n.p <= 0 pass through the uncut shape's centre,
// and in a part's frame, centred on its centre of mass c, they read n.p <= -n.c.
FracturedBody pre_fractured_block(const Rock& rock, int parts, double strength, int surface_samples,
                                  int mass_resolution) {
  if (parts == 1) return FracturedBody(RigidRock(rock, surface_samples, mass_resolution), {});
  if (parts != 2 && parts != 4 && parts != 8) {
    throw std::invalid_argument("pre_fractured_block: a block has 1, 2, 4 or 8 parts");
  }
  const std::array<int, 3> axes = cut_axes(rock);
  const ImplicitShape whole(rock, surface_samples);
  std::vector<ImplicitShape> shapes{whole};
  std::vector<std::vector<CutPlane>> planes(1);  // each shape's cuts, in the uncut frame
  for (std::size_t cut = 0; shapes.size() < static_cast<std::size_t>(parts); ++cut) {
    const Eigen::Vector3d normal = Eigen::Vector3d::Unit(axes[cut]);
    std::vector<ImplicitShape> halves;
    halves.reserve(2 * shapes.size());
    for (const ImplicitShape& shape : shapes) halves.push_back(shape.cut({normal, 0.0}));
    for (const ImplicitShape& shape : shapes) halves.push_back(shape.cut({-normal, 0.0}));
    shapes = std::move(halves);
    const std::size_t before = planes.size();
    planes.resize(2 * before, {});
    for (std::size_t k = 0; k < before; ++k) {
      planes[k + before] = planes[k];
      planes[k].push_back({normal, 0.0});
      planes[k + before].push_back({-normal, 0.0});
    }
  }
  std::vector<RockPart> pieces;
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const MassProperties properties = integrate_mass(shapes[k], rock.density, mass_resolution);
    std::vector<CutPlane> local = planes[k];
    for (CutPlane& plane : local) plane.offset -= plane.normal.dot(properties.centre);
    pieces.push_back({shapes[k].shifted(properties.centre), properties.centre, properties.mass, properties.inertia,
                      std::move(local), whole.shifted(properties.centre)});
  }
  std::vector<Bond> bonds;
  for (std::size_t k = 1; k < pieces.size(); ++k) bonds.push_back({k - std::bit_floor(k), k, strength});
  return FracturedBody(RigidRock(std::move(pieces), smallest_semi_axis(rock)), std::move(bonds));
}

// Paper fig. 4 and 3.1 (Newton and Euler for the whole block, then for each side of a bond).
// With a = F / m, the part p of mass m_p at r_p needs m_p (a + alpha x r_p + w x (w x r_p)); the
// forces shared by mass give m_p / m of theirs, which is m_p a less m_p / m of the contacts'
// total C. So each part leaves d_p = m_p / m C - C_p + m_p (alpha x r_p + w x (w x r_p)) to its
// bonds (C_p: its contacts), and a bond's force is the sum of d_p over its side.
std::vector<Eigen::Vector3d> bond_forces(const FracturedBody& block, const RockState& state, const BodyLoads& loads) {
  const RigidRock& body = block.body();
  const std::vector<RockPart>& parts = body.parts();
  const Eigen::Matrix3d rotation = state.orientation.toRotationMatrix();
  const Eigen::Vector3d w = angular_velocity(body, state);
  const Eigen::Vector3d alpha =
      rotation * (body.inverse_inertia() * (rotation.transpose() * (loads.torque - w.cross(state.angular_momentum))));
  Eigen::Vector3d contacts = Eigen::Vector3d::Zero();  // N
  std::vector<Eigen::Vector3d> on_part(parts.size(), Eigen::Vector3d::Zero());
  for (const ContactLoad& load : loads.contacts) {
    contacts += load.force;
    on_part[body.part_at(rotation.transpose() * load.arm)] += load.force;
  }
  std::vector<Eigen::Vector3d> left(parts.size());  // N: d_p
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const Eigen::Vector3d r = rotation * parts[p].offset;
    left[p] = (parts[p].mass / body.mass()) * contacts - on_part[p] + parts[p].mass * (alpha.cross(r) + w.cross(w.cross(r)));
  }
  std::vector<Eigen::Vector3d> forces;
  for (std::size_t b = 0; b < block.bonds().size(); ++b) {
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    for (std::size_t p = 0; p < parts.size(); ++p) {
      if ((block.side(b) >> p) & 1U) force += left[p];
    }
    forces.push_back(force);
  }
  return forces;
}

// Paper fig. 4, the break: groups by the unbroken bonds; each group's parts keep their shapes
// and mass properties and are re-centred on the group's centre of mass c (RigidRock does it with
// the same centre_of_mass); its state is the block's rigid motion at r = R c.
std::vector<Fragment> split(const FracturedBody& block, const RockState& state, const std::vector<bool>& broken) {
  const RigidRock& body = block.body();
  const std::vector<RockPart>& parts = body.parts();
  const std::vector<std::size_t> label = group_labels(parts.size(), block.bonds(), broken);
  const Eigen::Matrix3d rotation = state.orientation.toRotationMatrix();
  const Eigen::Vector3d w = angular_velocity(body, state);
  std::vector<Fragment> fragments;
  for (std::size_t group = 0; group < parts.size(); ++group) {
    if (label[group] != group) continue;  // not the smallest part of a group
    std::vector<std::size_t> members;
    std::vector<std::size_t> index_of(parts.size(), parts.size());  // the block's part -> the fragment's
    std::vector<RockPart> pieces;
    for (std::size_t p = 0; p < parts.size(); ++p) {
      if (label[p] != group) continue;
      index_of[p] = members.size();
      members.push_back(p);
      pieces.push_back(parts[p]);
    }
    std::vector<Bond> bonds;
    for (std::size_t b = 0; b < block.bonds().size(); ++b) {
      const Bond& bond = block.bonds()[b];
      if (broken[b] || label[bond.first] != group) continue;
      bonds.push_back({index_of[bond.first], index_of[bond.second], bond.strength});
    }
    const Eigen::Vector3d arm = rotation * centre_of_mass(pieces);
    RigidRock fragment_body(std::move(pieces), body.inner_radius());
    const RockState fragment_state = rock_state(fragment_body, state.position + arm, state.velocity + w.cross(arm),
                                                state.orientation, w);
    fragments.push_back({FracturedBody(std::move(fragment_body), std::move(bonds)), fragment_state, std::move(members)});
  }
  return fragments;
}

}  // namespace talus
