#include "cmodel/error.hpp"

namespace tfu {
namespace {

bool is_control(char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }

// Cuts `s` to at most `max_chars` characters, the last three being "..." when it is cut. A cut never
// splits a UTF-8 sequence (continuation bytes 10xxxxxx are dropped with their lead byte).
std::string cut(std::string s, size_t max_chars) {
  if (s.size() <= max_chars) return s;
  size_t keep = max_chars >= 3 ? max_chars - 3 : 0;
  while (keep > 0 && (static_cast<unsigned char>(s[keep]) & 0xC0) == 0x80) --keep;
  s.resize(keep);
  return s + "...";
}

}  // namespace

bool has_control_characters(std::string_view text) {
  for (const char c : text)
    if (is_control(c)) return true;
  return false;
}

std::string quote_input(std::string_view text, size_t max_chars) {
  std::string s(text.substr(0, max_chars + 4));  // enough to know whether it is cut
  for (char& c : s)
    if (is_control(c)) c = '?';
  return cut(std::move(s), max_chars);
}

std::string quote_path(std::string_view path) {
  if (path.size() <= kMaxQuotedPathChars) return quote_input(path, kMaxQuotedPathChars);
  constexpr size_t head = 30, tail = kMaxQuotedPathChars - head - 3;
  std::string s = quote_input(path.substr(0, head), head) + "..." + quote_input(path.substr(path.size() - tail), tail);
  // Do not start the tail inside a UTF-8 sequence.
  size_t t = head + 3;
  while (t < s.size() && (static_cast<unsigned char>(s[t]) & 0xC0) == 0x80) s.erase(t, 1);
  return s;
}

std::string one_line(std::string_view message, size_t max_chars) {
  std::string s(message.substr(0, max_chars + 4));
  for (char& c : s)
    if (is_control(c)) c = ' ';
  return cut(std::move(s), max_chars);
}

}  // namespace tfu
