// An OpenGL command stream recorded by apitrace (`apitrace trace --api gl`), read through apitrace's
// own text dump: `apitrace dump --blobs --multiline=no --calls=0-LAST TRACE` run in a temporary
// directory, which prints one call per line and writes every blob argument (texture images,
// client arrays, index lists) to a file blob_callN.bin there. The binary trace format is apitrace's
// business; this file only parses the dump's text (docs/gl-replay.md, "The route"):
//
//   N name(arg = value, arg = value, ...) [= return value] [// fake]
//   value: a number (1, -8.03, 4.371139e-08), an enum (GL_TRIANGLES), a list {1, 0, 0.5},
//          blob("blob_callN.bin"), a reference &8 / &{...}, a pointer 0x.., NULL, a "string"
// Fake calls are the ones apitrace adds to carry what a draw reads from client memory (the arrays'
// contents at draw time, blob(N) from vertex 0 to the highest index drawn).
//
// Frames: frame K (from 0) is the calls after the K-th glXSwapBuffers up to and including the
// (K+1)-th (apitrace's and glretrace's numbering); the calls are read from 0 to the end of frame K.
// Errors (no apitrace, a truncated or corrupt trace, a frame out of range, a line that does not
// parse, a blob that is missing or larger than its call says) are InputError naming the trace and
// the call number.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tfu::gl {

struct Value {
  enum class Kind { Number, Enum, List, Blob, Other };
  Kind kind = Kind::Other;
  double number = 0;            // Number (an Enum's text is in `text`)
  std::string text;             // as dumped (Enum: its name; Blob: the blob's file; Other: the raw text)
  std::vector<double> list;     // List: the numbers of {...} (a list of non-numbers is Other)
};

struct Call {
  uint64_t number = 0;  // apitrace's call number
  std::string name;
  std::vector<std::pair<std::string, Value>> args;  // in order, by name
  bool fake = false;
  // The argument named `arg`; InputError naming the call if missing or not of `kind`.
  const Value& arg(const std::string& arg, Value::Kind kind) const;
  double number_arg(const std::string& a) const { return arg(a, Value::Kind::Number).number; }
  const std::string& enum_arg(const std::string& a) const;  // an enum, or GL_FALSE/GL_TRUE/0 as a name
};

struct Stream {
  std::string trace;       // the trace file, for messages
  std::vector<Call> calls;  // calls 0 .. end of the frame asked for, in order
  size_t frame_begin = 0;   // index in `calls` of the frame's first call
  int frames = 0;           // frames in the trace (swaps, plus a last partial frame)
  std::string blob_dir;     // the temporary directory holding the blobs (removed with the Dump)
  // Where reading the trace went (tfu sim --gl-trace --bench): apitrace's two dumps (wall clock, and
  // the CPU of its process: user + system), and this process's CPU parsing their text.
  double dump_wall_seconds = 0, dump_cpu_seconds = 0, parse_cpu_seconds = 0;
};

// This thread's CPU time in seconds (CLOCK_THREAD_CPUTIME_ID).
double thread_seconds();

// Largest blob read (a 4096 x 4096 RGBA level is 64 MiB), and largest dump text accepted.
inline constexpr uint64_t kMaxBlobBytes = uint64_t{64} << 20;
inline constexpr uint64_t kMaxDumpBytes = uint64_t{2} << 30;

// Where a dump's temporary directory is made: $TFU_GL_BLOB_DIR, else /dev/shm when writable (the
// blobs are many small files: in memory they cost a tenth of the system time), else the temp directory.
std::string blob_parent();

// The apitrace program: $TFU_APITRACE, else `apitrace` on the PATH.
std::string apitrace_program();

// The temporary directory of one dump; removes it and its blobs when destroyed.
class Dump {
 public:
  // Runs apitrace on `trace` and parses calls 0 .. end of `frame`.
  Dump(const std::string& trace, int frame);
  ~Dump();
  Dump(const Dump&) = delete;
  Dump& operator=(const Dump&) = delete;
  const Stream& stream() const { return stream_; }
  // The bytes of a call's blob argument: exactly `expected` bytes are needed (InputError naming the
  // trace and call when the blob is shorter, absent, or larger than kMaxBlobBytes); a longer blob
  // is read up to `expected`.
  std::vector<uint8_t> blob(const Call& c, const std::string& arg, uint64_t expected) const;

 private:
  Stream stream_;
};

// Parses one line of `apitrace dump` text (exposed for tests); nullopt for lines that are not calls
// (blank, a process.name line); InputError "WHERE: ..." for a line that does not parse.
std::optional<Call> parse_call_line(const std::string& line, const std::string& where);

}  // namespace tfu::gl
