// The project's spawn cameras against the real engine: scripts/capture-openarena (docs/capture.md)
// places ioquake3's player at spawn point oa:MAP:SPAWN of the project's numbering and records the
// eye the engine used (its `viewpos` command: the integer parts, toward zero, of the eye and yaw).
// The spawn rule (cmodel/q3_collision.hpp drop, cmodel/q3_camera.hpp eye) must give the same eye from
// the same archive. TFU_CAPTURE_JSON names a fresh capture.json (the ctest capture_openarena sets
// it); without it the engine's answers recorded in testbench/data/capture/engine-eyes.json are
// checked (extracted from captures of Debian's openarena 0.8.8; the file says how).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/bsp.hpp"
#include "cmodel/q3_archives.hpp"
#include "cmodel/q3_camera.hpp"
#include "cmodel/q3_level.hpp"

namespace tfu::q3 {
namespace {

// One capture: the level, the spawn index, the archive entry the engine read, the spawn's origin as
// the capture script enumerated it, and the engine's eye and yaw.
struct EngineEye {
  std::string map, level_source;
  int spawn = 0;
  glm::dvec3 origin{0.0};
  int eye[3] = {0, 0, 0};
  int yaw = 0;
};

EngineEye from_capture_json(const nlohmann::json& j) {
  EngineEye e;
  e.map = j.at("map").get<std::string>();
  e.level_source = j.at("level_source").get<std::string>();
  e.spawn = j.at("spawn").at("index").get<int>();
  const auto& o = j.at("spawn").at("origin");
  e.origin = {o.at(0).get<double>(), o.at(1).get<double>(), o.at(2).get<double>()};
  for (int k = 0; k < 3; ++k) e.eye[k] = j.at("engine_viewpos").at("eye_truncated").at(static_cast<size_t>(k)).get<int>();
  e.yaw = j.at("engine_viewpos").at("yaw_deg").get<int>();
  return e;
}

// Checks one capture; returns false (and says why) when this game directory holds another archive
// for the level than the capture read, so the comparison would not be about the same level.
bool check_eye(const GameArchives& archives, const EngineEye& c) {
  const EntryRef ref = archives.locate_level(c.map);
  if (archives.describe(ref) != c.level_source) return false;
  const Bsp bsp = parse_bsp(archives.read(ref), archives.describe(ref));
  const std::vector<SpawnPoint> spawns = level_spawn_points(bsp, archives.describe(ref));
  const std::string what = fmt::format("{}:{}", c.map, c.spawn);
  EXPECT_LT(static_cast<size_t>(c.spawn), spawns.size()) << what;
  if (static_cast<size_t>(c.spawn) >= spawns.size()) return true;
  const SpawnPoint& s = spawns[static_cast<size_t>(c.spawn)];
  // The same numbering: the capture script's spawn c.spawn is the project's.
  EXPECT_EQ(s.origin, c.origin) << what;
  EXPECT_TRUE(s.landed) << what;
  const glm::dvec3 eye = spawn_eye(s);
  for (int k = 0; k < 3; ++k)  // the engine prints (int) of its float eye: truncation toward zero
    EXPECT_EQ(static_cast<int>(eye[k]), c.eye[k]) << what << " axis " << k << ": rule " << eye[k];
  // The yaw goes through the engine's 16-bit angles (360/65536 degrees) and is printed truncated.
  const double d = std::remainder(static_cast<double>(c.yaw) - s.yaw_deg, 360.0);
  EXPECT_LT(std::fabs(d), 1.0) << what << ": spawn yaw " << s.yaw_deg << ", engine " << c.yaw;
  return true;
}

TEST(Capture, EngineEyeMatchesTheSpawnRule) {
  const char* fresh = std::getenv("TFU_CAPTURE_JSON");
  const std::string dir = openarena_dir();
  if (fresh && *fresh) {  // the ctest's own capture: nothing may be missing
    const GameArchives archives(dir);
    std::ifstream f(fresh);
    ASSERT_TRUE(f) << "TFU_CAPTURE_JSON=" << fresh << ": cannot open";
    const EngineEye c = from_capture_json(nlohmann::json::parse(f));
    EXPECT_TRUE(check_eye(archives, c)) << c.map << ": the capture read " << c.level_source << ", " << dir
                                        << " has " << archives.describe(archives.locate_level(c.map));
    return;
  }
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << dir << ": no game data (Debian openarena)";
  const GameArchives archives(dir);
  std::ifstream f(std::filesystem::path(TFU_GOLDEN_DIR).parent_path() / "data" / "capture" / "engine-eyes.json");
  ASSERT_TRUE(f) << "testbench/data/capture/engine-eyes.json missing";
  const nlohmann::json j = nlohmann::json::parse(f);
  std::string other;
  for (const auto& c : j.at("captures"))
    if (!check_eye(archives, from_capture_json(c)))
      other += fmt::format(" {}:{}", c.at("map").get<std::string>(), c.at("level_source").get<std::string>());
  // Levels the captures read from archives this directory lacks (Debian's full openarena 0.8.8
  // overrides some of openarena-081-maps' levels): said, not compared.
  if (!other.empty()) GTEST_SKIP() << dir << " lacks the archives of these captures (Debian openarena):" << other;
}

// The capture script numbers spawn points itself (it rewrites the level before the engine reads
// it): its class list must be kSpawnClasses, in the same order.
TEST(Capture, ScriptSpawnClassesAreTheProjects) {
  std::ifstream f(std::filesystem::path(TFU_DOCS_DIR).parent_path() / "scripts" / "capture-openarena");
  ASSERT_TRUE(f) << "scripts/capture-openarena missing";
  std::string line, want = "SPAWN_CLASSES = [";
  for (size_t i = 0; i < kSpawnClasses.size(); ++i) want += fmt::format("{}\"{}\"", i ? ", " : "", kSpawnClasses[i]);
  want += "]";
  bool found = false;
  while (std::getline(f, line))
    if (line.rfind("SPAWN_CLASSES = ", 0) == 0) {
      EXPECT_EQ(line, want);
      found = true;
    }
  EXPECT_TRUE(found) << "no SPAWN_CLASSES line in scripts/capture-openarena";
}

}  // namespace
}  // namespace tfu::q3
