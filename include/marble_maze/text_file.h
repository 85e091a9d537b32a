// Reading a text file that a user names (a maze, a tilt programme), bounded: a wrong path to a
// device or a huge file is refused with a message instead of being read without end.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace marble_maze {

/// The most a maze file or a tilt programme may hold: far above a 1000 x 1000 cell maze (4 MB).
constexpr std::size_t kMostTextFileBytes = 16u << 20;

/// A file that cannot be read as text: what() reads "PATH: reason".
struct TextFileError : std::runtime_error {
  TextFileError(const std::string& path, const std::string& reason)
      : std::runtime_error(path + ": " + reason), reason(reason) {}
  std::string reason;  ///< without the path
};

/// The whole of the file at `path`; throws TextFileError when it cannot be read, is a directory,
/// or holds more than `most_bytes`.
std::string readTextFile(const std::string& path, std::size_t most_bytes = kMostTextFileBytes);

}  // namespace marble_maze
