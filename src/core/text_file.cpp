#include "marble_maze/text_file.h"

#include <filesystem>
#include <fstream>

namespace marble_maze {

std::string readTextFile(const std::string& path, std::size_t most_bytes) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw TextFileError(path + ": is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw TextFileError(path + ": cannot read file");
  // One byte more than allowed tells a file that is too long without reading all of it (a
  // device such as /dev/zero has no end).
  std::string text(most_bytes + 1, '\0');
  in.read(&text[0], static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw TextFileError(path + ": cannot read file");
  if (static_cast<std::size_t>(in.gcount()) > most_bytes)
    throw TextFileError(path + ": more than " + std::to_string(most_bytes >> 20) +
                        " MB, more than a maze or a tilt programme can need");
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

}  // namespace marble_maze
