// Error conventions shared by the model and its tools: the error kinds and exit codes
// (cmodel/error_kinds.hpp) and the helpers that quote the user's input in a one-line message.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "cmodel/error_kinds.hpp"

namespace tfu {

// A piece of the user's input for a message: control characters (newline, NUL, ...) as '?', cut to
// `max_chars` characters with "..." appended when longer. The caller adds the quotes.
std::string quote_input(std::string_view text, size_t max_chars = kMaxQuotedChars);

// A file path for a message: control characters as '?'; a path longer than kMaxQuotedPathChars
// keeps its start and its end (the file name) around "...". The caller adds the quotes.
inline constexpr size_t kMaxQuotedPathChars = 100;
std::string quote_path(std::string_view path);

// A name from an archive or a file (a pk3 entry, a BSP texture name, a trace binding) holds a
// control character (below 0x20, or 0x7f): such names are refused before they reach any output
// format, where a newline would start a line of its own (docs/inputs-outputs.md, "Names").
bool has_control_characters(std::string_view text);

// Any message as one line of at most `max_chars` characters: control characters become spaces
// (a newline too), and a longer message is cut with "..." at the end.
std::string one_line(std::string_view message, size_t max_chars = kMaxMessageChars);

}  // namespace tfu
