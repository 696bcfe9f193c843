// Collision of an axis-aligned box with a level's brushes, as Quake III's CM_BoxTrace sweeps it
// (ioquake3 code/qcommon/cm_trace.c, read for the rules; docs/real-frames.md, "Spawn points"):
// where a player dropped at a spawn spot comes to rest.
//
// Brushes: the convex solids of the BSP (lumps 2, 8, 9), each the intersection of its sides'
// half-spaces dot(n, p) <= dist; its contents are the content flags of its texture entry. Only
// brushes whose contents meet the trace's mask take part (MASK_PLAYERSOLID for a player).
//
// A box [mins, maxs] swept from `start` to `end`:
//   centring  the box is made symmetric about its centre c = (mins + maxs) / 2: start and end move
//             by c, half extents e = maxs - c (the player box -15 -15 -24 .. 15 15 32 has c = (0, 0,
//             4), e = (15, 15, 28)).
//   planes    each side's plane is pushed out by the box corner nearest to it: dist' = dist -
//             dot(corner, n) with corner_i = -e_i where n_i >= 0 and +e_i where n_i < 0 (the
//             Minkowski sum of brush and box, exact for the axial sides and bevels q3map2 writes).
//   per side  d1 = dot(start, n) - dist', d2 = dot(end, n) - dist'. d1 > 0 and (d2 >= eps or
//             d2 >= d1): the sweep stays in front of this side, the brush is missed. d1 <= 0 and
//             d2 <= 0: the side does not matter. Entering (d1 > d2): f = (d1 - eps) / (d1 - d2),
//             at least 0, the brush's enter fraction is the largest; leaving: f = (d1 + eps) / (d1 -
//             d2), at most 1, the leave fraction the smallest. eps = kSurfaceClipEpsilon = 0.125, so
//             the box stops 1/8 unit in front of the surface it hits.
//   per brush start behind every side: start_solid (and all_solid, fraction 0, if the end is too);
//             otherwise if enter < leave and enter > -1 the trace's fraction = min(fraction,
//             max(0, enter)).
//   result    end_pos = start + fraction (end - start), in the caller's (uncentred) coordinates.
// Brushes are tested one by one in lump order with a bounding-box reject (the engine walks the BSP
// tree to the leaves the sweep touches; a brush outside them cannot touch the sweep, so the result
// is the same). Double precision (the engine uses float: results agree to ~1e-4 unit).
// Patches (curved surfaces) also collide in the engine (CM_TraceThroughPatch, on facets generated
// from the tessellated grid); they are not modelled here: spawn_rest() says where one may matter.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "cmodel/bsp.hpp"

namespace tfu::q3 {

inline constexpr double kSurfaceClipEpsilon = 0.125;  // cm_local.h SURFACE_CLIP_EPSILON

struct BoxTrace {
  double fraction = 1.0;  // of the way from start to end the box travels
  glm::dvec3 end_pos{0.0};
  bool start_solid = false;  // the box at `start` is inside a brush
  bool all_solid = false;    // ... and at `end` too (fraction 0)
  int32_t brush = -1;        // the brush that stopped the box (-1: none)
};

class BrushWorld {
 public:
  // The brushes of model `model` (0: the world; brush entities are models 1..). A BSP without
  // models has no collision world (every trace runs free).
  explicit BrushWorld(const Bsp& bsp, int model = 0);

  BoxTrace trace(const glm::dvec3& start, const glm::dvec3& end, const glm::dvec3& mins, const glm::dvec3& maxs,
                 int32_t mask) const;
  size_t brush_count() const { return brushes_.size(); }

 private:
  struct Side {
    glm::dvec3 normal{0.0};
    double dist = 0.0;
  };
  struct Brush {
    int32_t index = 0, contents = 0;
    bool bounded = false;  // the first six sides are the axial planes (-x, +x, -y, +y, -z, +z): bounds known
    glm::dvec3 lo{0.0}, hi{0.0};
    std::vector<Side> sides;
  };
  void trace_brush(const Brush& b, const glm::dvec3& start, const glm::dvec3& end, const glm::dvec3& half,
                   BoxTrace& tr) const;
  std::vector<Brush> brushes_;
};

// The player's box (bg_public.h: MINS_Z -24, maxs z 32; bg_pmove.c: 15 on x and y).
inline constexpr glm::dvec3 kPlayerMins{-15, -15, -24}, kPlayerMaxs{15, 15, 32};
inline constexpr double kSpawnLift = 9.0;  // g_client.c SelectSpawnPoint: the origin starts 9 above the spot

// Where a player spawned at `spot` comes to rest: the player box dropped straight down from spot +
// (0, 0, kSpawnLift) against the world's MASK_PLAYERSOLID brushes, down to `floor_z` (below the
// level). The engine lets the player fall under gravity frame by frame; every frame's move is such
// a trace, so the rest position is where one long trace stops.
struct SpawnRest {
  glm::dvec3 origin{0.0};    // the resting player origin (spot + 9 when nothing was hit)
  bool landed = false;       // a brush stopped the fall
  bool start_solid = false;  // the box at spot + 9 is inside a brush (origin: spot + 9)
};
SpawnRest spawn_rest(const BrushWorld& world, const glm::dvec3& spot, double floor_z);

}  // namespace tfu::q3
