#include "cmodel/error_report.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <new>
#include <stdexcept>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {

void print_error_line(std::FILE* out, const std::string& kind, const std::string& message) {
  const std::string prefix = "tfu: " + kind + ": ";
  const std::string line = one_line(prefix + message, kMaxLineChars);
  std::fprintf(out, "%s\n", line.c_str());
  std::fflush(out);
}

std::string write_deadlock_dump(const std::string& dump) {
  std::error_code ec;
  std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
  if (ec) dir = "/tmp";
  for (int n = 0; n < 1000; ++n) {
    const std::filesystem::path p = dir / fmt::format("tfu-deadlock-{}-{}.txt", static_cast<long>(::getpid()), n);
    const int fd = ::open(p.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
      if (errno == EEXIST) continue;
      throw std::runtime_error(fmt::format("cannot create {}: {}", p.string(), std::strerror(errno)));
    }
    const std::string text = dump + "\n";
    size_t done = 0;
    while (done < text.size()) {
      const ssize_t w = ::write(fd, text.data() + done, text.size() - done);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        const int err = errno;
        ::close(fd);
        throw std::runtime_error(fmt::format("cannot write {}: {}", p.string(), std::strerror(err)));
      }
      done += static_cast<size_t>(w);
    }
    if (::close(fd) != 0) throw std::runtime_error(fmt::format("cannot write {}: {}", p.string(), std::strerror(errno)));
    return p.string();
  }
  throw std::runtime_error("cannot create a dump file in " + dir.string());
}

int report_error(std::exception_ptr e, std::FILE* out) {
  try {
    std::rethrow_exception(e);
  } catch (const InputError& x) {
    print_error_line(out, "error", x.what());
    return kExitBadInput;
  } catch (const CheckFailed& x) {
    print_error_line(out, "check failed", x.what());
    return kExitCheckFailed;
  } catch (const DeadlockError& x) {
    std::string where;
    try {
      where = "full per-stage dump in " + write_deadlock_dump(x.dump());
    } catch (const std::exception& w) {
      where = std::string("the per-stage dump could not be written: ") + w.what();
    }
    // The file name must survive the cut: the summary gives way.
    const std::string tail = "; " + where + " (a bug: please report it)";
    const size_t room = kMaxLineChars > tail.size() + 20 ? kMaxLineChars - tail.size() - 15 : 40;
    print_error_line(out, "deadlock", one_line(x.what(), room) + tail);
    return kExitDeadlock;
  } catch (const std::filesystem::filesystem_error& x) {
    // The file system refused something the user asked for (a path, a permission, a full disk).
    print_error_line(out, "error", x.path1().empty() ? x.code().message()
                                                     : fmt::format("'{}': {}", quote_input(x.path1().string()), x.code().message()));
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    print_error_line(out, "error", "out of memory (an input too large for this machine?)");
    return kExitBadInput;
  } catch (const std::exception& x) {
    print_error_line(out, "internal error", std::string(x.what()) + " (a bug: please report it)");
    return kExitInternal;
  } catch (...) {
    print_error_line(out, "internal error", "unknown exception (a bug: please report it)");
    return kExitInternal;
  }
}

}  // namespace tfu
