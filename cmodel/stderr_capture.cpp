#include "cmodel/stderr_capture.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>

#include "cmodel/error.hpp"

namespace tfu {
namespace {

std::mutex& capture_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

StderrCapture::StderrCapture() : lock_(capture_mutex()) {
  std::fflush(stderr);
  file_ = std::tmpfile();
  if (!file_) return;  // no temporary file: nothing is captured, stderr stays as it is
  saved_fd_ = ::dup(STDERR_FILENO);
  if (saved_fd_ < 0 || ::dup2(::fileno(file_), STDERR_FILENO) < 0) {
    if (saved_fd_ >= 0) ::close(saved_fd_);
    saved_fd_ = -1;
    std::fclose(file_);
    file_ = nullptr;
  }
}

StderrCapture::~StderrCapture() {
  if (!file_) return;
  std::fflush(stderr);
  ::dup2(saved_fd_, STDERR_FILENO);
  ::close(saved_fd_);
  std::fclose(file_);
}

std::string StderrCapture::text(size_t max_chars) {
  if (!file_) return {};
  std::fflush(stderr);
  std::string all;
  std::array<char, 4096> block{};
  const auto fd = ::fileno(file_);
  for (off_t at = 0; all.size() < 4096;) {
    const ssize_t n = ::pread(fd, block.data(), block.size(), at);
    if (n <= 0) break;
    all.append(block.data(), static_cast<size_t>(n));
    at += n;
  }
  // One line: lines joined by "; ", surrounding blanks dropped.
  std::string line;
  size_t start = 0;
  while (start < all.size()) {
    size_t end = all.find('\n', start);
    if (end == std::string::npos) end = all.size();
    std::string piece = all.substr(start, end - start);
    while (!piece.empty() && (piece.back() == '\r' || piece.back() == ' ')) piece.pop_back();
    if (!piece.empty()) line += (line.empty() ? "" : "; ") + piece;
    start = end + 1;
  }
  return one_line(line, max_chars);
}

std::string with_captured(const std::string& message, StderrCapture& capture) {
  // The captured text gets what room the error line has left (kMaxMessageChars): the message, which
  // names the input, is never what is cut.
  const size_t used = message.size() + 3;  // " (" and ")"
  if (used + 20 > kMaxMessageChars) return message;
  const std::string t = capture.text(std::min<size_t>(120, kMaxMessageChars - used));
  return t.empty() ? message : message + " (" + t + ")";
}

}  // namespace tfu
