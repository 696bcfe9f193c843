#include "cmodel/q3_archives.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu::q3 {

std::string openarena_dir(const std::string& given) {
  if (!given.empty()) return given;
  const char* env = std::getenv(kOpenArenaDirEnv);
  if (env != nullptr && *env != '\0') return env;
  return kDefaultOpenArenaDir;
}

namespace {

std::vector<std::string> pk3_files(const std::string& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(fmt::format("{}: no such game directory (install openarena-081-maps and openarena-081-textures, "
                                 "or set --game-dir / {})",
                                 dir, kOpenArenaDirEnv));
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string ext = ascii_lower(e.path().extension().string());
    if (ext == ".pk3" && e.is_regular_file()) out.push_back(e.path().string());
  }
  if (ec) throw InputError(fmt::format("{}: cannot list the game directory ({})", dir, ec.message()));
  std::sort(out.begin(), out.end(), [](const std::string& a, const std::string& b) {
    return std::filesystem::path(a).filename().string() < std::filesystem::path(b).filename().string();
  });
  if (out.empty()) throw InputError(fmt::format("{}: no .pk3 archives in the game directory", dir));
  return out;
}

}  // namespace

GameArchives::GameArchives(const std::string& dir) : GameArchives(pk3_files(dir)) { dir_ = dir; }

GameArchives::GameArchives(const std::vector<std::string>& pk3_paths) {
  archives_.reserve(pk3_paths.size());
  for (const std::string& p : pk3_paths) archives_.emplace_back(p);
  if (!pk3_paths.empty()) dir_ = std::filesystem::path(pk3_paths.front()).parent_path().string();
}

std::optional<EntryRef> GameArchives::locate(const std::string& name) const {
  for (size_t k = archives_.size(); k-- > 0;)
    if (auto stored = archives_[k].find(name)) return EntryRef{k, *stored};
  return std::nullopt;
}

std::vector<uint8_t> GameArchives::read(const EntryRef& ref) const { return archives_.at(ref.archive).read(ref.entry); }

std::string GameArchives::describe(const EntryRef& ref) const {
  return fmt::format("{}:{}", std::filesystem::path(archives_.at(ref.archive).path()).filename().string(), ref.entry);
}

std::vector<std::string> GameArchives::level_names() const {
  std::set<std::string> names;
  for (const Pk3Archive& a : archives_)
    for (const std::string& e : a.entry_names()) {
      const std::string lower = ascii_lower(e);
      if (lower.starts_with("maps/") && lower.ends_with(".bsp") && lower.find('/', 5) == std::string::npos &&
          lower.size() > 9)
        names.insert(lower.substr(5, lower.size() - 9));
    }
  return {names.begin(), names.end()};
}

EntryRef GameArchives::locate_level(const std::string& name) const {
  if (auto ref = locate("maps/" + name + ".bsp")) return *ref;
  throw InputError(fmt::format("no level '{}' (maps/{}.bsp) in the {} archives of {} (tfu render --list names them)",
                               name, name, archives_.size(), dir_));
}

}  // namespace tfu::q3
