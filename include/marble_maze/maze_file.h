// Loading a scene (a maze and its physics) from a YAML maze file or from the mazes built in.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "marble_maze/maze.h"
#include "marble_maze/params.h"

namespace marble_maze {

/// A maze and the physics it needs: the maze file's `physics:` section applied over defaults.
struct Scene {
  Scene() = default;
  /// A scene built in code: no file answers for it.
  Scene(Maze maze, Params params) : maze(std::move(maze)), params(std::move(params)) {}

  Maze maze;
  Params params;
  std::string text;    ///< the maze file's text it was read from ("" when built in code)
  std::string source;  ///< where the text came from: a path or "<embedded:NAME>"
  /// A parameter the file's physics section sets, and where its value is (1-based).
  struct FileKey {
    std::string key;
    int line = 0;
    int column = 0;
  };
  /// The parameters the file's physics section sets, in its order (the rest are defaults), less
  /// those set over it since (overrideParam).
  std::vector<FileKey> physics_keys;
  /// Where the file marks the start ('S'): "SOURCE:LINE:COLUMN" ("" when built in code), for an
  /// error about the start cell.
  std::string start_in_file;
};

/// Sets one parameter of the scene over what its file says (setParam; ParamError naming the key):
/// the file then no longer answers for it, and an error about the value names the key alone.
void overrideParam(Scene* scene, const std::string& key, const std::string& value);

/// Replaces the scene's parameters wholesale (a recording's): the file answers for none of them.
void replaceParams(Scene* scene, const Params& params);

/// Where the scene's file sets the key, or nullptr when it does not (or it was set over since).
const Scene::FileKey* findFileKey(const Scene& scene, const std::string& key);

/// A malformed maze file. what() reads "SOURCE:LINE:COLUMN: message" (1-based line and column).
struct MazeFileError : std::runtime_error {
  MazeFileError(const std::string& source, int line, int column, const std::string& message);
  std::string source;
  int line;
  int column;
};

/// Parses maze-file text. `source` names it in error messages (a path or "<embedded:NAME>").
Scene parseScene(const std::string& text, const std::string& source,
                 const Params& defaults = Params());

/// Reads and parses a maze file; an unreadable file is a MazeFileError at line 0.
Scene loadSceneFile(const std::string& path, const Params& defaults = Params());

/// The names of the mazes built into the program ("classic" first: the default).
std::vector<std::string> embeddedSceneNames();
/// The same as messages list them: "classic, brio, prototype".
std::string embeddedSceneList();

/// A built-in maze by name, or a file when `name_or_path` names no built-in maze.
Scene loadScene(const std::string& name_or_path, const Params& defaults = Params());

}  // namespace marble_maze
