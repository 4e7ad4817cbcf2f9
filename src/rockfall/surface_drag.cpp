// Air friction during flight as the surface integral of paper 3.2 over a rock's surface samples.
#include "talus/rockfall/implicit_shape.hpp"

namespace talus {

// Paper 3.2: F = 1/2 rho Cx integral |V| V (V_hat . n) dS over the surface facing the flow, with
// the air's velocity V = -v relative to a rock moving at v through still air. Every sample
// facing the motion (n . v > 0) adds the projected area a = (v_hat . n) dA, all along -v:
// F = -1/2 rho Cx |v| v sum a, where sum a is the frontal area. Its moment about the local
// origin is sum (R p) x dF = (R sum a p) x F / sum a: the force acts through the centroid of the
// rock's shadow on a plane across the flow, which for centrally symmetric rocks (sphere,
// ellipsoid, box) is the centre, so only cut parts feel a drag torque about their centre.
Eigen::Vector3d surface_drag(const ImplicitShape& shape, const Eigen::Quaterniond& orientation,
                             const Eigen::Vector3d& velocity, double air_density, double drag_coefficient,
                             Eigen::Vector3d* torque) {
  if (torque != nullptr) torque->setZero();
  const double speed = velocity.norm();
  if (speed == 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Quaterniond rotation = orientation.normalized();
  const Eigen::Vector3d flow_local = rotation.conjugate() * (velocity / speed);
  double projected_area = 0.0;                             // m2
  Eigen::Vector3d area_moment = Eigen::Vector3d::Zero();   // m3, local frame
  for (const SurfaceSample& sample : shape.surface()) {
    const double facing = sample.normal.dot(flow_local);
    if (facing <= 0.0) continue;
    const double area = facing * sample.area;
    projected_area += area;
    area_moment += area * sample.position;
  }
  const Eigen::Vector3d force = -0.5 * air_density * drag_coefficient * projected_area * speed * velocity;
  if (torque != nullptr && projected_area > 0.0) {
    *torque = (rotation * (area_moment / projected_area)).cross(force);
  }
  return force;
}

}  // namespace talus
