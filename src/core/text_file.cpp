#include "marble_maze/text_file.h"

#include <filesystem>
#include <fstream>

namespace marble_maze {

std::string readTextFile(const std::string& path, std::size_t most_bytes) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw TextFileError(path, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw TextFileError(path, "cannot read file");
  // Read a piece at a time, and stop one byte past the bound: a device such as /dev/zero has no
  // end, and a file of the usual few kilobytes costs no more than its size.
  std::string text;
  char piece[1 << 16];
  while (in && text.size() <= most_bytes) {
    in.read(piece, sizeof piece);
    text.append(piece, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw TextFileError(path, "cannot read file");
  if (text.size() > most_bytes)
    throw TextFileError(path, "more than " + std::to_string(most_bytes >> 20) +
                                  " MB, more than a maze or a tilt programme can need");
  return text;
}

}  // namespace marble_maze
