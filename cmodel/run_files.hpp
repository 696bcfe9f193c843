// The files of one run: an output never replaces an input of the same run, not even with --force
// (docs/inputs-outputs.md). Every input the tools open through cmodel/input_file.hpp is noted here
// (scenes, configs, traces, textures, images), and readers that open a file themselves note it too
// (the sweep spec); OutputFiles (cmodel/output_files.hpp) notes each output it reserves, until it
// commits or discards it. An output that is an input noted so far, or an input that is an output
// not yet committed, is refused with one line (InputError), before anything is written. Files are
// the same when their canonical paths are, or, for files that exist, their device and inode (so
// "a.json", "./a.json" and a hard link are one file).
//
// Off unless the command line turns it on (track_run_files(true) in tfu's main(), one run per
// process): a library user or a test that reads a file and then writes it is not refused.
#pragma once

#include <cstdint>
#include <string>

namespace tfu {

struct FileIdentity {
  std::string canonical;  // absolute, symbolic links resolved as far as the path exists
  bool exists = false;
  uint64_t dev = 0, ino = 0;  // when it exists
  bool same_file(const FileIdentity& o) const {
    return canonical == o.canonical || (exists && o.exists && dev == o.dev && ino == o.ino);
  }
};
FileIdentity file_identity(const std::string& path);

void track_run_files(bool on);

// `path` is an input of this run (`label` names it as its messages do, e.g. "scene 'a.json'").
void note_run_input(const std::string& path, const std::string& label);
// `id` is an output of this run reserved by `owner` (`label`: e.g. "--stats 'a.json'").
void note_run_output(const void* owner, const FileIdentity& id, const std::string& label);
// `owner`'s outputs are committed or discarded: no longer pending.
void forget_run_outputs(const void* owner);

}  // namespace tfu
