// Capture of what third-party libraries print on stderr. libpng (inside OpenImageIO) writes
// "libpng error: ..." straight to file descriptor 2 before OpenImageIO reports the failure, which
// would make a bad PNG two lines of output. While a StderrCapture is alive, descriptor 2 goes to an
// anonymous temporary file; text() returns what was written, as one line (newlines as "; "), and
// the destructor restores stderr. Captures are serialized by a process-wide mutex (descriptor 2 is
// process-wide); nothing of ours prints while one is alive.
#pragma once

#include <cstdio>
#include <mutex>
#include <string>

namespace tfu {

class StderrCapture {
 public:
  StderrCapture();
  ~StderrCapture();
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;
  // What was written to stderr so far, trimmed, as one line of at most `max_chars` characters.
  std::string text(size_t max_chars = 120);

 private:
  std::unique_lock<std::mutex> lock_;
  std::FILE* file_ = nullptr;
  int saved_fd_ = -1;
};

// "MESSAGE" if nothing was captured, else "MESSAGE (CAPTURED)", e.g. "a.png: cannot decode pixels:
// Read error (libpng error: IDAT: Read error: hit end of file)".
std::string with_captured(const std::string& message, StderrCapture& capture);

}  // namespace tfu
