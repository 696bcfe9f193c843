#include "cmodel/gl_trace.hpp"

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string_view>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu::gl {
namespace {

namespace fs = std::filesystem;

std::string trim(std::string_view s) {
  size_t a = 0, b = s.size();
  while (a < b && (s[a] == ' ' || s[a] == '\t' || s[a] == '\r')) ++a;
  while (b > a && (s[b - 1] == ' ' || s[b - 1] == '\t' || s[b - 1] == '\r')) --b;
  return std::string(s.substr(a, b - a));
}

// Splits `s` at the commas outside (), {}, [] and "strings".
std::vector<std::string> split_top_level(std::string_view s) {
  std::vector<std::string> parts;
  int depth = 0;
  bool quoted = false;
  size_t start = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (quoted) {
      if (c == '\\' && i + 1 < s.size()) ++i;
      else if (c == '"') quoted = false;
      continue;
    }
    if (c == '"') quoted = true;
    else if (c == '(' || c == '{' || c == '[') ++depth;
    else if (c == ')' || c == '}' || c == ']') --depth;
    else if (c == ',' && depth == 0) {
      parts.push_back(trim(s.substr(start, i - start)));
      start = i + 1;
    }
  }
  const std::string last = trim(s.substr(start));
  if (!last.empty() || !parts.empty()) parts.push_back(last);
  return parts;
}

bool parse_number(const std::string& s, double& v) {
  if (s.empty()) return false;
  const char c = s[0];
  if (!(c == '-' || c == '+' || c == '.' || (c >= '0' && c <= '9'))) return false;
  if (s.size() > 1 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) return false;  // a pointer
  char* end = nullptr;
  errno = 0;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

bool is_enum_name(const std::string& s) {
  if (s.empty() || !(s[0] >= 'A' && s[0] <= 'Z')) return false;
  for (const char c : s)
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

Value parse_value(const std::string& text) {
  Value v;
  v.text = text;
  if (parse_number(text, v.number)) {
    v.kind = Value::Kind::Number;
  } else if (is_enum_name(text)) {
    v.kind = Value::Kind::Enum;
  } else if (text.rfind("blob(\"", 0) == 0 && text.size() >= 8 && text.compare(text.size() - 2, 2, "\")") == 0) {
    v.kind = Value::Kind::Blob;
    v.text = text.substr(6, text.size() - 8);
  } else if (text.size() >= 2 && text.front() == '{' && text.back() == '}') {
    v.kind = Value::Kind::List;
    for (const std::string& e : split_top_level(std::string_view(text).substr(1, text.size() - 2))) {
      double x = 0;
      if (!parse_number(e, x)) {
        v.kind = Value::Kind::Other;
        v.list.clear();
        break;
      }
      v.list.push_back(x);
    }
  } else if (text.size() >= 2 && text[0] == '&') {
    // A reference to one value (&8, &119): the value itself.
    double x = 0;
    if (parse_number(text.substr(1), x)) {
      v.kind = Value::Kind::Number;
      v.number = x;
    }
  }
  return v;
}

// Runs `argv` in `dir` with stdout and stderr to files there; returns the exit status (-1: not run).
int run_program(const std::vector<std::string>& argv, const std::string& dir, const std::string& out_file,
                const std::string& err_file) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    const int out = open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int err = open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (out < 0 || err < 0 || dup2(out, 1) < 0 || dup2(err, 2) < 0 || chdir(dir.c_str()) != 0) _exit(126);
    execvp(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string first_line_of(const std::string& path) {
  std::ifstream in(path);
  std::string line, text;
  while (std::getline(in, line))
    if (!trim(line).empty()) return trim(line);
  return text;
}

}  // namespace

const Value& Call::arg(const std::string& a, Value::Kind kind) const {
  for (const auto& [n, v] : args)
    if (n == a) {
      if (v.kind != kind)
        throw InputError(fmt::format("call {} {}: argument {} = '{}' is not of the expected kind", number, name, a,
                                     quote_input(v.text)));
      return v;
    }
  throw InputError(fmt::format("call {} {}: no argument {}", number, name, a));
}

const std::string& Call::enum_arg(const std::string& a) const { return arg(a, Value::Kind::Enum).text; }

std::optional<Call> parse_call_line(const std::string& raw, const std::string& where) {
  const std::string line = trim(raw);
  if (line.empty() || line.rfind("//", 0) == 0 || line.rfind("process.", 0) == 0) return std::nullopt;
  const auto bad = [&](const char* why) {
    return InputError(fmt::format("{}: {}: '{}'", where, why, quote_input(line)));
  };
  size_t p = 0;
  while (p < line.size() && line[p] >= '0' && line[p] <= '9') ++p;
  if (p == 0 || p > 19 || p >= line.size() || line[p] != ' ') throw bad("expected a call number and a call");
  Call c;
  c.number = std::stoull(line.substr(0, p));
  const size_t open = line.find('(', p + 1);
  if (open == std::string::npos) throw bad("expected name(arguments)");
  // Function and argument names are C identifiers (apitrace's dump), a GL name under 64 characters:
  // messages quote them whole.
  constexpr size_t kMaxNameChars = 64;
  const auto identifier = [](std::string_view id) {
    if (id.empty() || id.size() > kMaxNameChars) return false;
    for (const char ch : id)
      if (!((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_')) return false;
    return true;
  };
  c.name = line.substr(p + 1, open - p - 1);
  if (!identifier(c.name)) throw bad("expected a function name");
  // The matching parenthesis (nesting and strings skipped).
  int depth = 0;
  bool quoted = false;
  size_t close = std::string::npos;
  for (size_t i = open; i < line.size() && close == std::string::npos; ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '\\' && i + 1 < line.size()) ++i;
      else if (ch == '"') quoted = false;
      continue;
    }
    if (ch == '"') quoted = true;
    else if (ch == '(' || ch == '{' || ch == '[') ++depth;
    else if ((ch == ')' || ch == '}' || ch == ']') && --depth == 0) close = i;
  }
  if (close == std::string::npos || line[close] != ')') throw bad("unbalanced argument list (truncated line?)");
  for (const std::string& a : split_top_level(std::string_view(line).substr(open + 1, close - open - 1))) {
    const size_t eq = a.find(" = ");
    if (eq == std::string::npos) throw bad("expected arguments as name = value");
    if (!identifier(std::string_view(a).substr(0, eq))) throw bad("expected an argument name");
    c.args.emplace_back(a.substr(0, eq), parse_value(trim(std::string_view(a).substr(eq + 3))));
  }
  const std::string rest = line.substr(close + 1);
  c.fake = rest.find("// fake") != std::string::npos;
  return c;
}

std::string blob_parent() {
  if (const char* env = std::getenv("TFU_GL_BLOB_DIR"); env && *env) return env;
  // A dump writes every blob as a file: tens of thousands of small files per frame, which cost the
  // file system's metadata work (seconds of system time on a disk file system, a tenth of that in memory).
  std::error_code ec;
  if (fs::is_directory("/dev/shm", ec) && access("/dev/shm", W_OK | X_OK) == 0) return "/dev/shm";
  return fs::temp_directory_path().string();
}

double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string apitrace_program() {
  const char* env = std::getenv("TFU_APITRACE");
  return env && *env ? std::string(env) : std::string("apitrace");
}

Dump::Dump(const std::string& trace, int frame) {
  stream_.trace = trace;
  const std::string where = "--gl-trace '" + quote_path(trace) + "'";
  std::error_code ec;
  if (!fs::is_regular_file(trace, ec)) throw InputError(fmt::format("{}: not a readable file", where));
  if (frame < 0) throw InputError(fmt::format("--frame {} must be >= 0", frame));
  const std::string abs_trace = fs::absolute(trace).string();
  std::string tmpl = (fs::path(blob_parent()) / "tfu-gl-XXXXXX").string();
  if (mkdtemp(tmpl.data()) == nullptr) throw InputError(fmt::format("{}: cannot create a temporary directory", where));
  stream_.blob_dir = tmpl;
  const std::string out = stream_.blob_dir + "/dump.txt", err = stream_.blob_dir + "/dump.err";
  const std::string program = apitrace_program();
  const auto children_cpu = [] {
    rusage ru{};
    getrusage(RUSAGE_CHILDREN, &ru);
    return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  };
  const auto run = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {program, "dump", "--multiline=no", "--color=never"});
    args.push_back(abs_trace);
    const double cpu0 = children_cpu();
    const auto wall0 = std::chrono::steady_clock::now();
    const int rc = run_program(args, stream_.blob_dir, out, err);
    stream_.dump_wall_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    stream_.dump_cpu_seconds += children_cpu() - cpu0;
    if (rc == 127 || rc == 126 || rc < 0)
      throw InputError(fmt::format("{}: cannot run '{}' (apitrace 11, Debian package apitrace; or set TFU_APITRACE)", where,
                                   quote_input(program)));
    if (rc != 0) throw InputError(fmt::format("{}: apitrace dump failed (exit {}): {}", where, rc, quote_input(first_line_of(err), 120)));
  };
  const auto read_lines = [&](const std::function<void(const std::string&, size_t)>& each) {
    if (fs::file_size(out, ec) > kMaxDumpBytes) throw InputError(fmt::format("{}: dump larger than {} bytes", where, kMaxDumpBytes));
    const double t0 = thread_seconds();
    std::ifstream in(out);
    std::string line;
    for (size_t n = 1; std::getline(in, line); ++n) each(line, n);
    stream_.parse_cpu_seconds += thread_seconds() - t0;
  };
  try {
    // Pass 1: the frame boundaries (every glXSwapBuffers).
    run({"--grep=^glXSwapBuffers$"});
    std::vector<uint64_t> swaps;
    read_lines([&](const std::string& line, size_t n) {
      if (auto c = parse_call_line(line, fmt::format("{}: dump line {}", where, n))) swaps.push_back(c->number);
    });
    stream_.frames = static_cast<int>(swaps.size());
    if (swaps.empty())
      throw InputError(fmt::format("{}: no complete frame (no glXSwapBuffers in apitrace's dump): a truncated trace, or no GLX application's", where));
    if (static_cast<size_t>(frame) >= swaps.size())
      throw InputError(fmt::format("{}: --frame {} out of range: the trace has {} frames (glXSwapBuffers), 0..{}", where, frame,
                                   swaps.size(), static_cast<int>(swaps.size()) - 1));
    const uint64_t first = frame == 0 ? 0 : swaps[static_cast<size_t>(frame) - 1] + 1, last = swaps[static_cast<size_t>(frame)];
    // Pass 2: every call up to the frame's end, with the blobs.
    run({"--blobs", fmt::format("--calls=0-{}", last)});
    uint64_t previous = 0;
    bool any = false;
    read_lines([&](const std::string& line, size_t n) {
      auto c = parse_call_line(line, fmt::format("{}: dump line {}", where, n));
      if (!c) return;
      if (any && c->number <= previous)
        throw InputError(fmt::format("{}: call {} after call {}: calls out of order", where, c->number, previous));
      if (c->number < first) stream_.frame_begin = stream_.calls.size() + 1;
      previous = c->number;
      any = true;
      stream_.calls.push_back(std::move(*c));
    });
    if (stream_.calls.empty() || stream_.calls.back().number != last)
      throw InputError(fmt::format("{}: the dump ends before call {} (the end of frame {}): truncated trace?", where, last, frame));
  } catch (...) {
    fs::remove_all(stream_.blob_dir, ec);
    throw;
  }
}

Dump::~Dump() {
  std::error_code ec;
  if (!stream_.blob_dir.empty()) fs::remove_all(stream_.blob_dir, ec);
}

std::vector<uint8_t> Dump::blob(const Call& c, const std::string& arg, uint64_t expected) const {
  const std::string where = fmt::format("--gl-trace '{}': call {} {}", quote_path(stream_.trace), c.number, c.name);
  if (expected > kMaxBlobBytes)
    throw InputError(fmt::format("{}: {} needs {} bytes, more than {}", where, arg, expected, kMaxBlobBytes));
  const Value& v = c.arg(arg, Value::Kind::Blob);
  // apitrace names blobs blob_callN.bin in its working directory: nothing else is opened.
  if (v.text.find('/') != std::string::npos || v.text.rfind("blob_call", 0) != 0)
    throw InputError(fmt::format("{}: unexpected blob name '{}'", where, quote_input(v.text)));
  const std::string path = stream_.blob_dir + "/" + v.text;
  std::error_code ec;
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(fmt::format("{}: blob {} of {} is missing", where, quote_input(v.text), arg));
  if (size < expected)
    throw InputError(fmt::format("{}: {} holds {} bytes, the call needs {}", where, arg, size, expected));
  std::vector<uint8_t> bytes(expected);
  std::ifstream in(path, std::ios::binary);
  if (expected > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(expected)))
    throw InputError(fmt::format("{}: cannot read blob {}", where, quote_input(v.text)));
  return bytes;
}

}  // namespace tfu::gl
