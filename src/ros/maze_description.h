// The `maze` topic's message from a scene, and a scene's maze back from the message: how a
// planner or an agent reads the maze without its file.
#pragma once

#include <string>

#include "marble_maze/MazeDescription.h"
#include "marble_maze/maze_file.h"

namespace marble_maze_ros {

marble_maze::MazeDescription describe(const marble_maze::Scene& scene,
                                      const std::string& board_frame);

/// The maze (and the physics the message carries) back; throws std::runtime_error naming the
/// field when the message does not describe a maze (sizes that disagree, cells off the grid).
marble_maze::Scene sceneOf(const marble_maze::MazeDescription& msg);

}  // namespace marble_maze_ros
