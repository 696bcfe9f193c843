#include "cmodel/pk3.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <utility>

#include <fmt/format.h>
#include <zip.h>

#include "cmodel/error.hpp"

namespace tfu {
namespace {

std::string zip_open_error(int code) {
  zip_error_t err;
  zip_error_init_with_code(&err, code);
  std::string msg = zip_error_strerror(&err);
  zip_error_fini(&err);
  return msg;
}

struct ZipFileCloser {
  void operator()(zip_file_t* f) const { zip_fclose(f); }
};

}  // namespace

std::string ascii_lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; });
  return s;
}

Pk3Archive::Pk3Archive(std::string path) : path_(std::move(path)) {
  if (!std::filesystem::is_regular_file(path_)) throw InputError(fmt::format("{}: no such archive", path_));
  int code = 0;
  archive_ = zip_open(path_.c_str(), ZIP_RDONLY, &code);
  if (archive_ == nullptr) throw InputError(fmt::format("{}: not a readable zip archive ({})", path_, zip_open_error(code)));
  const zip_int64_t n = zip_get_num_entries(archive_, 0);
  for (zip_int64_t i = 0; i < n; ++i) {
    const char* name = zip_get_name(archive_, static_cast<zip_uint64_t>(i), ZIP_FL_ENC_RAW);
    if (name == nullptr || *name == '\0') continue;
    std::string s(name);
    if (has_control_characters(s)) {  // never to reach a level list, a trace or a report
      const std::string what = fmt::format("{}: entry {} is named '{}', with a control character (entry names must be printable)",
                                           path_, i, quote_input(s));
      zip_discard(archive_);  // the destructor does not run for a constructor that throws
      archive_ = nullptr;
      throw InputError(what);
    }
    if (s.back() == '/') continue;  // directory entry
    names_.push_back(s);
    index_[ascii_lower(s)] = static_cast<uint64_t>(i);
  }
}

Pk3Archive::~Pk3Archive() {
  if (archive_ != nullptr) zip_discard(archive_);  // read-only: nothing to write back
}

Pk3Archive::Pk3Archive(Pk3Archive&& other) noexcept
    : path_(std::move(other.path_)), archive_(std::exchange(other.archive_, nullptr)), names_(std::move(other.names_)),
      index_(std::move(other.index_)) {}

Pk3Archive& Pk3Archive::operator=(Pk3Archive&& other) noexcept {
  if (this != &other) {
    if (archive_ != nullptr) zip_discard(archive_);
    path_ = std::move(other.path_);
    archive_ = std::exchange(other.archive_, nullptr);
    names_ = std::move(other.names_);
    index_ = std::move(other.index_);
  }
  return *this;
}

std::optional<std::string> Pk3Archive::find(const std::string& name) const {
  const auto it = index_.find(ascii_lower(name));
  if (it == index_.end()) return std::nullopt;
  return std::string(zip_get_name(archive_, it->second, ZIP_FL_ENC_RAW));
}

std::vector<uint8_t> Pk3Archive::read(const std::string& name) const {
  const auto it = index_.find(ascii_lower(name));
  if (it == index_.end()) throw InputError(fmt::format("{}: no entry '{}'", path_, name));
  const zip_uint64_t index = it->second;
  const std::string where = fmt::format("{}:{}", path_, zip_get_name(archive_, index, ZIP_FL_ENC_RAW));
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat_index(archive_, index, 0, &st) != 0 || (st.valid & ZIP_STAT_SIZE) == 0)
    throw InputError(fmt::format("{}: cannot stat entry ({})", where, zip_strerror(archive_)));
  if (st.size > kMaxPk3EntryBytes)
    throw InputError(fmt::format("{}: entry of {} bytes exceeds the {}-byte limit", where, st.size, kMaxPk3EntryBytes));
  std::unique_ptr<zip_file_t, ZipFileCloser> file(zip_fopen_index(archive_, index, 0));
  if (!file) throw InputError(fmt::format("{}: cannot open entry ({})", where, zip_strerror(archive_)));
  std::vector<uint8_t> bytes(static_cast<size_t>(st.size));
  zip_uint64_t done = 0;
  while (done < st.size) {
    const zip_int64_t got = zip_fread(file.get(), bytes.data() + done, st.size - done);
    if (got < 0) throw InputError(fmt::format("{}: read failed ({})", where, zip_file_strerror(file.get())));
    if (got == 0) throw InputError(fmt::format("{}: entry ends after {} of {} bytes", where, done, st.size));
    done += static_cast<zip_uint64_t>(got);
  }
  // The CRC is checked when the end of the data is reached: one more read reports a mismatch.
  char probe = 0;
  if (zip_fread(file.get(), &probe, 1) != 0)
    throw InputError(fmt::format("{}: read failed ({})", where, zip_file_strerror(file.get())));
  return bytes;
}

}  // namespace tfu
