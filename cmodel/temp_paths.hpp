// Temporary directories that no other user can predict or redirect (docs/inputs-outputs.md).
//
//   TempDir dir("tfu-aniso-compare");   // $TMPDIR/tfu-aniso-compare-XXXXXX, mode 0700, by mkdtemp
//   write(dir.path() / "texture0.tif");
//   // ~TempDir removes the directory and what this run put in it
//
// The name's random part is chosen by mkdtemp(3), which creates the directory atomically and fails
// rather than reuse anything that exists (a directory or symbolic link planted at a guessed name is
// never entered, and never removed). The directory is private (0700), so nobody else can plant a
// link inside it; removal does not follow symbolic links.
#pragma once

#include <filesystem>
#include <string>

namespace tfu {

class TempDir {
 public:
  // A new directory PARENT/PREFIX-XXXXXX; PARENT empty: $TMPDIR, else /tmp. InputError (one line,
  // naming the parent) when it cannot be created.
  explicit TempDir(const std::string& prefix, const std::string& parent = "");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The directory temporaries go to: $TMPDIR when set and not empty, else /tmp.
std::string temp_root();

}  // namespace tfu
