// The game data of a Quake III engine game (OpenArena): the .pk3 archives of one directory, in
// Quake III's search order, and the levels they hold.
//
// Where (docs/real-frames.md): the directory given by the caller (e.g. tfu's --game-dir), else the
// environment variable TFU_OPENARENA_DIR, else kDefaultOpenArenaDir, where Debian's
// openarena-081-maps (pak1-maps.pk3: 50 levels) and openarena-081-textures (pak4-textures.pk3)
// install their archives.
//
// Search order: every *.pk3 of the directory (not its subdirectories), sorted by file name in byte
// order; as in Quake III, an archive later in that order overrides the earlier ones, so a lookup
// asks the last archive first. Names match case-insensitively (Pk3Archive).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cmodel/pk3.hpp"

namespace tfu::q3 {

inline constexpr const char* kDefaultOpenArenaDir = "/usr/share/games/openarena/baseoa";
inline constexpr const char* kOpenArenaDirEnv = "TFU_OPENARENA_DIR";

// `given` if non-empty, else $TFU_OPENARENA_DIR if set and non-empty, else kDefaultOpenArenaDir.
std::string openarena_dir(const std::string& given = {});

struct EntryRef {
  size_t archive = 0;  // index into GameArchives::archives()
  std::string entry;   // stored spelling of the entry name
};

class GameArchives {
 public:
  // Opens every *.pk3 of `dir`. Throws InputError if `dir` is not a directory or holds no .pk3.
  explicit GameArchives(const std::string& dir);
  // Opens the given archives; later ones override earlier ones.
  explicit GameArchives(const std::vector<std::string>& pk3_paths);

  const std::string& dir() const { return dir_; }
  const std::vector<Pk3Archive>& archives() const { return archives_; }
  // The archive that wins for `name` (the last one holding it), or nothing.
  std::optional<EntryRef> locate(const std::string& name) const;
  std::vector<uint8_t> read(const EntryRef& ref) const;
  // "pak4-textures.pk3:textures/e7/e7walldesign01.jpg" (archive file name, not the full path).
  std::string describe(const EntryRef& ref) const;

  // Level names (lower-case stems of maps/*.bsp in any archive), sorted, each once.
  std::vector<std::string> level_names() const;
  // The BSP of level `name` ("aggressor" -> maps/aggressor.bsp); throws InputError naming the
  // directory if no archive holds it.
  EntryRef locate_level(const std::string& name) const;

 private:
  std::string dir_;
  std::vector<Pk3Archive> archives_;
};

}  // namespace tfu::q3
