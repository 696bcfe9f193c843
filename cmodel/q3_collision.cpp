#include "cmodel/q3_collision.hpp"

#include <algorithm>
#include <cmath>

namespace tfu::q3 {
namespace {

// The six axial planes q3map2 writes first on every brush, in this order (bounds from their dists).
constexpr glm::dvec3 kAxial[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

}  // namespace

BrushWorld::BrushWorld(const Bsp& bsp, int model) {
  if (model < 0 || static_cast<size_t>(model) >= bsp.models.size()) return;
  const BspModel& m = bsp.models[static_cast<size_t>(model)];
  for (int32_t i = m.first_brush; i < m.first_brush + m.brush_count; ++i) {
    const BspBrush& bb = bsp.brushes[static_cast<size_t>(i)];
    Brush b;
    b.index = i;
    b.contents = bsp.textures[static_cast<size_t>(bb.texture)].content_flags;
    for (int32_t k = 0; k < bb.side_count; ++k) {
      const BspPlane& p =
          bsp.planes[static_cast<size_t>(bsp.brush_sides[static_cast<size_t>(bb.first_side + k)].plane)];
      b.sides.push_back({p.normal, p.dist});
    }
    b.bounded = b.sides.size() >= 6;
    for (size_t k = 0; k < 6 && b.bounded; ++k) b.bounded = b.sides[k].normal == kAxial[k];
    if (b.bounded) {
      b.lo = {-b.sides[0].dist, -b.sides[2].dist, -b.sides[4].dist};
      b.hi = {b.sides[1].dist, b.sides[3].dist, b.sides[5].dist};
    }
    brushes_.push_back(std::move(b));
  }
}

void BrushWorld::trace_brush(const Brush& b, const glm::dvec3& start, const glm::dvec3& end, const glm::dvec3& half,
                             BoxTrace& tr) const {
  if (b.sides.empty()) return;
  double enter = -1.0, leave = 1.0;
  bool start_out = false, end_out = false;
  for (const Side& s : b.sides) {
    // The box corner nearest the plane (the most negative along n).
    const glm::dvec3 corner{s.normal.x < 0 ? half.x : -half.x, s.normal.y < 0 ? half.y : -half.y,
                            s.normal.z < 0 ? half.z : -half.z};
    const double dist = s.dist - glm::dot(corner, s.normal);
    const double d1 = glm::dot(start, s.normal) - dist, d2 = glm::dot(end, s.normal) - dist;
    if (d2 > 0) end_out = true;
    if (d1 > 0) start_out = true;
    if (d1 > 0 && (d2 >= kSurfaceClipEpsilon || d2 >= d1)) return;  // in front of this side all the way
    if (d1 <= 0 && d2 <= 0) continue;
    if (d1 > d2) {
      enter = std::max(enter, std::max(0.0, (d1 - kSurfaceClipEpsilon) / (d1 - d2)));
    } else {
      leave = std::min(leave, std::min(1.0, (d1 + kSurfaceClipEpsilon) / (d1 - d2)));
    }
  }
  if (!start_out) {
    tr.start_solid = true;
    if (!end_out) {
      tr.all_solid = true;
      tr.fraction = 0.0;
      tr.brush = b.index;
    }
    return;
  }
  if (enter < leave && enter > -1.0 && enter < tr.fraction) {
    tr.fraction = std::max(0.0, enter);
    tr.brush = b.index;
  }
}

BoxTrace BrushWorld::trace(const glm::dvec3& start, const glm::dvec3& end, const glm::dvec3& mins,
                           const glm::dvec3& maxs, int32_t mask) const {
  const glm::dvec3 centre = (mins + maxs) * 0.5, half = maxs - centre;
  const glm::dvec3 s = start + centre, e = end + centre;
  const glm::dvec3 sweep_lo = glm::min(s, e) - half, sweep_hi = glm::max(s, e) + half;
  BoxTrace tr;
  for (const Brush& b : brushes_) {
    if ((b.contents & mask) == 0) continue;
    if (b.bounded && (glm::any(glm::lessThan(sweep_hi, b.lo)) || glm::any(glm::greaterThan(sweep_lo, b.hi)))) continue;
    trace_brush(b, s, e, half, tr);
    if (tr.fraction == 0.0) break;
  }
  tr.end_pos = tr.fraction == 1.0 ? end : start + tr.fraction * (end - start);
  return tr;
}

SpawnRest spawn_rest(const BrushWorld& world, const glm::dvec3& spot, double floor_z) {
  const glm::dvec3 start = spot + glm::dvec3(0, 0, kSpawnLift);
  const glm::dvec3 end{start.x, start.y, std::min(floor_z, start.z)};
  const BoxTrace tr = world.trace(start, end, kPlayerMins, kPlayerMaxs, kMaskPlayerSolid);
  SpawnRest r;
  r.start_solid = tr.start_solid;
  if (tr.start_solid) {
    r.origin = start;
    return r;
  }
  r.landed = tr.fraction < 1.0;
  r.origin = r.landed ? tr.end_pos : start;
  return r;
}

}  // namespace tfu::q3
