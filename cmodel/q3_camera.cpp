#include "cmodel/q3_camera.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu::q3 {

double vertical_fov_deg(double fov_x_deg, double aspect) {
  const double half_x = fov_x_deg * std::numbers::pi / 360.0;
  return 2.0 * std::atan(std::tan(half_x) / aspect) * 180.0 / std::numbers::pi;
}

glm::dvec3 spawn_eye(const SpawnPoint& s, EyeRule rule) {
  return (rule == EyeRule::Rest ? s.rest : s.origin) + glm::dvec3(0, 0, kViewHeight);
}

Camera spawn_camera(const Level& level, int spawn, int width, int height, EyeRule rule) {
  if (spawn < 0 || static_cast<size_t>(spawn) >= level.spawns.size())
    throw InputError(fmt::format("level '{}' has {} spawn points ({}), no spawn point {}", level.name,
                                 level.spawns.size(), level.spawn_class.empty() ? "none" : level.spawn_class, spawn));
  const SpawnPoint& s = level.spawns[static_cast<size_t>(spawn)];
  Camera cam;
  cam.position = spawn_eye(s, rule);
  const double yaw = s.yaw_deg * std::numbers::pi / 180.0;
  cam.look_at = cam.position + glm::dvec3(std::cos(yaw), std::sin(yaw), 0.0);
  cam.up = {0, 0, 1};
  cam.fov_y_deg = vertical_fov_deg(kFovXDeg, static_cast<double>(width) / height);
  cam.near_plane = kNearPlane;
  const glm::dvec3 reach = glm::max(glm::abs(cam.position - level.bounds_min), glm::abs(cam.position - level.bounds_max));
  cam.far_plane = std::max(2 * kNearPlane, 1.01 * glm::length(reach) + kFarMargin);
  return cam;
}

}  // namespace tfu::q3
