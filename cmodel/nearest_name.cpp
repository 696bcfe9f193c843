#include "cmodel/nearest_name.hpp"

#include <algorithm>
#include <cctype>

#include "cmodel/error.hpp"

namespace tfu {

namespace {

// Lower case, '_' as '-', leading dashes dropped; at most 64 characters are compared (a longer
// input is no typo of a name, and the distance stays cheap for hostile inputs).
std::string normalised(std::string_view s) {
  while (!s.empty() && s.front() == '-') s.remove_prefix(1);
  std::string out;
  for (char c : s.substr(0, 64)) out += c == '_' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> out;
  size_t b = 0;
  while (b <= s.size()) {
    const size_t e = std::min(s.find('-', b), s.size());
    if (e - b >= 3) out.push_back(s.substr(b, e - b));
    b = e + 1;
  }
  return out;
}

int osa_distance(const std::string& a, const std::string& b) {
  const size_t n = a.size(), m = b.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1));
  for (size_t i = 0; i <= n; ++i) d[i][0] = static_cast<int>(i);
  for (size_t j = 0; j <= m; ++j) d[0][j] = static_cast<int>(j);
  for (size_t i = 1; i <= n; ++i)
    for (size_t j = 1; j <= m; ++j) {
      const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

}  // namespace

int name_distance(std::string_view a, std::string_view b) { return osa_distance(normalised(a), normalised(b)); }

std::optional<std::string> nearest_name(std::string_view input, const std::vector<std::string>& candidates) {
  const std::string in = normalised(input);
  if (in.empty()) return std::nullopt;
  const std::vector<std::string> in_words = words(in);
  std::optional<std::string> best;
  int best_d = 0;
  for (const std::string& c : candidates) {
    const std::string cn = normalised(c);
    if (c == input) return std::nullopt;  // the input is valid: nothing to suggest
    const int d = osa_distance(in, cn);
    const int limit = std::max<int>(1, static_cast<int>(std::min(in.size(), cn.size()) / 3));
    bool near = d <= limit || (in.size() >= 3 && cn.rfind(in, 0) == 0);
    for (const std::string& w : words(cn))
      near = near || std::find(in_words.begin(), in_words.end(), w) != in_words.end();
    if (near && (!best || d < best_d)) {
      best = c;
      best_d = d;
    }
  }
  return best;
}

std::string did_you_mean(std::string_view input, const std::vector<std::string>& candidates) {
  const std::optional<std::string> n = nearest_name(input, candidates);
  return n ? "did you mean '" + quote_input(*n) + "'? " : std::string();
}

}  // namespace tfu
