// The maze and the marble as RViz markers: a translation of the core's maze, no physics.
#pragma once

#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>

#include "marble_maze/maze.h"

namespace marble_maze_ros {

/// The maze in the board frame: one CUBE_LIST per kind of tile (floor, walls, holes, start,
/// goal) and tile size, each in its kind's namespace with a stable id, frame-locked so that RViz
/// moves it with the board's tf.
visualization_msgs::MarkerArray mazeMarkers(const marble_maze::Maze& maze,
                                            const std::string& board_frame);

/// The marble: a steel-grey sphere at the origin of its own frame, frame-locked.
visualization_msgs::Marker marbleMarker(double radius, const std::string& marble_frame);

}  // namespace marble_maze_ros
