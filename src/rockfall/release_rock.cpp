// The nominal rock and start velocity of a release source (release_rock.hpp).
#include "talus/rockfall/release_rock.hpp"

namespace talus {

Rock release_rock(const Rock& run_rock, const ReleaseConditions& conditions) {
  Rock rock = run_rock;
  if (conditions.shape) rock.shape = *conditions.shape;
  if (conditions.axes) rock.axes = Eigen::Vector3d((*conditions.axes)[0], (*conditions.axes)[1], (*conditions.axes)[2]);
  if (conditions.density) rock.density = *conditions.density;
  return rock;
}

Eigen::Vector3d release_velocity(const ReleaseConditions& conditions) {
  if (!conditions.velocity) return Eigen::Vector3d::Zero();
  const auto& v = *conditions.velocity;
  return {v[0], v[1], v[2]};
}

}  // namespace talus
