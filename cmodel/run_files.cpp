// The files of one run (cmodel/run_files.hpp).
#include "cmodel/run_files.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <mutex>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {
namespace {

namespace fs = std::filesystem;

struct NotedFile {
  FileIdentity id;
  std::string label;
  const void* owner = nullptr;  // outputs: the OutputFiles that reserved it
};

std::atomic<bool> g_tracking{false};
std::mutex g_mutex;               // inputs are opened on several threads (texture loading)
std::vector<NotedFile> g_inputs;  // every input of the run
std::vector<NotedFile> g_outputs;  // outputs reserved and not yet committed or discarded

}  // namespace

FileIdentity file_identity(const std::string& path) {
  FileIdentity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.dev = static_cast<uint64_t>(st.st_dev);
    id.ino = static_cast<uint64_t>(st.st_ino);
  }
  std::error_code ec;
  const fs::path abs = fs::absolute(path, ec);
  const fs::path canon = ec ? fs::path(path) : fs::weakly_canonical(abs, ec);
  id.canonical = (ec ? abs : canon).lexically_normal().string();
  return id;
}

void track_run_files(bool on) { g_tracking = on; }

void note_run_input(const std::string& path, const std::string& label) {
  if (!g_tracking) return;
  FileIdentity id = file_identity(path);
  const std::lock_guard<std::mutex> lock(g_mutex);
  for (const NotedFile& o : g_outputs)
    if (o.id.same_file(id))
      throw InputError(fmt::format("{} is also an output of this run ({}); an output never replaces an input, even "
                                   "with --force",
                                   label, o.label));
  if (std::none_of(g_inputs.begin(), g_inputs.end(), [&](const NotedFile& i) { return i.id.same_file(id); }))
    g_inputs.push_back({std::move(id), label, nullptr});
}

void note_run_output(const void* owner, const FileIdentity& id, const std::string& label) {
  if (!g_tracking) return;
  const std::lock_guard<std::mutex> lock(g_mutex);
  for (const NotedFile& i : g_inputs)
    if (i.id.same_file(id))
      throw InputError(fmt::format("{} is also an input of this run ({}); an output never replaces an input, even "
                                   "with --force",
                                   label, i.label));
  g_outputs.push_back({id, label, owner});
}

void forget_run_outputs(const void* owner) {
  if (!g_tracking) return;
  const std::lock_guard<std::mutex> lock(g_mutex);
  std::erase_if(g_outputs, [owner](const NotedFile& o) { return o.owner == owner; });
}

}  // namespace tfu
