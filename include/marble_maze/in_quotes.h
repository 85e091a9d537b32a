// A user's text quoted in a message about it (a value, a key, a line of a file), bounded: a file
// that is no maze, named to the node's load_maze service, would otherwise come back whole in the
// error, and a line of kilobytes says no more than its start.
#pragma once

#include <cstddef>
#include <string>

namespace marble_maze {

/// The most characters of a text that inQuotes() shows.
constexpr std::size_t kMostQuotedCharacters = 60;

/// `text` in single quotes: at most kMostQuotedCharacters characters of it (a UTF-8 sequence
/// whole or not at all), control characters as escapes (\n, \t, \r, \xHH), and when it is
/// longer, "..." and its length in bytes: 'root:x:0:0:root:/root:/bin/bash\ndaemon:x:1:1:...'
/// (1,234 bytes).
std::string inQuotes(const std::string& text);

}  // namespace marble_maze
