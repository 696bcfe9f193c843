// The output files of one run, handled in one place for every command (docs/inputs-outputs.md).
//
//   OutputFiles outputs(force);
//   OutputFile& img = outputs.add_image("--out", out_path);   // before any work: every check
//   OutputFile& st = outputs.add("--stats", stats_path);
//   ... work ...
//   img.write_image(image);
//   st.stream() << json;
//   outputs.commit();                                          // all or nothing
//
// add() checks, before anything is written: the name is not empty and no path component is longer
// than the system allows (255 bytes); the file is not already an output of this run (compared as
// canonical paths and, for existing files, by device and inode, so "a.png", "./a.png", "//x/a.png"
// and hard links are the same file); an existing file is a regular file (a directory, device or
// pipe is refused) and is only replaced with --force; the missing parent directories can be
// created; and a temporary file can be created in the target's directory (so "cannot write" is
// known before the run, not after it); and the file is not an input of this run (cmodel/run_files.hpp:
// refused even with --force).
//
// Everything is written to that temporary file (".tfu-PID-N.tmp" beside the target). commit()
// flushes and closes every stream, checking the state after writing and after closing, then
// renames each temporary onto its target (without --force, renameat2(RENAME_NOREPLACE), so a file
// that appeared meanwhile is not replaced). If the run fails (an exception unwinds past the
// OutputFiles, or commit() fails), the destructor removes every temporary and the directories it
// created: a failed run leaves nothing behind. Every error is an InputError naming the option and
// the path.
#pragma once

#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "cmodel/run_files.hpp"
#include "cmodel/texture.hpp"

namespace tfu {

class OutputFile {
 public:
  ~OutputFile();
  const std::string& option() const { return option_; }
  const std::string& path() const { return path_; }  // as the user gave it
  // The temporary file as a stream (opened on first use).
  std::ostream& stream();
  // Writes the whole image through OpenImageIO in the format of path()'s extension.
  void write_image(const Image& img);
  // "OPTION 'PATH'" for messages.
  std::string label() const;
  // The temporary's name, for another process that reads what stream() wrote (after a flush) or
  // writes the file itself (e.g. a script, opening it without following links); then mark_written(),
  // so that commit() renames it into place.
  const std::string& temp_path() const { return temp_; }
  void mark_written() { written_ = true; }

 private:
  friend class OutputFiles;
  OutputFile(std::string option, std::string path, std::string temp);
  void close_stream();  // flush and close, checking both
  class Buffer;  // the temporary's descriptor behind stream(); keeps the first write error
  std::string option_, path_, temp_;
  std::unique_ptr<Buffer> buffer_;
  std::unique_ptr<std::ostream> stream_;
  bool written_ = false;
  bool committed_ = false;
};

class OutputFiles {
 public:
  explicit OutputFiles(bool force);
  ~OutputFiles();
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;

  // Reserves an output (all checks above). The reference stays valid for the OutputFiles' lifetime.
  OutputFile& add(const std::string& option, const std::string& path);
  // add() for an image: also checks that OpenImageIO can write the file type of its extension.
  OutputFile& add_image(const std::string& option, const std::string& path);
  // Closes and renames every output; an output never written is dropped (nothing is created).
  void commit();

 private:
  using Identity = FileIdentity;
  void check_name(const std::string& option, const std::string& path) const;
  void make_parents(const std::string& option, const std::string& path);
  std::string make_temp(const std::string& option, const std::string& path);
  void discard();
  bool force_;
  bool done_ = false;
  std::vector<std::unique_ptr<OutputFile>> files_;
  std::vector<Identity> ids_;
  std::vector<std::string> made_dirs_;  // created by make_parents, outermost first
};

}  // namespace tfu
