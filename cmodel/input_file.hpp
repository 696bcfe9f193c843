// Input files: every file the tools read (traces, scenes, unit configs, textures, images) is checked
// here first, in one place (docs/inputs-outputs.md):
//   * it must be a regular file: a directory, named pipe (FIFO), character or block device or socket
//     is refused, so that `/dev/zero` or a pipe nobody writes to never hangs a run;
//   * it must be at most a size bound (per kind of input), checked against the file's size before
//     reading and again while reading (files in /proc report size 0);
//   * a missing file, a path component longer than the system allows, a permission problem: one line.
// Errors are InputError "LABEL: reason", LABEL naming the input as the caller gives it (e.g.
// "--config 'x.json'" or just the path).
#pragma once

#include <cstdint>
#include <istream>
#include <memory>
#include <string>

#include <sys/types.h>

namespace tfu {

inline constexpr uint64_t kMaxTextInputBytes = uint64_t{64} << 20;  // scene and config JSON
inline constexpr uint64_t kMaxTraceBytes = uint64_t{4} << 30;       // request traces (2^26 requests fit)
inline constexpr uint64_t kMaxImageBytes = uint64_t{1} << 30;       // texture and image files

// The path as a label for messages: quote_path(path) in single quotes.
std::string quoted_path(const std::string& path);

// What a file that is not a regular file is, for messages (`mode` from stat): "a directory", "a
// named pipe", "a character device", "a block device", "a socket", else "not a regular file".
std::string file_kind(mode_t mode);

// Throws InputError unless `path` names a regular file of at most `max_bytes` bytes that can be
// opened for reading. For inputs opened by a library (OpenImageIO).
void check_input_file(const std::string& path, const std::string& label, uint64_t max_bytes);

// A checked input file read as a stream. A read error or a file that grows past `max_bytes` while
// being read throws InputError out of the stream's read operations.
class InputFile {
 public:
  // RunInput: noted as an input of the run (cmodel/run_files.hpp), which no output may then replace.
  // OwnState: a file a command keeps for itself and replaces by design, checked all the same (a
  // sweep directory's sweep.json and point files, which a resumed run reads and writes again).
  enum class Use { RunInput, OwnState };
  InputFile(const std::string& path, const std::string& label, uint64_t max_bytes, Use use = Use::RunInput);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  std::istream& stream() { return stream_; }

 private:
  class Buffer;
  std::unique_ptr<Buffer> buffer_;
  std::istream stream_;
};

// The whole file (checked as above).
std::string read_input_file(const std::string& path, const std::string& label, uint64_t max_bytes,
                            InputFile::Use use = InputFile::Use::RunInput);

}  // namespace tfu
