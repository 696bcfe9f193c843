#include "cmodel/output_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"

namespace tfu {
namespace {

namespace fs = std::filesystem;

constexpr size_t kMaxComponentBytes = NAME_MAX;  // 255 on Linux

std::string reason(int err) {
  switch (err) {
    case ENOENT: return "no such directory";
    case ENOTDIR: return "a path component is not a directory";
    case ENAMETOOLONG: return "file name too long";
    case EACCES: return "permission denied";
    case EROFS: return "read-only file system";
    case ENOSPC: return "no space left on the device";
    default: return std::strerror(err);
  }
}

fs::path parent_dir(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

std::atomic<unsigned> g_temp_counter{0};

}  // namespace

// ---- OutputFile ----

// A stream buffer over the temporary's descriptor that remembers the first error of write(2) or
// close(2) (errno is long gone by the time a std::ofstream reports a failed state).
class OutputFile::Buffer : public std::streambuf {
 public:
  explicit Buffer(int fd) : fd_(fd) { setp(block_.data(), block_.data() + block_.size()); }
  ~Buffer() override {
    if (fd_ >= 0) ::close(fd_);
  }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  int error() const { return error_; }
  // Writes what is buffered and closes the descriptor; false (error() set) on failure.
  bool finish() {
    const bool flushed = drain();
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0 && error_ == 0) error_ = errno;
    return flushed && error_ == 0;
  }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    if (error_ != 0) return false;
    const char* p = pbase();
    while (p < pptr()) {
      const ssize_t n = ::write(fd_, p, static_cast<size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        error_ = n < 0 ? errno : EIO;
        return false;
      }
      p += n;
    }
    setp(block_.data(), block_.data() + block_.size());
    return true;
  }
  int fd_;
  int error_ = 0;
  std::array<char, 65536> block_{};
};

OutputFile::OutputFile(std::string option, std::string path, std::string temp)
    : option_(std::move(option)), path_(std::move(path)), temp_(std::move(temp)) {}

OutputFile::~OutputFile() = default;

std::string OutputFile::label() const { return fmt::format("{} {}", option_, quoted_path(path_)); }

std::ostream& OutputFile::stream() {
  if (!stream_) {
    const int fd = ::open(temp_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) throw InputError(fmt::format("{}: cannot write: {}", label(), reason(errno)));
    buffer_ = std::make_unique<Buffer>(fd);
    stream_ = std::make_unique<std::ostream>(buffer_.get());
    written_ = true;
  }
  return *stream_;
}

void OutputFile::write_image(const Image& img) {
  write_image_file(img, path_, temp_);
  written_ = true;
}

void OutputFile::close_stream() {
  if (!buffer_) return;
  // The state after writing (a write that failed earlier) and after closing (close(2) reports
  // delayed write errors, e.g. on network file systems).
  const bool written = !stream_->fail();
  const bool closed = buffer_->finish();
  const int err = buffer_->error();
  buffer_.reset();
  stream_.reset();
  if (!written || !closed) throw InputError(fmt::format("{}: write failed: {}", label(), err ? reason(err) : "stream error"));
}

// ---- OutputFiles ----

OutputFiles::OutputFiles(bool force) : force_(force) {}

OutputFiles::~OutputFiles() {
  if (!done_) discard();
  forget_run_outputs(this);
}

void OutputFiles::check_name(const std::string& option, const std::string& path) const {
  if (path.empty()) throw InputError(fmt::format("{}: empty file name", option));
  for (const fs::path& part : fs::path(path))
    if (part.native().size() > kMaxComponentBytes)
      throw InputError(fmt::format("{} {}: a path component is longer than {} bytes", option, quoted_path(path),
                                   kMaxComponentBytes));
  const fs::path name = fs::path(path).filename();
  if (name.empty() || name == "." || name == "..")
    throw InputError(fmt::format("{} {}: names a directory, not a file", option, quoted_path(path)));
}

void OutputFiles::make_parents(const std::string& option, const std::string& path) {
  std::vector<fs::path> missing;  // innermost first
  struct stat st {};
  for (fs::path p = parent_dir(path); !p.empty(); p = p.parent_path()) {
    if (::stat(p.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode))
        throw InputError(fmt::format("{} {}: '{}' is not a directory", option, quoted_path(path), quote_input(p.string())));
      break;
    }
    if (errno != ENOENT)
      throw InputError(fmt::format("{} {}: cannot use directory '{}': {}", option, quoted_path(path),
                                   quote_input(p.string()), reason(errno)));
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (::mkdir(it->c_str(), 0777) != 0 && errno != EEXIST)
      throw InputError(fmt::format("{} {}: cannot create directory '{}': {}", option, quoted_path(path),
                                   quote_input(it->string()), std::strerror(errno)));
    made_dirs_.push_back(it->string());
  }
}

std::string OutputFiles::make_temp(const std::string& option, const std::string& path) {
  // The name is unique in this process; another process with the same PID (another host writing
  // into a shared directory, as Slurm array tasks do) makes O_EXCL fail with EEXIST: take the next.
  fs::path temp;
  int fd = -1;
  for (int attempt = 0; attempt < 64 && fd < 0; ++attempt) {
    temp = parent_dir(path) / fmt::format(".tfu-{}-{}.tmp", static_cast<long>(::getpid()), g_temp_counter++);
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0)
    throw InputError(fmt::format("{} {}: cannot create a file in '{}': {}", option, quoted_path(path),
                                 quote_input(parent_dir(path).string()), reason(errno)));
  ::close(fd);
  return temp.string();
}

OutputFile& OutputFiles::add(const std::string& option, const std::string& path) {
  if (done_) throw std::logic_error("OutputFiles::add after commit");
  check_name(option, path);
  Identity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode))
      throw InputError(fmt::format("{} {} exists and is {}", option, quoted_path(path), file_kind(st.st_mode)));
    if (!force_) throw InputError(fmt::format("{} {} already exists (pass --force to overwrite)", option, quoted_path(path)));
    id.exists = true;
    id.dev = static_cast<uint64_t>(st.st_dev);
    id.ino = static_cast<uint64_t>(st.st_ino);
  } else if (errno != ENOENT && errno != ENOTDIR) {
    throw InputError(fmt::format("{} {}: {}", option, quoted_path(path), reason(errno)));
  }
  std::error_code ec;
  const fs::path abs = fs::absolute(path, ec);
  const fs::path canon = ec ? fs::path(path) : fs::weakly_canonical(abs, ec);
  id.canonical = (ec ? abs : canon).lexically_normal().string();
  for (size_t i = 0; i < ids_.size(); ++i) {
    const Identity& o = ids_[i];
    if (o.canonical == id.canonical || (o.exists && id.exists && o.dev == id.dev && o.ino == id.ino))
      throw InputError(fmt::format("{} {} is the same file as {}; every output needs its own file", option,
                                   quoted_path(path), files_[i]->label()));
  }
  note_run_output(this, id, fmt::format("{} {}", option, quoted_path(path)));
  make_parents(option, path);
  const std::string temp = make_temp(option, path);
  files_.push_back(std::unique_ptr<OutputFile>(new OutputFile(option, path, temp)));
  ids_.push_back(std::move(id));
  return *files_.back();
}

OutputFile& OutputFiles::add_image(const std::string& option, const std::string& path) {
  OutputFile& f = add(option, path);  // the path's own problems first (its temporary goes with the run)
  if (!image_writer_exists(path))
    throw InputError(fmt::format("{} {}: no image writer for this file type (use .png, .tif, .exr, ...)", option,
                                 quoted_path(path)));
  return f;
}

void OutputFiles::commit() {
  if (done_) return;
  for (auto& f : files_) f->close_stream();
  for (auto& f : files_) {
    if (!f->written_) {
      ::unlink(f->temp_.c_str());
      f->committed_ = true;  // nothing to keep
      continue;
    }
    int rc;
    if (force_) {
      rc = std::rename(f->temp_.c_str(), f->path_.c_str());
    } else {
      rc = ::renameat2(AT_FDCWD, f->temp_.c_str(), AT_FDCWD, f->path_.c_str(), RENAME_NOREPLACE);
      if (rc != 0 && errno == EINVAL) {  // a file system without RENAME_NOREPLACE
        struct stat st {};
        if (::stat(f->path_.c_str(), &st) == 0) {
          errno = EEXIST;
        } else {
          rc = std::rename(f->temp_.c_str(), f->path_.c_str());
        }
      }
    }
    if (rc != 0) {
      if (errno == EEXIST)
        throw InputError(fmt::format("{} appeared while tfu ran; not replaced (pass --force to overwrite)", f->label()));
      throw InputError(fmt::format("{}: cannot rename the finished file into place: {}", f->label(), reason(errno)));
    }
    f->committed_ = true;
  }
  done_ = true;
  forget_run_outputs(this);
}

void OutputFiles::discard() {
  for (auto& f : files_) {
    f->stream_.reset();
    f->buffer_.reset();  // closes the descriptor
    if (!f->committed_) ::unlink(f->temp_.c_str());
  }
  for (auto it = made_dirs_.rbegin(); it != made_dirs_.rend(); ++it) ::rmdir(it->c_str());  // only if empty
  done_ = true;
  forget_run_outputs(this);
}

}  // namespace tfu
