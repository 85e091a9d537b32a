// Small scenes built in code for the physics tests.
#pragma once

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
