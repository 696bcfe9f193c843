#include "cmodel/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <streambuf>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/run_files.hpp"

namespace tfu {
namespace {

std::string errno_reason(int err) {
  switch (err) {
    case ENOENT: return "no such file";
    case ENOTDIR: return "no such file (a path component is not a directory)";
    case ENAMETOOLONG: return "file name too long";
    case EACCES: return "permission denied";
    case ELOOP: return "too many levels of symbolic links";
    default: return std::strerror(err);
  }
}

// Why a file of this type is not an input, or empty for a regular file.
std::string type_problem(mode_t mode) {
  if (S_ISREG(mode)) return {};
  if (S_ISDIR(mode)) return "is a directory, not a file";
  const std::string kind = file_kind(mode);
  if (kind == "not a regular file") return "is not a regular file";
  return fmt::format("is {}{}, not a regular file", kind, S_ISFIFO(mode) ? " (FIFO)" : "");
}

[[noreturn]] void fail(const std::string& label, const std::string& reason) {
  throw InputError(fmt::format("{}: {}", label, reason));
}

void check_size(const std::string& label, uint64_t size, uint64_t max_bytes) {
  if (size > max_bytes) fail(label, fmt::format("larger than the limit of {} bytes for this input", max_bytes));
}

// Opens `path` for reading after checking its type and size; returns the descriptor.
int open_checked(const std::string& path, const std::string& label, uint64_t max_bytes, bool run_input = true) {
  if (path.empty()) fail(label, "empty file name");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) fail(label, errno_reason(errno));
  if (const std::string p = type_problem(st.st_mode); !p.empty()) fail(label, p);
  check_size(label, static_cast<uint64_t>(st.st_size), max_bytes);
  // O_NONBLOCK: if the path was replaced by a FIFO since stat(), open() must not wait for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) fail(label, errno_reason(errno));
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    const std::string p = type_problem(st.st_mode);
    ::close(fd);
    fail(label, p.empty() ? std::string("cannot be examined") : p);
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  try {
    if (run_input) note_run_input(path, label);  // refused if it is an output of this run (cmodel/run_files.hpp)
  } catch (...) {
    ::close(fd);
    throw;
  }
  return fd;
}

}  // namespace

std::string file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a named pipe";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string quoted_path(const std::string& path) { return fmt::format("'{}'", quote_path(path)); }

// Reads the descriptor in blocks, counting bytes against the bound; errors throw InputError.
class InputFile::Buffer : public std::streambuf {
 public:
  Buffer(int fd, std::string label, uint64_t max_bytes) : fd_(fd), label_(std::move(label)), max_(max_bytes) {}
  ~Buffer() override { ::close(fd_); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

 protected:
  int_type underflow() override {
    if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
    ssize_t n;
    do {
      n = ::read(fd_, block_.data(), block_.size());
    } while (n < 0 && errno == EINTR);
    if (n < 0) fail(label_, fmt::format("read failed: {}", std::strerror(errno)));
    if (n == 0) return traits_type::eof();
    total_ += static_cast<uint64_t>(n);
    check_size(label_, total_, max_);
    setg(block_.data(), block_.data(), block_.data() + n);
    return traits_type::to_int_type(*gptr());
  }

 private:
  int fd_;
  std::string label_;
  uint64_t max_, total_ = 0;
  std::array<char, 65536> block_{};
};

InputFile::InputFile(const std::string& path, const std::string& label, uint64_t max_bytes, Use use)
    : buffer_(std::make_unique<Buffer>(open_checked(path, label, max_bytes, use == Use::RunInput), label, max_bytes)),
      stream_(buffer_.get()) {
  // A streambuf's exception sets badbit; with badbit in the mask the stream rethrows it, so the
  // InputError reaches the caller instead of looking like the end of the file.
  stream_.exceptions(std::ios::badbit);
}

InputFile::~InputFile() = default;

void check_input_file(const std::string& path, const std::string& label, uint64_t max_bytes) {
  ::close(open_checked(path, label, max_bytes));
}

std::string read_input_file(const std::string& path, const std::string& label, uint64_t max_bytes, InputFile::Use use) {
  InputFile f(path, label, max_bytes, use);
  std::string text;
  std::array<char, 65536> block{};
  while (f.stream().read(block.data(), block.size()) || f.stream().gcount() > 0)
    text.append(block.data(), static_cast<size_t>(f.stream().gcount()));
  return text;
}

}  // namespace tfu
