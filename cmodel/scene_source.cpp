#include "cmodel/scene_source.hpp"

#include <charconv>
#include <map>
#include <mutex>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/q3_archives.hpp"
#include "cmodel/q3_scene.hpp"
#include "cmodel/q3_textures.hpp"

namespace tfu {
namespace {

// The game data of one directory with its texture cache and loaded levels.
struct Game {
  explicit Game(const std::string& dir) : archives(dir), textures(archives) {}
  q3::GameArchives archives;
  q3::TextureCache textures;
  std::map<std::string, std::shared_ptr<const q3::Level>> levels;
};

std::mutex& games_mutex() {
  static std::mutex m;
  return m;
}
std::map<std::string, std::unique_ptr<Game>>& games() {
  static std::map<std::string, std::unique_ptr<Game>> g;
  return g;
}

}  // namespace

std::shared_ptr<const q3::Level> cached_level(const std::string& game_dir, const std::string& map) {
  const std::string dir = q3::openarena_dir(game_dir);
  const std::lock_guard lock(games_mutex());
  auto& game = games()[dir];
  if (!game) game = std::make_unique<Game>(dir);
  auto& level = game->levels[map];
  if (!level) level = std::make_shared<const q3::Level>(q3::load_level(game->archives, map, game->textures));
  return level;
}

std::shared_ptr<const q3::Level> requested_level(const SceneRequest& r) {
  if (!q3::is_level_scene(r.name)) return nullptr;
  return cached_level(r.game_dir, q3::parse_level_scene(r.name).level);
}

Scene open_scene(const SceneRequest& r, const UploadCompression& compress) {
  if (r.width < 0 || r.height < 0 || r.width > kMaxRenderSize || r.height > kMaxRenderSize)
    throw InputError(fmt::format("render size {}x{} outside 1..{} (0: the scene's own)", r.width, r.height, kMaxRenderSize));
  if (q3::is_level_scene(r.name)) {
    const q3::LevelSceneSpec spec = q3::parse_level_scene(r.name);
    const auto level = cached_level(r.game_dir, spec.level);
    return q3::level_scene(*level, spec.spawn, r.width > 0 ? r.width : q3::kLevelSceneWidth,
                           r.height > 0 ? r.height : q3::kLevelSceneHeight, spec.options, compress);
  }
  if (compress.rule != UploadRule::None)
    throw InputError(fmt::format("--compress {} applies to oa: level scenes; scene '{}' names its textures' compress keys itself",
                                 compress.name(), r.name.substr(0, 80)));
  Scene s = load_scene(r.name);
  if (r.width > 0) s.width = r.width;
  if (r.height > 0) s.height = r.height;
  return s;
}

std::shared_ptr<const Texture> level_texture(const std::string& spec, const std::string& where, const std::string& game_dir) {
  // oa:MAP:texture:NAME | oa:MAP:lightmap:N | oa:MAP:lightmap-shiftK:N
  const auto fail = [&](const std::string& why) {
    return InputError(
        fmt::format("{}: texture '{}': {} (expected oa:MAP:texture:NAME, oa:MAP:lightmap:N or "
                    "oa:MAP:lightmap-shiftK:N)",
                    where, spec.substr(0, 80), why));
  };
  const std::string rest = spec.substr(std::string(q3::kLevelScenePrefix).size());
  const size_t c1 = rest.find(':');
  if (c1 == std::string::npos) throw fail("no texture kind");
  const size_t c2 = rest.find(':', c1 + 1);
  if (c2 == std::string::npos) throw fail("no texture name");
  const std::string map = rest.substr(0, c1), kind = rest.substr(c1 + 1, c2 - c1 - 1), name = rest.substr(c2 + 1);
  const auto level = cached_level(game_dir, map);
  const std::string shifted = "lightmap-shift";
  if (kind == "lightmap" || kind.starts_with(shifted)) {
    int shift = 0;
    if (kind != "lightmap") {
      const char* first = kind.data() + shifted.size();
      const auto [end, ec] = std::from_chars(first, kind.data() + kind.size(), shift);
      if (end == first || ec != std::errc{} || end != kind.data() + kind.size() || shift < 1 ||
          shift > q3::kMaxLightingShift)
        throw fail(
            fmt::format("light-map shift '{}' outside 1..{}", kind.substr(shifted.size(), 10), q3::kMaxLightingShift));
    }
    size_t n = 0;
    const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), n);
    if (ec != std::errc{} || end != name.data() + name.size() || n >= level->lightmaps.size())
      throw fail(fmt::format("level '{}' has light maps 0..{}", map, level->lightmaps.size() - 1));
    // The white light map is never shifted (level_scene names it oa:MAP:lightmap:N).
    return static_cast<int32_t>(n) == level->white_lightmap ? level->lightmaps[n]
                                                            : q3::shifted_lightmap(level->lightmaps[n], shift);
  }
  if (kind != "texture") throw fail(fmt::format("unknown kind '{}'", kind.substr(0, 20)));
  for (const q3::LevelTexture& t : level->textures)
    if (t.name == name && t.texture) return t.texture;
  throw fail(fmt::format("level '{}' draws no texture of that name", map));
}

}  // namespace tfu
