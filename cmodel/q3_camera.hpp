// Cameras of a Quake III level: the player's view at a spawn point (docs/real-frames.md, "Camera").
//
//   eye        EyeRule::Rest (the engine's): the resting player origin + (0, 0, kViewHeight). Quake
//              III spawns the player 9 units above the spot and lets it fall onto whatever is below
//              (q3_collision.hpp spawn_rest: the player box, -15 -15 -24 .. 15 15 32, swept down
//              against the world's brushes, stopping 0.125 unit above the floor); the view is
//              DEFAULT_VIEWHEIGHT = 26 units above the player origin: on a floor at height F the
//              eye is at F + 24.125 + 26. EyeRule::Spot (the earlier rule): spot origin + 26, right
//              only where the spot sits exactly 24 units above the floor.
//   direction  horizontal, yaw = the spot's "angle" (degrees about +z from +x): look_at = eye +
//              (cos yaw, sin yaw, 0); up = (0, 0, 1). Quake's axes are used as they are (z up,
//              right-handed); gluLookAt handles them, no axis conversion.
//   field      horizontal fov kFovXDeg = 90 degrees (cg_fov's default); the renderer's vertical
//              fov for a width x height image is 2 atan(tan(45 deg) height / width), as Quake III's
//              CG_CalcFov computes it (58.72 degrees at 16:9).
//   depth      near = kNearPlane (r_znear's default, 4 units); far = the largest distance from the
//              eye to a corner of the level's bounds, plus 1% and kFarMargin units.
#pragma once

#include "cmodel/q3_level.hpp"
#include "cmodel/scene.hpp"

namespace tfu::q3 {

inline constexpr double kViewHeight = 26.0;  // bg_public.h DEFAULT_VIEWHEIGHT
inline constexpr double kFovXDeg = 90.0;     // cg_fov
inline constexpr double kNearPlane = 4.0;    // r_znear
inline constexpr double kFarMargin = 16.0;

// Vertical field of view (degrees) for a horizontal one at aspect = width / height.
double vertical_fov_deg(double fov_x_deg, double aspect);

enum class EyeRule { Rest, Spot };
inline constexpr EnumNames<EyeRule, 2> kEyeRuleNames{"eye rule", {{{EyeRule::Rest, "rest"}, {EyeRule::Spot, "spot"}}}};

// The eye position at spawn point `s` under `rule`.
glm::dvec3 spawn_eye(const SpawnPoint& s, EyeRule rule = EyeRule::Rest);

// The camera at spawn point `spawn` of `level` for a width x height image; throws InputError if
// the level has no such spawn point.
Camera spawn_camera(const Level& level, int spawn, int width, int height, EyeRule rule = EyeRule::Rest);

}  // namespace tfu::q3
