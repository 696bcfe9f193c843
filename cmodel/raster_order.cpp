#include "cmodel/raster_order.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {
namespace {

// "NAME[:N]": the name and the number (-1: none given). InputError naming `what` on a bad number.
std::pair<std::string, int> split_name(const std::string& s, const char* what) {
  const auto colon = s.find(':');
  if (colon == std::string::npos) return {s, -1};
  const std::string num = s.substr(colon + 1);
  int n = 0;
  const bool digits = !num.empty() && num.size() <= 4 &&
                      std::all_of(num.begin(), num.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (digits) n = std::stoi(num);
  if (!digits || n < 2 || n > kMaxRasterTile)
    throw InputError(
        fmt::format("{} '{}': the tile size after ':' must be an integer 2..{}", what, quote_input(s), kMaxRasterTile));
  return {s.substr(0, colon), n};
}

bool power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

// Interleaves the low 8 bits of x and y: x bit 0, y bit 0, x bit 1, ... (a Morton code).
uint32_t morton(uint32_t x, uint32_t y) {
  uint32_t m = 0;
  for (uint32_t b = 0; b < 8; ++b) m |= ((x >> b) & 1u) << (2 * b) | ((y >> b) & 1u) << (2 * b + 1);
  return m;
}

}  // namespace

RasterOrder raster_order_from_name(const std::string& name) {
  const auto [base, n] = split_name(name, "raster order");
  RasterOrder o;
  o.traversal = kRasterTraversalNames.from_name(base);
  if (o.traversal == RasterTraversal::Scanline) {
    if (n >= 0) throw InputError(fmt::format("raster order '{}': scanline takes no tile size", quote_input(name)));
    return o;
  }
  if (n < 0)
    throw InputError(fmt::format("raster order '{}': {} needs a tile size, e.g. {}:8", quote_input(name), base, base));
  if (n % 2 != 0)
    throw InputError(fmt::format("raster order '{}': the tile size must be even (whole 2x2 quads)", quote_input(name)));
  if (o.traversal == RasterTraversal::Morton && !power_of_two(n))
    throw InputError(fmt::format("raster order '{}': a Morton tile size must be a power of two", quote_input(name)));
  o.tile = n;
  return o;
}

std::string raster_order_name(const RasterOrder& o) {
  if (o.traversal == RasterTraversal::Scanline) return kRasterTraversalNames.name(o.traversal);
  return fmt::format("{}:{}", kRasterTraversalNames.name(o.traversal), o.tile);
}

uint32_t quad_rank_in_tile(const RasterOrder& o, int qx, int qy) {
  const auto x = static_cast<uint32_t>(qx), y = static_cast<uint32_t>(qy);
  if (o.traversal == RasterTraversal::Morton) return morton(x, y);
  return y * static_cast<uint32_t>(std::max(1, o.tile / 2)) + x;
}

std::vector<size_t> raster_sequence(const RasterOrder& o, const std::vector<QuadPlace>& quads) {
  std::vector<size_t> seq(quads.size());
  std::iota(seq.begin(), seq.end(), size_t{0});
  if (o.traversal == RasterTraversal::Scanline) return seq;
  if (o.tile < 2 || o.tile > kMaxRasterTile || o.tile % 2 != 0)
    throw InputError(fmt::format("raster order: tile size {} outside the even sizes 2..{}", o.tile, kMaxRasterTile));
  // Key: tile row, tile column, triangle, rank inside the tile; a stable sort keeps the stages of a
  // quad (equal keys) in their recorded order.
  int tiles_x = 1;
  for (const QuadPlace& q : quads) tiles_x = std::max(tiles_x, q.x / o.tile + 1);
  std::vector<std::pair<uint64_t, uint64_t>> key(quads.size());
  for (size_t i = 0; i < quads.size(); ++i) {
    const QuadPlace& q = quads[i];
    const auto tile =
        static_cast<uint64_t>(q.y / o.tile) * static_cast<uint64_t>(tiles_x) + static_cast<uint64_t>(q.x / o.tile);
    const uint32_t rank = quad_rank_in_tile(o, (q.x % o.tile) / 2, (q.y % o.tile) / 2);
    key[i] = {tile << 32 | q.triangle, rank};
  }
  std::stable_sort(seq.begin(), seq.end(), [&key](size_t a, size_t b) { return key[a] < key[b]; });
  return seq;
}

UnitTiles unit_tiles_from_name(const std::string& name) {
  const auto [base, n] = split_name(name, "unit distribution");
  UnitTiles t;
  t.distribution = kUnitDistributionNames.from_name(base);
  if (n >= 0) {
    if (n % 2 != 0)
      throw InputError(
          fmt::format("unit distribution '{}': the tile size must be even (whole 2x2 quads)", quote_input(name)));
    t.tile = n;
  }
  return t;
}

std::string unit_tiles_name(const UnitTiles& t) {
  return fmt::format("{}:{}", kUnitDistributionNames.name(t.distribution), t.tile);
}

int unit_of_quad(const UnitTiles& t, int units, int width, int height, int x, int y) {
  const int tiles_x = (width + t.tile - 1) / t.tile, tile_rows = (height + t.tile - 1) / t.tile;
  const int row = y / t.tile;
  if (t.distribution == UnitDistribution::Bands)
    return static_cast<int>(static_cast<int64_t>(row) * units / std::max(1, tile_rows));
  return static_cast<int>((static_cast<int64_t>(row) * tiles_x + x / t.tile) % units);
}

}  // namespace tfu
