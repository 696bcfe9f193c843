#include "cmodel/trace.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <istream>
#include <ostream>
#include <string_view>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/raster_order.hpp"

namespace tfu {

const char* trace_mode_name(TraceMode m) { return kTraceModeNames.name(m); }

namespace {

// The columns of a request line.
enum class Column { Texture, Sampler, Stage, X, Y, S, T, Lod, Dsdx, Dtdx, Dsdy, Dtdy };
constexpr std::pair<const char*, Column> kColumns[] = {
    {"texture", Column::Texture}, {"sampler", Column::Sampler}, {"stage", Column::Stage}, {"x", Column::X},
    {"y", Column::Y},             {"s", Column::S},
    {"t", Column::T},             {"lod", Column::Lod},         {"dsdx", Column::Dsdx},   {"dtdx", Column::Dtdx},
    {"dsdy", Column::Dsdy},       {"dtdy", Column::Dtdy}};

std::vector<Column> default_columns(TraceMode m) {
  switch (m) {
    case TraceMode::Lod: return {Column::S, Column::T, Column::Lod};
    case TraceMode::Grad: return {Column::S, Column::T, Column::Dsdx, Column::Dtdx, Column::Dsdy, Column::Dtdy};
    case TraceMode::Quad: return {Column::S, Column::T};
  }
  return {};
}

const char* column_name(Column c) {
  for (const auto& [n, k] : kColumns)
    if (k == c) return n;
  return "?";
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> w;
  size_t p = 0;
  while (true) {
    p = s.find_first_not_of(" \t", p);
    if (p == std::string::npos) break;
    const size_t e = s.find_first_of(" \t", p);
    w.push_back(s.substr(p, e == std::string::npos ? std::string::npos : e - p));
    if (e == std::string::npos) break;
    p = e;
  }
  return w;
}

struct Header {
  bool mode_known = false;
  std::vector<Column> columns;  // empty: the mode's default columns
};

// "# tfu-trace mode=<m> [fields=a,b,...]"
void parse_trace_header(const std::string& line, Trace& tr, Header& h, const std::string& where) {
  for (const std::string& w : words(line.substr(std::string("# tfu-trace").size()))) {
    const auto eq = w.find('=');
    const std::string key = w.substr(0, eq), value = eq == std::string::npos ? std::string() : w.substr(eq + 1);
    if (key == "mode") {
      if (!kTraceModeNames.find(value, tr.mode))
        throw InputError(fmt::format("{}: unknown trace mode '{}' (expected {})", where, quote_input(value),
                                     kTraceModeNames.expected()));
      h.mode_known = true;
    } else if (key == "fields") {
      h.columns.clear();
      size_t p = 0;
      while (true) {
        const size_t c = value.find(',', p);
        const std::string name = value.substr(p, c == std::string::npos ? std::string::npos : c - p);
        const auto it = std::find_if(std::begin(kColumns), std::end(kColumns), [&](const auto& k) { return name == k.first; });
        if (it == std::end(kColumns)) throw InputError(fmt::format("{}: unknown field '{}'", where, quote_input(name)));
        if (std::find(h.columns.begin(), h.columns.end(), it->second) != h.columns.end())
          throw InputError(fmt::format("{}: field '{}' twice", where, name));
        h.columns.push_back(it->second);
        if (c == std::string::npos) break;
        p = c + 1;
      }
    } else {
      throw InputError(fmt::format("{}: unknown trace header key '{}'", where, quote_input(key)));
    }
  }
  if (h.columns.empty()) return;
  if (!h.mode_known) throw InputError(fmt::format("{}: fields= needs mode=", where));
  for (Column c : default_columns(tr.mode))
    if (std::find(h.columns.begin(), h.columns.end(), c) == h.columns.end())
      throw InputError(fmt::format("{}: a {} trace needs the field '{}'", where, trace_mode_name(tr.mode), column_name(c)));
  const bool x = std::find(h.columns.begin(), h.columns.end(), Column::X) != h.columns.end();
  const bool y = std::find(h.columns.begin(), h.columns.end(), Column::Y) != h.columns.end();
  if (x != y) throw InputError(fmt::format("{}: a screen position needs both fields 'x' and 'y'", where));
  if (x && tr.mode != TraceMode::Quad)
    throw InputError(fmt::format("{}: screen positions 'x', 'y' belong to quad traces, not to a {} trace", where, trace_mode_name(tr.mode)));
  tr.positions = x;
  for (Column c : h.columns) {
    const auto need = default_columns(tr.mode);
    if (c >= Column::S && std::find(need.begin(), need.end(), c) == need.end())
      throw InputError(fmt::format("{}: field '{}' is not one of a {} trace", where, column_name(c), trace_mode_name(tr.mode)));
  }
}

// The words of a binding line (docs/traces.md, "Descriptor indices and bindings"): a texture's spec
// is a file name as the user or the archive spelled it, which may hold a space ("my textures/a.png")
// or look like a parameter ("a.png mipmaps=none"). So a word is written with each space, '%' and,
// in a key, '=' as %20, %25, %3D, and read back with every %XX decoded (two hex digits); names
// without these bytes are written as they are.
std::string encode_word(std::string_view w, bool key) {
  std::string out;
  for (const char c : w) {
    if (c == ' ' || c == '%' || (key && c == '=')) {
      out += fmt::format("%{:02X}", static_cast<unsigned>(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out;
}

std::string decode_word(const std::string& w, const std::string& where) {
  std::string out;
  for (size_t i = 0; i < w.size(); ++i) {
    if (w[i] != '%') {
      out += w[i];
      continue;
    }
    const auto hex = [&](size_t k) { return k < w.size() && std::isxdigit(static_cast<unsigned char>(w[k])); };
    if (!hex(i + 1) || !hex(i + 2))
      throw InputError(fmt::format("{}: '{}': a '%' starts %XX, two hex digits (a '%' itself is %25)", where, quote_input(w)));
    out += static_cast<char>(std::stoi(w.substr(i + 1, 2), nullptr, 16));
    i += 2;
  }
  return out;
}

// "# tfu-texture N SPEC key=value..." / "# tfu-sampler N key=value..."
TraceBinding parse_binding(const std::string& line, bool texture, const std::string& where) {
  // Names never carry a control character (docs/inputs-outputs.md, "Names"; write_trace refuses them).
  if (has_control_characters(line)) throw InputError(fmt::format("{}: a control character in a binding line", where));
  const std::vector<std::string> w = words(line);
  TraceBinding b;
  b.where = where;
  size_t k = 2;
  if (w.size() < 3) throw InputError(fmt::format("{}: a binding needs an index{}", where, texture ? " and a texture" : ""));
  char* end = nullptr;
  const long idx = std::strtol(w[2].c_str(), &end, 10);
  const long max_index = texture ? 4095 : 255;
  if (end == w[2].c_str() || end != w[2].c_str() + w[2].size() || idx < 0 || idx > max_index)
    throw InputError(fmt::format("{}: index '{}' is not an integer 0..{}", where, quote_input(w[2]), max_index));
  b.index = static_cast<int>(idx);
  k = 3;
  if (texture) {
    if (w.size() < 4) throw InputError(fmt::format("{}: texture binding {} names no texture", where, b.index));
    b.spec = decode_word(w[3], where);
    k = 4;
  }
  for (; k < w.size(); ++k) {
    const auto eq = w[k].find('=');
    if (eq == std::string::npos || eq == 0) throw InputError(fmt::format("{}: '{}' is not key=value", where, quote_input(w[k])));
    std::string key = decode_word(w[k].substr(0, eq), where);
    if (b.params.contains(key)) throw InputError(fmt::format("{}: key '{}' twice", where, quote_input(key)));
    b.params.emplace(std::move(key), decode_word(w[k].substr(eq + 1), where));
  }
  return b;
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

float parse_float(const std::string& field, size_t column, const std::string& where) {
  if (!is_decimal_number(field))
    throw InputError(fmt::format("{}: field {} '{}' is not a decimal number", where, column, quote_input(field)));
  const float x = std::strtof(field.c_str(), nullptr);
  return x;  // ERANGE: strtof already returns +-inf or a denormal/0, which is the binary32 value
}

int parse_index(const std::string& field, size_t column, long max, const std::string& where) {
  char* end = nullptr;
  const long x = std::strtol(field.c_str(), &end, 10);
  if (end == field.c_str() || end != field.c_str() + field.size() || x < 0 || x > max)  // no stray byte (NUL)
    throw InputError(fmt::format("{}: field {} '{}' is not an integer 0..{}", where, column, quote_input(field), max));
  return static_cast<int>(x);
}


}  // namespace

Trace parse_trace(std::istream& in, const std::string& name) {
  Trace tr;
  tr.source = name;
  Header h;
  std::string line;
  size_t lineno = 0;
  std::vector<std::string> fields;
  while (std::getline(in, line)) {
    ++lineno;
    const std::string where = fmt::format("{}:{}", name, lineno);
    const std::string s = trim(line);
    if (s.empty()) continue;
    if (s[0] == '#') {
      const bool header = s.rfind("# tfu-trace", 0) == 0, tex = s.rfind("# tfu-texture", 0) == 0,
                 smp = s.rfind("# tfu-sampler", 0) == 0;
      if ((header || tex || smp) && !tr.requests.empty())
        throw InputError(fmt::format("{}: trace header after the first request", where));
      if (header) parse_trace_header(s, tr, h, where);
      if (tex) tr.textures.push_back(parse_binding(s, true, where));
      if (smp) tr.samplers.push_back(parse_binding(s, false, where));
      continue;
    }
    fields.clear();
    size_t pos = 0;
    while (true) {
      const auto comma = s.find(',', pos);
      fields.push_back(trim(s.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos)));
      if (fields.back().empty()) throw InputError(fmt::format("{}: empty field {}", where, fields.size()));
      if (fields.size() > std::size(kColumns)) throw InputError(fmt::format("{}: too many fields", where));
      if (comma == std::string::npos) break;
      pos = comma + 1;
    }
    if (!h.mode_known) {
      if (fields.size() == 3) tr.mode = TraceMode::Lod;
      else if (fields.size() == 6) tr.mode = TraceMode::Grad;
      else if (fields.size() == 2) tr.mode = TraceMode::Quad;
      else throw InputError(fmt::format("{}: {} fields; a request has 2 (quad), 3 (s,t,lod) or 6 (gradients)", where, fields.size()));
      h.mode_known = true;
    }
    if (h.columns.empty()) h.columns = default_columns(tr.mode);
    if (fields.size() != h.columns.size())
      throw InputError(fmt::format("{}: {} fields, but this {} trace has {} per line", where, fields.size(),
                                   trace_mode_name(tr.mode), h.columns.size()));
    if (tr.requests.size() >= kMaxTraceRequests)
      throw InputError(fmt::format("{}: more than {} requests", where, kMaxTraceRequests));
    TraceRequest r;
    for (size_t c = 0; c < fields.size(); ++c) {
      const std::string& f = fields[c];
      switch (h.columns[c]) {
        case Column::Texture: r.texture = static_cast<uint16_t>(parse_index(f, c + 1, 4095, where)); break;
        case Column::Sampler: r.sampler = static_cast<uint8_t>(parse_index(f, c + 1, 255, where)); break;
        case Column::Stage: r.stage = static_cast<uint8_t>(parse_index(f, c + 1, 3, where)); break;
        case Column::X: r.x = static_cast<uint16_t>(parse_index(f, c + 1, kMaxTracePosition, where)); break;
        case Column::Y: r.y = static_cast<uint16_t>(parse_index(f, c + 1, kMaxTracePosition, where)); break;
        case Column::S: r.s = parse_float(f, c + 1, where); break;
        case Column::T: r.t = parse_float(f, c + 1, where); break;
        case Column::Lod: r.lod = parse_float(f, c + 1, where); break;
        case Column::Dsdx: r.dsdx = parse_float(f, c + 1, where); break;
        case Column::Dtdx: r.dtdx = parse_float(f, c + 1, where); break;
        case Column::Dsdy: r.dsdy = parse_float(f, c + 1, where); break;
        case Column::Dtdy: r.dtdy = parse_float(f, c + 1, where); break;
      }
    }
    if (tr.mode == TraceMode::Quad && tr.requests.size() % 4 != 0) {
      const TraceRequest& q = tr.requests[tr.requests.size() - tr.requests.size() % 4];
      if (q.texture != r.texture || q.sampler != r.sampler || q.stage != r.stage)
        throw InputError(fmt::format("{}: the four pixels of a quad name one texture, sampler and stage", where));
      if (q.x != r.x || q.y != r.y)
        throw InputError(fmt::format("{}: the four pixels of a quad name one screen position x, y", where));
    }
    if (tr.requests.size() == tr.requests.capacity()) {
      // The vector grows by doubling, reserved here so that what it holds is what the budget is charged
      // (cmodel/memory_budget.hpp): a 4 GiB trace of short lines holds some 400 million requests.
      const size_t grow = std::max<size_t>(4096, tr.requests.capacity());
      if (!tr.memory) tr.memory = std::make_shared<MemoryCharge>(0, "trace " + quote_input(name, 100), "requests");
      tr.memory->add(grow * sizeof(TraceRequest));
      tr.requests.reserve(tr.requests.capacity() + grow);
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
  // A binding is one line of words: a control character (a newline above all) in its spec or a
  // parameter would start a line of its own, so it is refused before anything is written; so are
  // the words the reader could not take back (a texture with no spec, an empty key). Spaces, '%'
  // and a key's '=' are encoded (encode_word).
  for (const auto* bindings : {&trace.textures, &trace.samplers})
    for (const TraceBinding& b : *bindings) {
      const char* kind = bindings == &trace.textures ? "tfu-texture" : "tfu-sampler";
      bool bad = has_control_characters(b.spec);
      for (const auto& [k, v] : b.params) bad = bad || has_control_characters(k) || has_control_characters(v);
      if (bad)
        throw InputError(fmt::format("trace binding {} {} ('{}'): a control character cannot be written into a trace line",
                                     kind, b.index, quote_input(b.spec)));
      if (bindings == &trace.textures && b.spec.empty())
        throw InputError(fmt::format("trace binding {} {}: a texture binding needs a spec", kind, b.index));
      if (b.params.contains(""))
        throw InputError(fmt::format("trace binding {} {} ('{}'): a parameter with an empty key", kind, b.index, quote_input(b.spec)));
    }
  if (trace.positions && trace.mode != TraceMode::Quad)
    throw InputError("a trace with screen positions must be a quad trace");
  bool indexed = trace.positions || !trace.textures.empty() || !trace.samplers.empty();
  for (const TraceRequest& r : trace.requests) indexed = indexed || r.texture != 0 || r.sampler != 0 || r.stage != 0;
  out << "# tfu-trace mode=" << trace_mode_name(trace.mode);
  if (indexed) {
    out << " fields=texture,sampler,stage";
    if (trace.positions) out << ",x,y";
    for (Column c : default_columns(trace.mode)) out << ',' << column_name(c);
  }
  out << '\n';
  const auto binding = [&out](const char* kind, const TraceBinding& b) {
    out << "# " << kind << ' ' << b.index;
    if (!b.spec.empty()) out << ' ' << encode_word(b.spec, false);
    for (const auto& [k, v] : b.params) out << ' ' << encode_word(k, true) << '=' << encode_word(v, false);
    out << '\n';
  };
  for (const TraceBinding& b : trace.textures) binding("tfu-texture", b);
  for (const TraceBinding& b : trace.samplers) binding("tfu-sampler", b);
  for (const TraceRequest& r : trace.requests) {
    if (indexed) out << r.texture << ',' << int{r.sampler} << ',' << int{r.stage} << ',';
    if (trace.positions) out << r.x << ',' << r.y << ',';
    out << fmt::format("{:.9g},{:.9g}", r.s, r.t);
    if (trace.mode == TraceMode::Lod) out << fmt::format(",{:.9g}", r.lod);
    if (trace.mode == TraceMode::Grad) out << fmt::format(",{:.9g},{:.9g},{:.9g},{:.9g}", r.dsdx, r.dtdx, r.dsdy, r.dtdy);
    out << '\n';
  }
}

Trace reorder_trace(const Trace& trace, const RasterOrder& order) {
  if (trace.mode != TraceMode::Quad || !trace.positions)
    throw InputError(fmt::format("trace {}: re-ordering needs a quad trace with screen positions (fields x, y)", quote_input(trace.source, 100)));
  // One place per quad; the triangle is unknown, so every quad counts as triangle 0 and the stable
  // sort keeps the trace's order among quads of one position.
  std::vector<QuadPlace> places(trace.requests.size() / 4);
  for (size_t q = 0; q < places.size(); ++q) places[q] = {0, trace.requests[q * 4].x, trace.requests[q * 4].y};
  const std::vector<size_t> seq = raster_sequence(order, places);
  Trace out = trace;
  for (size_t i = 0; i < seq.size(); ++i)
    std::copy_n(trace.requests.begin() + static_cast<ptrdiff_t>(seq[i] * 4), 4, out.requests.begin() + static_cast<ptrdiff_t>(i * 4));
  return out;
}

int32_t request_lambda(const Trace& tr, size_t i, int width, int height) {
  const TraceRequest& r = tr.requests[i];
  switch (tr.mode) {
    case TraceMode::Lod: return lambda_explicit(r.lod);
    case TraceMode::Grad: return lambda_from_gradients(r.dsdx, r.dtdx, r.dsdy, r.dtdy, width, height);
    case TraceMode::Quad: {
      const float s[4] = {r.s, tr.requests[i + 1].s, tr.requests[i + 2].s, tr.requests[i + 3].s};
      const float t[4] = {r.t, tr.requests[i + 1].t, tr.requests[i + 2].t, tr.requests[i + 3].t};
      return lambda_from_quad(s, t, width, height);
    }
  }
  return 0;
}

std::optional<TexelDerivatives> request_derivatives(const Trace& tr, size_t i, int width, int height) {
  const TraceRequest& r = tr.requests[i];
  switch (tr.mode) {
    case TraceMode::Lod: return std::nullopt;
    case TraceMode::Grad: return derivatives_from_gradients(r.dsdx, r.dtdx, r.dsdy, r.dtdy, width, height);
    case TraceMode::Quad: {
      const float s[4] = {r.s, tr.requests[i + 1].s, tr.requests[i + 2].s, tr.requests[i + 3].s};
      const float t[4] = {r.t, tr.requests[i + 1].t, tr.requests[i + 2].t, tr.requests[i + 3].t};
      return derivatives_from_quad(s, t, width, height);
    }
  }
  return std::nullopt;
}

AnisoLod request_lod(const Trace& tr, size_t i, int width, int height, const AnisoParams& p) {
  const std::optional<TexelDerivatives> d = request_derivatives(tr, i, width, height);
  return d ? aniso_lod(*d, p) : isotropic_lod(lambda_explicit(tr.requests[i].lod));
}

std::vector<int32_t> trace_lambdas(const Trace& tr, const std::function<std::pair<int, int>(int)>& extent) {
  std::vector<int32_t> lam(tr.requests.size());
  for (size_t i = 0; i < tr.requests.size(); ++i) {
    if (tr.mode == TraceMode::Quad && i % 4 != 0) {
      lam[i] = lam[i - i % 4];  // one lambda per quad
      continue;
    }
    const auto [w, h] = extent(tr.requests[i].texture);
    lam[i] = request_lambda(tr, i, w, h);
  }
  return lam;
}

std::vector<int32_t> trace_lambdas(const Trace& tr, int width, int height) {
  return trace_lambdas(tr, [width, height](int) { return std::pair{width, height}; });
}

}  // namespace tfu
