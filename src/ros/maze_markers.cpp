#include "maze_markers.h"

#include <cstdio>
#include <map>
#include <tuple>
#include <vector>

namespace marble_maze_ros {

std_msgs::ColorRGBA colour(float r, float g, float b, float a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

visualization_msgs::Marker lockedMarker(const std::string& frame, const std::string& ns, int id,
                                        int type) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.frame_locked = true;
  return m;
}

namespace {

using marble_maze::Box;
using marble_maze::Index3;
using marble_maze::Maze;
using marble_maze::Vec3;

/// Boxes of one kind, grouped by size, because a CUBE_LIST has one scale for all its cubes.
class CubeLists {
 public:
  CubeLists(std::string ns, std_msgs::ColorRGBA colour) : ns_(std::move(ns)), colour_(colour) {}

  void add(const Vec3& centre, const Vec3& size) {
    // Sizes come from a few slot widths; rounding to 0.1 um keys them exactly.
    const auto key = std::make_tuple(std::llround(size.x() * 1e7), std::llround(size.y() * 1e7),
                                     std::llround(size.z() * 1e7));
    auto& list = lists_[key];
    list.size = size;
    geometry_msgs::Point p;
    p.x = centre.x();
    p.y = centre.y();
    p.z = centre.z();
    list.points.push_back(p);
  }

  void appendTo(const std::string& frame, visualization_msgs::MarkerArray* array) const {
    int id = 0;  // sizes in sorted order: the same maze gives the same ids
    for (const auto& entry : lists_) {
      visualization_msgs::Marker m =
          lockedMarker(frame, ns_, id++, visualization_msgs::Marker::CUBE_LIST);
      m.scale.x = entry.second.size.x();
      m.scale.y = entry.second.size.y();
      m.scale.z = entry.second.size.z();
      m.color = colour_;
      m.points = entry.second.points;
      array->markers.push_back(m);
    }
  }

 private:
  struct List {
    Vec3 size;
    std::vector<geometry_msgs::Point> points;
  };
  std::string ns_;
  std_msgs::ColorRGBA colour_;
  std::map<std::tuple<long long, long long, long long>, List> lists_;
};

/// A thin square on the floor's top surface over column (i, j), in the board frame.
void addFloorPatch(const Maze& maze, int i, int j, double lift, CubeLists* lists) {
  const Box box = maze.tileBox(Index3(i, j, 0));
  const double thickness = 0.0005;
  const Vec3 centre(box.centre().x(), box.centre().y(), maze.floorTop() + lift - thickness / 2);
  lists->add(centre - maze.pivot(), Vec3(box.size().x(), box.size().y(), thickness));
}

}  // namespace

visualization_msgs::MarkerArray mazeMarkers(const Maze& maze, const std::string& board_frame) {
  CubeLists floor("floor", colour(0.85f, 0.70f, 0.48f));
  CubeLists walls("walls", colour(0.55f, 0.36f, 0.20f));
  // Holes are dark but not opaque, so that a marble that fell in still shows through.
  CubeLists holes("holes", colour(0.02f, 0.02f, 0.02f, 0.6f));
  CubeLists start("start", colour(0.20f, 0.45f, 0.95f, 0.8f));
  CubeLists goal("goal", colour(0.10f, 0.80f, 0.25f, 0.8f));
  for (int k = 0; k < maze.size().z(); ++k)
    for (int j = 0; j < maze.size().y(); ++j)
      for (int i = 0; i < maze.size().x(); ++i) {
        const Index3 t(i, j, k);
        if (!maze.solid(t)) continue;
        const Box box = maze.tileBox(t);
        (k == 0 ? floor : walls).add(box.centre() - maze.pivot(), box.size());
      }
  // Holes, start and goal are drawn as patches just above or below the floor's surface.
  for (const Maze::Cell& c : maze.holes()) addFloorPatch(maze, c.i, c.j, -0.0002, &holes);
  addFloorPatch(maze, maze.start().i, maze.start().j, 0.0003, &start);
  for (const Maze::Cell& c : maze.goals()) addFloorPatch(maze, c.i, c.j, 0.0003, &goal);
  visualization_msgs::MarkerArray array;
  for (const CubeLists* lists : {&floor, &walls, &holes, &start, &goal})
    lists->appendTo(board_frame, &array);
  return array;
}

visualization_msgs::Marker marbleMarker(double radius, const std::string& marble_frame) {
  visualization_msgs::Marker m =
      lockedMarker(marble_frame, "marble", 0, visualization_msgs::Marker::SPHERE);
  m.scale.x = m.scale.y = m.scale.z = 2 * radius;
  m.color = colour(1.0f, 0.35f, 0.10f);
  return m;
}

visualization_msgs::MarkerArray liveMarkers(const Maze& maze, const std::vector<Vec3>& trail,
                                            double radius, double roll, double pitch,
                                            const std::string& board_frame) {
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker line =
      lockedMarker(board_frame, "marble_trail", 0, visualization_msgs::Marker::LINE_STRIP);
  if (trail.size() < 2) line.action = visualization_msgs::Marker::DELETE;
  line.scale.x = 0.5 * radius;  // the line's width
  line.color = colour(1.0f, 0.55f, 0.15f, 0.7f);
  for (const Vec3& p : trail) {
    geometry_msgs::Point point;
    point.x = p.x();
    point.y = p.y();
    point.z = p.z() - 0.8 * radius;  // low on the marble, so that the marble stands on its path
    line.points.push_back(point);
  }
  array.markers.push_back(line);

  // The board's normal, beside the middle of its near (-y) edge: it leans as the board tilts.
  const Vec3 corner(0, -maze.extent().y() / 2 - 0.025, 0);
  visualization_msgs::Marker arrow =
      lockedMarker(board_frame, "tilt", 0, visualization_msgs::Marker::ARROW);
  geometry_msgs::Point base, tip;
  base.x = tip.x = corner.x();
  base.y = tip.y = corner.y();
  tip.z = 0.06;
  arrow.points = {base, tip};
  arrow.scale.x = 0.004;  // shaft diameter
  arrow.scale.y = 0.008;  // head diameter
  arrow.scale.z = 0.012;  // head length
  arrow.color = colour(0.3f, 0.8f, 1.0f);
  array.markers.push_back(arrow);

  visualization_msgs::Marker text = arrow;
  text.id = 1;
  text.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
  text.points.clear();
  text.pose.position.x = corner.x();
  text.pose.position.y = corner.y();
  text.pose.position.z = 0.075;
  text.scale.x = text.scale.y = 0;
  text.scale.z = 0.012;  // the letters' height
  text.color = colour(0.9f, 0.95f, 1.0f);
  char words[64];
  const double degrees = 180 / 3.14159265358979323846;
  std::snprintf(words, sizeof words, "roll %+.1f°  pitch %+.1f°", roll * degrees, pitch * degrees);
  text.text = words;
  array.markers.push_back(text);
  return array;
}

}  // namespace marble_maze_ros
