// The maze and the marble as RViz markers: a translation of the core's maze, no physics.
#pragma once

#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "marble_maze/maze.h"

namespace marble_maze_ros {

/// A colour from its red, green, blue and opacity, each 0 to 1.
std_msgs::ColorRGBA colour(float r, float g, float b, float a = 1.0f);

/// A marker to add in `frame` (identity pose), frame-locked so that RViz moves it with the
/// frame's tf; `ns` and `id` name it, `type` is one of visualization_msgs::Marker's.
visualization_msgs::Marker lockedMarker(const std::string& frame, const std::string& ns, int id,
                                        int type);

/// The maze in the board frame: one CUBE_LIST per kind of tile (floor, walls, holes, start,
/// goal) and tile size, each in its kind's namespace with a stable id, frame-locked so that RViz
/// moves it with the board's tf.
visualization_msgs::MarkerArray mazeMarkers(const marble_maze::Maze& maze,
                                            const std::string& board_frame);

/// The marble: a bright sphere at the origin of its own frame, frame-locked (the eye should find
/// it first: the real one is steel, but a 12 mm steel ball is lost on a screen).
visualization_msgs::Marker marbleMarker(double radius, const std::string& marble_frame);

/// What changes as the game goes on: the marble's recent path (`trail`, board-frame positions,
/// oldest first, drawn as a line on the board), and the board's tilt as an arrow along the
/// board's normal beside the middle of its near (-y) edge, with the angles written above it.
visualization_msgs::MarkerArray liveMarkers(const marble_maze::Maze& maze,
                                            const std::vector<marble_maze::Vec3>& trail,
                                            double radius, double roll, double pitch,
                                            const std::string& board_frame);

}  // namespace marble_maze_ros
