#include "cmodel/json_input.hpp"

#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/json_output.hpp"

namespace tfu {
namespace {

using nlohmann::json;

// nlohmann's message without its "[json.exception...] parse error at line L, column C: " prefix.
std::string strip_prefix(const std::string& what) {
  const auto bracket = what.find("] ");
  std::string msg = bracket == std::string::npos ? what : what.substr(bracket + 2);
  const auto col = msg.find("column ");
  if (msg.rfind("parse error", 0) == 0 && col != std::string::npos) {
    const auto colon = msg.find(": ", col);
    if (colon != std::string::npos) msg = msg.substr(colon + 2);
  }
  return one_line(msg, 160);
}

// "line L, column C" of a 1-based byte offset (the parser's position after the last byte read).
std::string line_column(const std::string& text, size_t position) {
  const size_t end = std::min(position > 0 ? position - 1 : 0, text.size());
  const auto stop = text.begin() + static_cast<std::ptrdiff_t>(end);
  const size_t line = 1 + static_cast<size_t>(std::count(text.begin(), stop, '\n'));
  const size_t nl = end == 0 ? std::string::npos : text.rfind('\n', end - 1);
  const size_t column = nl == std::string::npos ? end + 1 : end - nl;
  return fmt::format("line {}, column {}", line, column);
}

// The DOM builder of nlohmann::json plus the key path of the value being parsed and a depth limit.
class PathSax {
 public:
  PathSax(json& root, const std::string& text, const std::string& source)
      : dom_(root, true), text_(text), source_(source) {}

  bool null() { return value() && dom_.null(); }
  bool boolean(bool v) { return value() && dom_.boolean(v); }
  bool number_integer(json::number_integer_t v) { return value() && dom_.number_integer(v); }
  bool number_unsigned(json::number_unsigned_t v) { return value() && dom_.number_unsigned(v); }
  bool number_float(json::number_float_t v, const json::string_t& s) { return value() && dom_.number_float(v, s); }
  bool string(json::string_t& v) { return value() && dom_.string(v); }
  bool binary(json::binary_t& v) { return value() && dom_.binary(v); }
  bool start_object(std::size_t n) { return open(false) && dom_.start_object(n); }
  bool key(json::string_t& k) {
    frames_.back().key = k;
    return dom_.key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return dom_.end_object();
  }
  bool start_array(std::size_t n) { return open(true) && dom_.start_array(n); }
  bool end_array() {
    frames_.pop_back();
    return dom_.end_array();
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& /*last_token*/, const Exception& ex) {
    // id 101..199: the text is not JSON; others (406: a number out of the range of double) are values.
    const bool syntax = ex.id >= 101 && ex.id < 200;
    fail(position, (syntax ? "malformed JSON: " : "") + strip_prefix(ex.what()));
    return false;  // not reached: fail() throws
  }

 private:
  struct Frame {
    bool array = false;
    std::string key;
    long index = -1;
  };

  // Every value advances the index of the array it is in.
  bool value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  bool open(bool array) {
    value();
    if (frames_.size() >= static_cast<size_t>(kMaxJsonDepth))
      throw InputError(fmt::format("{}: nested deeper than {} levels", source_, kMaxJsonDepth));
    frames_.push_back({array, {}, -1});
    return true;
  }
  // The key path of the value being parsed. At an error the innermost array's current element is
  // the one after the last complete value (the failing value never reached value()).
  std::string path() const {
    std::string p;
    for (size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      if (f.array) {
        const long index = i + 1 == frames_.size() ? f.index + 1 : f.index;
        if (index >= 0) p += fmt::format("[{}]", index);
      } else if (!f.key.empty()) {
        p += (p.empty() ? "" : ".") + quote_input(f.key, 40);
      }
    }
    return p;
  }
  [[noreturn]] void fail(std::size_t position, const std::string& msg) const {
    const std::string at = path();
    const std::string where = position > 0 ? ": " + line_column(text_, position) : std::string();
    throw InputError(fmt::format("{}{}: {}{}", source_, where, at.empty() ? "" : "at " + at + ": ", msg));
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  const std::string& text_;
  const std::string& source_;
  std::vector<Frame> frames_;
};

}  // namespace

json parse_json_input(const std::string& text, const std::string& source) {
  json root;
  PathSax sax(root, text, source);
  json::sax_parse(text, &sax);
  return root;
}

std::string json_number_text(const json& v) { return quote_input(json_dump(v), 40); }

}  // namespace tfu
