#include "cmodel/trace.hpp"

#include <cctype>
#include <cstdlib>
#include <istream>
#include <ostream>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/lod.hpp"

namespace tfu {

const char* trace_mode_name(TraceMode m) {
  switch (m) {
    case TraceMode::Lod: return "lod";
    case TraceMode::Grad: return "grad";
    case TraceMode::Quad: return "quad";
  }
  return "?";
}

namespace {

int fields_of(TraceMode m) { return m == TraceMode::Lod ? 3 : (m == TraceMode::Grad ? 6 : 2); }

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// Header: "# tfu-trace mode=<m>" (other comment lines are ignored).
bool parse_header(const std::string& line, TraceMode* mode, const std::string& where) {
  const std::string key = "# tfu-trace";
  if (line.rfind(key, 0) != 0) return false;
  const auto p = line.find("mode=");
  if (p == std::string::npos) return true;
  const std::string m = trim(line.substr(p + 5));
  if (m == "lod") *mode = TraceMode::Lod;
  else if (m == "grad") *mode = TraceMode::Grad;
  else if (m == "quad") *mode = TraceMode::Quad;
  else throw InputError(fmt::format("{}: unknown trace mode '{}' (expected lod, grad or quad)", where, quote_input(m)));
  return true;
}

// The number syntax of docs/traces.md: decimal floating point ([+-] digits [. digits] [e [+-] digits],
// or [+-] . digits ...) or nan / inf / infinity in any case. strtof alone would also take hex floats
// ("0x1p-1") and stop at a NUL byte ("0.5\0garbage" would read as 0.5).
bool is_decimal_number(const std::string& f) {
  size_t i = 0;
  if (i < f.size() && (f[i] == '+' || f[i] == '-')) ++i;
  std::string word;
  for (size_t k = i; k < f.size(); ++k) word += static_cast<char>(std::tolower(static_cast<unsigned char>(f[k])));
  if (word == "nan" || word == "inf" || word == "infinity") return true;
  const auto digits = [&] {
    const size_t start = i;
    while (i < f.size() && f[i] >= '0' && f[i] <= '9') ++i;
    return i - start;
  };
  size_t mantissa = digits();
  if (i < f.size() && f[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < f.size() && (f[i] == 'e' || f[i] == 'E')) {
    ++i;
    if (i < f.size() && (f[i] == '+' || f[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == f.size();
}

}  // namespace

Trace parse_trace(std::istream& in, const std::string& name) {
  Trace tr;
  bool mode_known = false;
  std::string line;
  size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const std::string where = fmt::format("{}:{}", name, lineno);
    const std::string s = trim(line);
    if (s.empty()) continue;
    if (s[0] == '#') {
      TraceMode m{};
      if (parse_header(s, &m, where) && s.find("mode=") != std::string::npos) {
        if (!tr.requests.empty()) throw InputError(fmt::format("{}: trace header after the first request", where));
        tr.mode = m;
        mode_known = true;
      }
      continue;
    }
    std::vector<float> v;
    size_t pos = 0;
    while (true) {
      const auto comma = s.find(',', pos);
      const std::string field = trim(s.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
      if (field.empty()) throw InputError(fmt::format("{}: empty field {}", where, v.size() + 1));
      if (!is_decimal_number(field))
        throw InputError(fmt::format("{}: field {} '{}' is not a decimal number", where, v.size() + 1, quote_input(field)));
      const float x = std::strtof(field.c_str(), nullptr);
      v.push_back(x);  // ERANGE: strtof already returns +-inf or a denormal/0, which is the binary32 value
      if (v.size() > 6) throw InputError(fmt::format("{}: more than 6 fields", where));
      if (comma == std::string::npos) break;
      pos = comma + 1;
    }
    if (!mode_known) {
      if (v.size() == 3) tr.mode = TraceMode::Lod;
      else if (v.size() == 6) tr.mode = TraceMode::Grad;
      else if (v.size() == 2) tr.mode = TraceMode::Quad;
      else throw InputError(fmt::format("{}: {} fields; a request has 2 (quad), 3 (s,t,lod) or 6 (gradients)", where, v.size()));
      mode_known = true;
    }
    if (static_cast<int>(v.size()) != fields_of(tr.mode))
      throw InputError(fmt::format("{}: {} fields, but this is a {} trace with {} per line", where, v.size(),
                                   trace_mode_name(tr.mode), fields_of(tr.mode)));
    if (tr.requests.size() >= kMaxTraceRequests)
      throw InputError(fmt::format("{}: more than {} requests", where, kMaxTraceRequests));
    TraceRequest r;
    r.s = v[0];
    r.t = v[1];
    if (tr.mode == TraceMode::Lod) r.lod = v[2];
    if (tr.mode == TraceMode::Grad) {
      r.dsdx = v[2];
      r.dtdx = v[3];
      r.dsdy = v[4];
      r.dtdy = v[5];
    }
    tr.requests.push_back(r);
  }
  if (tr.mode == TraceMode::Quad && tr.requests.size() % 4 != 0)
    throw InputError(fmt::format("{}: quad trace has {} requests, not a multiple of 4", name, tr.requests.size()));
  return tr;
}

Trace load_trace(const std::string& path) {
  InputFile f(path, "trace " + quoted_path(path), kMaxTraceBytes);  // a regular file of bounded size
  return parse_trace(f.stream(), quote_path(path));
}

void write_trace(std::ostream& out, const Trace& trace) {
  out << "# tfu-trace mode=" << trace_mode_name(trace.mode) << "\n";
  for (const TraceRequest& r : trace.requests) {
    out << fmt::format("{:.9g},{:.9g}", r.s, r.t);
    if (trace.mode == TraceMode::Lod) out << fmt::format(",{:.9g}", r.lod);
    if (trace.mode == TraceMode::Grad) out << fmt::format(",{:.9g},{:.9g},{:.9g},{:.9g}", r.dsdx, r.dtdx, r.dsdy, r.dtdy);
    out << '\n';
  }
}

std::vector<int32_t> trace_lambdas(const Trace& tr, int width, int height) {
  std::vector<int32_t> lam(tr.requests.size());
  for (size_t i = 0; i < tr.requests.size(); ++i) {
    const TraceRequest& r = tr.requests[i];
    switch (tr.mode) {
      case TraceMode::Lod: lam[i] = lambda_explicit(r.lod); break;
      case TraceMode::Grad: lam[i] = lambda_from_gradients(r.dsdx, r.dtdx, r.dsdy, r.dtdy, width, height); break;
      case TraceMode::Quad:
        if (i % 4 == 0) {
          const float s[4] = {r.s, tr.requests[i + 1].s, tr.requests[i + 2].s, tr.requests[i + 3].s};
          const float t[4] = {r.t, tr.requests[i + 1].t, tr.requests[i + 2].t, tr.requests[i + 3].t};
          lam[i] = lambda_from_quad(s, t, width, height);
        } else {
          lam[i] = lam[i - i % 4];  // one lambda per quad
        }
        break;
    }
  }
  return lam;
}

}  // namespace tfu
