#include "maze_description.h"

#include <stdexcept>

namespace marble_maze_ros {
namespace mm = marble_maze;

namespace {

marble_maze::MazeCell cellMsg(const mm::Maze::Cell& c) {
  marble_maze::MazeCell msg;
  msg.i = c.i;
  msg.j = c.j;
  return msg;
}

mm::Maze::Cell cellOf(const marble_maze::MazeCell& msg, const mm::Maze& maze,
                      const std::string& field) {
  if (msg.i < 0 || msg.j < 0 || msg.i >= maze.size().x() || msg.j >= maze.size().y())
    throw std::runtime_error("maze: " + field + " (" + std::to_string(msg.i) + ", " +
                             std::to_string(msg.j) + ") is off the grid");
  return {msg.i, msg.j};
}

}  // namespace

marble_maze::MazeDescription describe(const mm::Scene& scene, const std::string& board_frame) {
  const mm::Maze& maze = scene.maze;
  const mm::Params& p = scene.params;
  marble_maze::MazeDescription msg;
  msg.header.frame_id = board_frame;
  msg.name = maze.name();
  for (int a = 0; a < 3; ++a) {
    msg.thin_width[a] = maze.axis(a).thin();
    msg.wide_width[a] = maze.axis(a).wide();
    msg.slots[a] = maze.axis(a).count();
  }
  const mm::Index3& n = maze.size();
  msg.solid.resize(static_cast<std::size_t>(n.x()) * n.y() * n.z());
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i)
        msg.solid[static_cast<std::size_t>(i) + n.x() * (j + static_cast<std::size_t>(n.y()) * k)] =
            maze.solid({i, j, k}) ? 1 : 0;
  msg.pivot.x = maze.pivot().x();
  msg.pivot.y = maze.pivot().y();
  msg.pivot.z = maze.pivot().z();
  msg.start = cellMsg(maze.start());
  for (const auto& g : maze.goals()) msg.goals.push_back(cellMsg(g));
  for (const auto& h : maze.holes()) msg.holes.push_back(cellMsg(h));
  msg.model = mm::getParam(p, "model");
  msg.marble_radius = p.marble_radius;
  msg.gravity = p.gravity;
  msg.restitution = p.restitution;
  msg.friction = p.friction;
  msg.tilt_limit = p.tilt_limit;
  msg.tilt_rate_limit = p.tilt_rate_limit;
  msg.tilt_response_time = p.tilt_response_time;
  return msg;
}

mm::Scene sceneOf(const marble_maze::MazeDescription& msg) {
  for (int a = 0; a < 3; ++a)
    if (!(msg.thin_width[a] > 0) || !(msg.wide_width[a] > 0) || msg.slots[a] < 1)
      throw std::runtime_error("maze: axis " + std::to_string(a) +
                               " needs positive widths and at least one slot");
  mm::Scene scene;
  mm::Maze maze(mm::AxisSlots(msg.thin_width[0], msg.wide_width[0], msg.slots[0]),
                mm::AxisSlots(msg.thin_width[1], msg.wide_width[1], msg.slots[1]),
                mm::AxisSlots(msg.thin_width[2], msg.wide_width[2], msg.slots[2]));
  const mm::Index3& n = maze.size();
  if (msg.solid.size() != static_cast<std::size_t>(n.x()) * n.y() * n.z())
    throw std::runtime_error("maze: solid has " + std::to_string(msg.solid.size()) +
                             " tiles, the slots make " +
                             std::to_string(static_cast<long>(n.x()) * n.y() * n.z()));
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i)
        maze.setSolid({i, j, k}, msg.solid[static_cast<std::size_t>(i) +
                                           n.x() * (j + static_cast<std::size_t>(n.y()) * k)] != 0);
  maze.setName(msg.name);
  maze.setStart(cellOf(msg.start, maze, "start"));
  for (const auto& g : msg.goals) maze.addGoal(cellOf(g, maze, "goal"));
  scene.maze = maze;
  mm::setParam(scene.params, "model", msg.model);
  scene.params.marble_radius = msg.marble_radius;
  scene.params.gravity = msg.gravity;
  scene.params.restitution = msg.restitution;
  scene.params.friction = msg.friction;
  scene.params.tilt_limit = msg.tilt_limit;
  scene.params.tilt_rate_limit = msg.tilt_rate_limit;
  scene.params.tilt_response_time = msg.tilt_response_time;
  return scene;
}

}  // namespace marble_maze_ros
