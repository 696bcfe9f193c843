// Fuzz target (h): a request trace whose binding headers name texture files, as `tfu sim --requests`
// reads it (docs/fuzzing.md). The trace is read as if from a private temporary directory that holds
// three small textures (testbench/fuzz/fuzz_texture_files.hpp; `b b.png` is `b%20b.png` in a trace), so `# tfu-texture N FILE key=value...` lines load real files relative to the
// trace, or procedural textures, with any of a scene texture's keys. A frame that builds
// (frame_from_trace) runs its first 16 requests through the cycle model and the golden model, which
// must agree bit for bit; its bindings written back (describe_frame, write_trace) must read again.
// Bad input must end in an InputError; anything else is a finding.
//
// Cost limits of the harness: a procedural size above 64 and a file outside the directory are
// skipped (the reader's own limits are larger; `texture` fuzzes image files themselves).
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/trace.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/tfu_unit.hpp"
#include "testbench/fuzz/fuzz_input.hpp"
#include "testbench/fuzz/fuzz_texture_files.hpp"

namespace {

namespace fs = std::filesystem;

// A procedural size above 64, or a file that is not one of the three.
bool too_costly(const tfu::Trace& t) {
  for (const tfu::TraceBinding& b : t.textures) {
    if (b.spec.rfind("proc:", 0) == 0) {
      const size_t colon = b.spec.rfind(':');
      if (colon > 4) {
        const std::string size = b.spec.substr(colon + 1);
        if (size.size() > 2 || (!size.empty() && std::atoi(size.c_str()) > 64)) return true;
      }
    } else if (!tfu::fuzz::is_texture_file(b.spec)) {
      return true;
    }
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 16384) return 0;
  const fs::path dir = tfu::fuzz::texture_file_dir();
  std::istringstream in(tfu::fuzz::as_text(data, size));
  try {
    tfu::Trace trace = tfu::parse_trace(in, (dir / "fuzz.trace").string());
    if (too_costly(trace)) return 0;
    if (trace.requests.size() > 16) trace.requests.resize(16);
    tfu::FrameDefaults defaults;
    defaults.texture = tfu::TextureSpec{"proc:checkerboard:16", {}};
    const tfu::Frame frame = tfu::frame_from_trace(trace, defaults, 64);
    const tfu::rtl::UnitOutput got = tfu::rtl::run_unit(frame, trace, tfu::rtl::UnitConfig{});
    const tfu::GoldenUnit golden(frame);
    if (!tfu::rtl::first_mismatch(trace, tfu::rtl::golden_outputs(golden, trace, got), got).empty()) std::abort();
    tfu::Trace described = trace;
    tfu::describe_frame(frame, described);
    std::ostringstream out;
    tfu::write_trace(out, described);  // the names came from a trace: they can be written back
    std::istringstream back(out.str());
    const tfu::Trace again = tfu::parse_trace(back, (dir / "written.trace").string());
    if (again.textures.size() != described.textures.size()) std::abort();
    for (size_t i = 0; i < again.textures.size(); ++i)
      if (again.textures[i].spec != described.textures[i].spec ||
          again.textures[i].params != described.textures[i].params)
        std::abort();
  } catch (const tfu::InputError&) {
  }
  return 0;
}
