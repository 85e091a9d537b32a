#include "marble_maze/in_quotes.h"

#include <cstdio>

namespace marble_maze {

std::string inQuotes(const std::string& text) {
  std::string shown = "'";
  std::size_t at = 0, characters = 0;
  while (at < text.size() && characters < kMostQuotedCharacters) {
    const auto c = static_cast<unsigned char>(text[at]);
    // A UTF-8 sequence is its lead byte and the continuation bytes (10xxxxxx) after it.
    std::size_t end = at + 1;
    if (c >= 0x80)
      while (end < text.size() && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) ++end;
    if (c == '\n') {
      shown += "\\n";
    } else if (c == '\t') {
      shown += "\\t";
    } else if (c == '\r') {
      shown += "\\r";
    } else if (c < 0x20 || c == 0x7F) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\x%02X", c);
      shown += escape;
    } else {
      shown.append(text, at, end - at);
    }
    at = end;
    ++characters;
  }
  shown += "'";
  if (at < text.size()) {
    // (The length in bytes, grouped by thousands: what a user's editor or wc -c tells.)
    std::string size = std::to_string(text.size());
    for (int i = static_cast<int>(size.size()) - 3; i > 0; i -= 3) size.insert(i, ",");
    shown.insert(shown.size() - 1, "...");
    shown += " (" + size + " bytes)";
  }
  return shown;
}

}  // namespace marble_maze
