// Pre-fractured blocks (paper 3.1, fig. 4): "large rocky blocks fracturing into smaller ones ...
// a set of rigid parts linked together by geometric constraints [10]. When internal constraint
// forces exceed a given threshold, the constraint is suppressed, so the block breaks into
// pieces." A block is the rock cut by planes through its centre into 2, 4 or 8 parts, held by
// bonds between parts that share a cut face. The bonds form a tree, which makes their forces
// statically determinate: each follows from the motion of, and the forces on, the parts on one
// of its sides. While every bond holds, the block moves as one rigid body (rigid_rock.hpp); a
// bond whose force exceeds its strength breaks, and the block splits into the groups of parts
// that the remaining bonds hold together, each a rigid body of its own that starts from the
// block's rigid motion. Equations and choices: docs/rockfall-full.md, section 11.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "talus/rockfall/rigid_rock.hpp"
#include "talus/rockfall/rock.hpp"

namespace talus {

// A breakable constraint between two parts of a body (paper fig. 4).
struct Bond {
  std::size_t first = 0, second = 0;  // indices of the parts it joins in the body's list
  double strength = 0;                // N: it breaks when its force's magnitude exceeds this
};

// A rigid body of parts held together by a tree of bonds (a body of one part has none).
class FracturedBody {
 public:
  // Throws std::invalid_argument unless `body` has at most 32 parts and the bonds join them
  // into a tree that spans them all (one bond fewer than parts, no cycle).
  FracturedBody(RigidRock body, std::vector<Bond> bonds);

  const RigidRock& body() const { return body_; }
  const std::vector<Bond>& bonds() const { return bonds_; }
  // The parts on the `second` side of a bond (bit p: part p): the group S whose bond force
  // bond_forces() reports.
  std::uint32_t side(std::size_t bond) const { return sides_[bond]; }

 private:
  RigidRock body_;
  std::vector<Bond> bonds_;
  std::vector<std::uint32_t> sides_;
};

// Paper fig. 4: `rock` cut by planes through its centre into `parts` parts: 1 (intact, no
// bonds), 2 (halves across its longest axis), 4 (also across the second longest), 8 (octants;
// a sphere's axes count in the order x, y, z). Each part's shape is ImplicitShape::cut, its
// mass, centre and inertia integrate_mass over it (mass_resolution cells per axis); the block's
// are their sums. Part k lies on the positive side of the i-th cut when bit i of k is set; part
// k > 0 is bonded to part k without its highest set bit (a spanning tree of parts sharing a
// face), every bond of `strength` N. Each part keeps its cut planes and the uncut shape in its
// own frame (RockPart::cuts, RockPart::whole), for the contacts of fragments and of the whole
// block (rigid_rock.hpp). Throws std::invalid_argument for other part counts.
FracturedBody pre_fractured_block(const Rock& rock, int parts, double strength, int surface_samples,
                                  int mass_resolution);

// A force on the body at a point.
struct ContactLoad {
  Eigen::Vector3d arm = Eigen::Vector3d::Zero();    // m: the point minus the body's centre, world
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N, world
};

// What acts on a body beside the forces shared by its parts in proportion to their mass (gravity,
// and by this model's choice air drag and vegetation), which drop out of the bond forces.
struct BodyLoads {
  std::vector<ContactLoad> contacts;                // piston touches: normal force plus Coulomb friction
  Eigen::Vector3d torque = Eigen::Vector3d::Zero(); // N m about the centre, world: every torque on the body
};

// Paper fig. 4, the constraint forces of a block moving as one rigid body: for each bond, the
// force F = m_S a_S - F_ext,S (N, world) that the rest of the body exerts through it on the group
// S of parts on its `second` side, with a_S = a + alpha x r_S + w x (w x r_S) the acceleration of
// S's centre in the rigid motion (a = total force / m; alpha = I_w^-1 (T - w x L), the torque T
// of `loads`; r_S from the centre to S's centre) and F_ext,S the forces on S's parts: their
// share of the mass-shared forces and the contacts whose point lies in one of them
// (RigidRock::part_at). One entry per bond, in the body's order.
std::vector<Eigen::Vector3d> bond_forces(const FracturedBody& block, const RockState& state, const BodyLoads& loads);

// One group of parts after a break, as a body of its own.
struct Fragment {
  FracturedBody block;              // its parts, re-centred on their centre of mass, and its unbroken bonds
  RockState state;                  // its share of the block's rigid motion
  std::vector<std::size_t> parts;   // indices of the block's parts it holds, ascending
};

// Paper fig. 4, a break: without the bonds marked in `broken` (one flag per bond), the block's
// parts fall apart into the groups the other bonds still join. Each group starts from the
// block's rigid motion: centre x + r_S, velocity v + w x r_S, the block's orientation, angular
// momentum R I_S R^T w about its own centre, so the split conserves momentum, angular momentum
// and kinetic energy. Fragments are ordered by their smallest part; the first holds part 0.
std::vector<Fragment> split(const FracturedBody& block, const RockState& state, const std::vector<bool>& broken);

}  // namespace talus
