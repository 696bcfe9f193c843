// Read-only access to one .pk3 archive (Quake III / OpenArena game data: a plain zip file) through
// libzip (Debian libzip-dev). No inflate code of our own.
//
// Entry names are matched case-insensitively (ASCII), as the Quake III file system does; when an
// archive holds two names that differ only in case, the later entry wins. Directory entries
// (names ending in '/') are ignored.
//
// Errors: InputError, one line naming the archive ("PATH: not a zip archive (...)") or the entry
// ("PATH:maps/x.bsp: read failed (...)"). An entry larger than kMaxPk3EntryBytes is refused.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

struct zip;  // libzip's archive handle (zip_t)

namespace tfu {

inline constexpr uint64_t kMaxPk3EntryBytes = uint64_t{256} << 20;  // 256 MiB: far above any level or texture

class Pk3Archive {
 public:
  // Opens `path` (throws InputError if it is missing or not a zip archive).
  explicit Pk3Archive(std::string path);
  ~Pk3Archive();
  Pk3Archive(Pk3Archive&& other) noexcept;
  Pk3Archive& operator=(Pk3Archive&& other) noexcept;
  Pk3Archive(const Pk3Archive&) = delete;
  Pk3Archive& operator=(const Pk3Archive&) = delete;

  const std::string& path() const { return path_; }
  // File entries in archive order, with their stored spelling.
  const std::vector<std::string>& entry_names() const { return names_; }
  // The stored spelling of `name` (any case), or nothing.
  std::optional<std::string> find(const std::string& name) const;
  bool contains(const std::string& name) const { return find(name).has_value(); }
  // The decompressed bytes of entry `name` (any case); throws InputError if it is absent or
  // cannot be read (CRC error, truncated data, too large).
  std::vector<uint8_t> read(const std::string& name) const;

 private:
  std::string path_;
  zip* archive_ = nullptr;
  std::vector<std::string> names_;
  std::map<std::string, uint64_t> index_;  // lower-case name -> libzip entry index
};

// ASCII lower case (the key of every case-insensitive lookup of game data).
std::string ascii_lower(std::string s);

}  // namespace tfu
