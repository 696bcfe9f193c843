// Fuzz target: lines of `apitrace dump` text through the GL replay's call parser
// (cmodel/gl_trace.hpp). A line parses into a call or is refused with one InputError line of at
// most 300 characters; a parsed call's arguments are read as every kind (a wrong kind is an
// InputError), and the line parses again to the same call (docs/gl-replay.md).
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>

#include "cmodel/error.hpp"
#include "cmodel/gl_trace.hpp"

namespace {

bool same_call(const tfu::gl::Call& a, const tfu::gl::Call& b) {
  if (a.number != b.number || a.name != b.name || a.fake != b.fake || a.args.size() != b.args.size()) return false;
  for (size_t i = 0; i < a.args.size(); ++i) {
    const tfu::gl::Value &x = a.args[i].second, &y = b.args[i].second;
    if (a.args[i].first != b.args[i].first || x.kind != y.kind || x.text != y.text || x.list.size() != y.list.size()) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::string line;
  while (std::getline(in, line)) {
    try {
      const auto call = tfu::gl::parse_call_line(line, "fuzz: dump line 1");
      if (!call) continue;
      for (const auto& [name, value] : call->args) {
        const tfu::gl::Value* first = &value;  // Call::arg reads the first argument of a name
        for (const auto& [n, v] : call->args)
          if (n == name) {
            first = &v;
            break;
          }
        for (const auto kind : {tfu::gl::Value::Kind::Number, tfu::gl::Value::Kind::Enum, tfu::gl::Value::Kind::List,
                                tfu::gl::Value::Kind::Blob, tfu::gl::Value::Kind::Other}) {
          try {
            if (&call->arg(name, kind) != first || first->kind != kind) std::abort();
          } catch (const tfu::InputError& e) {
            if (first->kind == kind || std::strlen(e.what()) > 300) std::abort();
          }
        }
      }
      const auto again = tfu::gl::parse_call_line(line, "fuzz: dump line 1");
      if (!again || !same_call(*call, *again)) std::abort();
    } catch (const tfu::InputError& e) {
      if (std::strlen(e.what()) > 300) std::abort();
    }
  }
  return 0;
}
