// Small scenes built in code for the physics tests.
#pragma once

#include <cstdlib>
#include <string>

#include "marble_maze/maze_file.h"

namespace marble_maze {
namespace test {

constexpr double kPi = 3.14159265358979323846;

/// A grid with the given slots, the floor slab (layer 0) solid everywhere, nothing else.
inline Maze floorMaze(const AxisSlots& x, const AxisSlots& y, const AxisSlots& z) {
  Maze maze(x, y, z);
  for (int j = 0; j < y.count(); ++j)
    for (int i = 0; i < x.count(); ++i) maze.setSolid({i, j, 0}, true);
  maze.setStart({x.count() / 2, y.count() / 2});
  maze.setName("test");
  return maze;
}

/// A flat floor of uniform square tiles, one layer deep.
inline Scene flatFloor(int nx, int ny, double tile, const Params& params = Params()) {
  return {floorMaze(AxisSlots::uniform(tile, nx), AxisSlots::uniform(tile, ny),
                    AxisSlots::uniform(0.005, 2)),
          params};
}

/// The classic maze with its holes filled and no goal: a marble plays in it as long as a test
/// likes.
inline Maze closedClassic() {
  const Maze classic = loadScene("classic").maze;
  Maze maze(classic.axis(0), classic.axis(1), classic.axis(2));
  for (int k = 0; k < classic.size().z(); ++k)
    for (int j = 0; j < classic.size().y(); ++j)
      for (int i = 0; i < classic.size().x(); ++i)
        maze.setSolid({i, j, k}, classic.solid({i, j, k}) || k == 0);
  maze.setStart(classic.start());
  return maze;
}

/// An N x N cell maze of the classic game's proportions: outer walls, inner walls from a hash
/// of each wall's position relative to the centre, and a closed 4 x 4 cell room in the middle
/// where the marble runs. The room and its surroundings are the same in every size, so the
/// marble's path is too: only the size of the maze differs between the cases. Without `walls`
/// it is an open floor inside the outer walls.
inline Maze generatedMaze(int cells, bool walls = true) {
  const int n = 2 * cells + 1;
  const AxisSlots x(0.005, 0.0221, n), y(0.005, 0.02325, n), z(0.005, 0.012, 2);
  Maze maze(x, y, z);
  const int c = cells / 2 * 2 + 1;  // an odd (cell) slot near the centre
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      maze.setSolid({i, j, 0}, true);
      const bool post = i % 2 == 0 && j % 2 == 0;
      const bool wall_slot = (i % 2 == 0) != (j % 2 == 0);
      const bool outer = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      const unsigned hash = static_cast<unsigned>(i - c) * 73856093u ^
                            static_cast<unsigned>(j - c) * 19349663u;  // wraps, as unsigned may
      const bool room_wall = (std::abs(i - c) == 5 && std::abs(j - c) <= 5) ||
                             (std::abs(j - c) == 5 && std::abs(i - c) <= 5);
      const bool inside_room = std::abs(i - c) < 5 && std::abs(j - c) < 5;
      const bool inner_wall = wall_slot && !inside_room && hash % 3 == 0;
      if (outer || (walls && (post || room_wall || inner_wall))) maze.setSolid({i, j, 1}, true);
    }
  maze.setStart({c, c});
  maze.setName(std::to_string(cells) + "x" + std::to_string(cells));
  return maze;
}

/// Params of a scheme: integrator, model, step and restitution.
inline Params scheme(IntegratorKind integrator, Model model, double step,
                     double restitution = 0.7) {
  Params p;
  p.integrator = integrator;
  p.model = model;
  p.step = step;
  p.restitution = restitution;
  return p;
}

/// "velocity_verlet rolling step 0.001": which scheme a failure is of.
inline std::string name(const Params& p) {
  return getParam(p, "integrator") + " " + getParam(p, "model") + " step " + getParam(p, "step");
}

/// Params for a marble placed by hand (board frame) at rest.
inline Params placed(Params p, const Vec3& position, const Vec3& velocity = Vec3::Zero()) {
  p.has_start_position = true;
  p.start_position = position;
  p.start_velocity = velocity;
  return p;
}

/// Gravity-free flight at 50 m/s, 1 m above a floor, under quadratic drag (C_d = 0.47).
inline Params dragFlight(const Params& p) {
  Params flight = placed(p, {0, 0, 1.0}, {50, 0, 0});
  flight.gravity = 0;
  flight.drag_coefficient = 0.47;
  return flight;
}

/// Its speed after time t in closed form: v0 / (1 + k v0 t), with k = rho C_d A / (2 m).
inline double dragFlightSpeed(const Params& p, double t) {
  const double area = kPi * p.marble_radius * p.marble_radius;
  const double k = p.air_density * p.drag_coefficient * area / (2 * p.marbleMass());
  return 50 / (1 + k * 50 * t);
}

}  // namespace test
}  // namespace marble_maze
