// Collision detection between the marble (a sphere) and the tile grid: the seed's five steps,
// plus contact normals and depths, seams that never act as edges, and a swept test for impacts
// on the way (no tunnelling).
#pragma once

#include <cstdint>
#include <vector>

#include "marble_maze/geometry.h"
#include "marble_maze/maze.h"

namespace marble_maze {

/// Where the tile grid is in the world at one instant: its basis [e_x' e_y' e_z'] and where the
/// point it turns about, which stays at the world's origin, lies in the grid.
///
/// Eq. (4) is taken about that point rather than about the grid's corner O': the rotation then
/// acts on the offset from the pivot, small where the marble plays, not on the offset from the
/// corner, which grows with the maze. A coordinate across the floor of a large maze rounds no
/// worse than it must, and the height above the floor carries no rounding that grows with the
/// maze's size (a marble resting on the floor of a 300 x 300 cell maze used to sit a rounding
/// error of its rotated 4 m offset below the floor's top, meet the floor again every step, and
/// sweep seven times the tiles of a smaller maze).
struct GridFrame {
  Mat3 rotation = Mat3::Identity();  ///< columns are e_x', e_y', e_z' in the world
  Vec3 grid_pivot = Vec3::Zero();    ///< the pivot (at the world's origin) in grid coordinates
  Vec3 angular_velocity = Vec3::Zero();

  /// Eq. (4): v_P' = [e_x' e_y' e_z']^-1 (v_P - v_O'); the basis is orthonormal, so ^-1 = ^T.
  Vec3 toGrid(const Vec3& world) const { return toBoard(world) + grid_pivot; }
  Vec3 toWorld(const Vec3& grid) const { return fromBoard(grid - grid_pivot); }
  /// Board coordinates: the grid's axes, from the pivot.
  Vec3 toBoard(const Vec3& world) const { return rotation.transpose() * world; }
  Vec3 fromBoard(const Vec3& board) const { return rotation * board; }
  /// Velocity of the board's material point at a world position: w x (p - pivot).
  Vec3 surfaceVelocity(const Vec3& world) const { return cross(angular_velocity, world); }
};

/// The marble touching one tile.
struct Contact {
  /// (Provided, so that a contact made in place, as a vector's emplace_back() makes it, is not
  /// zeroed first: its vectors are all written before they are read, as when it is declared.)
  Contact() {}

  Vec3 normal;       ///< world, unit, from the tile towards the marble's centre
  Vec3 grid_normal;  ///< the same in the grid frame, where the tiles do not turn
  Vec3 grid_point;   ///< the tile's closest point, in the grid frame (where the sweep wants it)
  /// World, v_b of eq. (1): the board's velocity where the marble's surface meets the normal
  /// (at `grid_point` along the normal; across it, within |w| times the marble's depth into the
  /// tile or gap from it, at most the margin once pushed out). At an impact they are one point.
  Vec3 surface_velocity;
  double depth = 0;  ///< radius minus distance: > 0 when the marble overlaps the tile
  Index3 tile = Index3::Zero();
};

/// The solid tiles around the marble, kept from one contact query to the next while it stays
/// well inside where they were gathered: every solid tile within `reach` of `centre` along each
/// grid axis, in the grid's order. The query needs those within its contacts' reach (radius plus
/// margin) plus `skin`, what a short path could meet; when the marble has moved too far for that
/// it gathers them anew, `slack` farther, so that they last a few substeps. With them a sweep
/// shorter than the gap to the nearest is answered without walking the grid (Sweep::clearOf).
struct NearTiles {
  struct Tile {
    Box box;
    Index3 index;
  };
  double skin = 0;             ///< m, set by the caller for each query
  double slack = 0;            ///< m, set by the caller: gathered this much beyond the need
  double reach = -1;           ///< m, gathered this far from `centre` along each axis (< 0: none)
  Vec3 centre = Vec3::Zero();  ///< grid frame
  std::vector<Tile> tiles;     ///< solid, in contact or not
  /// Where each layer of them (a z slot of the grid) begins in `tiles`, bottom up: they are
  /// gathered in the grid's order, layer by layer.
  std::vector<std::size_t> layers;
  /// Whether their lowest layer, tiles[0, bottom_end), fills its x-y rectangle, [lower, upper]
  /// (a floor, open or with walls on it): a centre above it and over the rectangle touches at
  /// most the top of that layer's tile under it, which the query then finds without looking at
  /// each of the layer's tiles (the layers above it are looked at tile by tile).
  bool full_bottom_layer = false;
  std::size_t bottom_end = 0;                            ///< where the lowest layer ends in tiles
  Vec3 lower = Vec3::Zero(), upper = Vec3::Zero();       ///< grid frame, its bounding box
  Index3 first = Index3::Zero(), last = Index3::Zero();  ///< its tiles' lowest and highest slots
  /// The one of its tiles under the centre of the last query the layer answered: the likeliest
  /// under the next (the query checks that it is).
  std::size_t under = 0;
  std::uint64_t gathers = 0;  ///< how often they were gathered from the grid
};

/// Every tile within radius + margin of the marble's centre, one contact per surface direction
/// (a floor of many tiles gives one contact). A tile adds no contact through a face it shares
/// with a solid neighbour: there the neighbour's own face is the surface, so seams never act as
/// edges. The cost depends on the marble's size, not on the maze's. With `near`, the tiles are
/// taken from it, gathered anew when they do not reach near->skin beyond the contacts' reach.
void findContacts(const Maze& maze, const GridFrame& frame, const Vec3& centre, double radius,
                  double margin, std::vector<Contact>* contacts, NearTiles* near = nullptr);

/// The marble's centre moving relative to the board over a stretch of time, in the grid frame:
/// centre(s) = from + path s + bend s^2 for s from 0 (the stretch's start) to 1 (its end). A
/// zero bend is a straight path; the integrators' parabolas bend.
struct Sweep {
  Vec3 from = Vec3::Zero();
  Vec3 path = Vec3::Zero();
  Vec3 bend = Vec3::Zero();
  double radius = 0;
  double margin = 0;  ///< tiles this close to the start are contacts, not impacts
  /// Across a tile it touches, a path slower than this (per unit s) rests on it: a path leaving
  /// faster may come back to it within the stretch, a small bounce.
  double resting_rate = 0;
  /// Planes the path keeps to: those of the contacts that hold the marble, which it neither
  /// leaves nor goes into over the stretch (n . x >= offset on its side). A tile wholly behind
  /// one can only be grazed, never met: the floor's other tiles under a rolling marble, a wall's
  /// under one that slides along it. At most three.
  int planes = 0;
  Vec3 plane_normal[3];
  double plane_offset[3] = {0, 0, 0};

  /// Keeps to the plane through `point` with the (unit) `normal`, when there is room for it.
  void keepTo(const Vec3& normal, const Vec3& point) {
    if (planes == 3) return;
    plane_normal[planes] = normal;
    plane_offset[planes++] = normal.dot(point);
  }
  Vec3 at(double s) const { return from + s * (path + s * bend); }
  Vec3 rate(double s) const { return path + 2 * s * bend; }  ///< d centre / ds
  /// True when the walk of the grid (timeOfImpact) would report no impact: the path stays where
  /// the near tiles were gathered, and each of them lies behind a plane it keeps to (as the walk
  /// judges it), farther from its start than the radius plus how far it strays (bounded by the
  /// sums of the sizes of path's and bend's components), or else is passed over by the walk's
  /// own tests before it seeks a root (a wall beside the path). False says nothing.
  bool clearOf(const NearTiles& near) const;
};

/// The first impact along a sweep.
struct SweepHit {
  double fraction = 1;  ///< s of the impact, 0..1
  Contact contact;      ///< at the moment of impact
  /// The solid tiles the walk looked at, hit or not: its cost, which must not grow with the maze.
  int tiles_visited = 0;
};

/// What a time of impact found (as Box2D's b2TOIOutput says why it found what it did).
enum class ImpactState {
  Hit,        ///< a tile met: the SweepHit says where and when
  Separated,  ///< the path walked, and no tile met while approaching it
  OffGrid,    ///< the path, grown by the radius, stays clear of the grid: nothing walked
  Still,      ///< no motion relative to the board: nothing to meet
  /// No tile met, and the path started inside a tile by more than the margin: the overlap is
  /// findContacts' to resolve (pushOut), not an impact's.
  Overlapped,
  /// The path is longer than a million radii: more pieces than a walk takes, nothing walked (a
  /// simulation's step never asks it: its speed is bounded to 1e5 radii a step).
  GaveUp,
};

/// Time of impact: the first tile the sweep hits while approaching it, or why none. Tiles within
/// radius + margin of the start are left to findContacts. The path is walked in pieces no longer
/// than the radius, so the cost grows with its length, never with the maze, and no wall is
/// skipped at any speed. On a bent path the time is a root of the quadratic (faces) or quartic
/// (rounded edges and corners) that the distance gives. The contact comes back in the world
/// through `frame`, the board's pose at the end of the stretch.
ImpactState timeOfImpact(const Maze& maze, const GridFrame& frame, const Sweep& sweep,
                         SweepHit* hit);

/// Time of impact (0..1) of a sphere moving from o by d against a box, both in one frame, when it
/// starts outside the box grown by the radius; `point` gets the touched point of the box.
bool sphereBoxImpact(const Vec3& o, const Vec3& d, double radius, const Box& box, double* time,
                     Vec3* point);

}  // namespace marble_maze
