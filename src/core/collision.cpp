#include "marble_maze/collision.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "marble_maze/polynomial.h"

namespace marble_maze {
namespace {

constexpr double kNone = std::numeric_limits<double>::infinity();
// Far above the rounding of a grid coordinate (some 1e-16 m), far below anything physical.
constexpr double kRoundingRoom = 1e-9;  // m

/// The tiles that a grid-frame box [lower, upper] can touch, clamped to the grid (seed step 2).
struct TileRange {
  Index3 first;
  Index3 last;
};

/// Whether a grid-frame box [lower, upper] reaches into the grid at all: a marble far above the
/// board (in flight) looks up no slot.
bool overlapsGrid(const Maze& maze, const Vec3& lower, const Vec3& upper) {
  const Vec3& extent = maze.extent();
  return (upper.array() >= 0).all() && (lower.array() <= extent.array()).all();
}

TileRange tileRange(const Maze& maze, const Vec3& lower, const Vec3& upper) {
  TileRange r;
  for (int a = 0; a < 3; ++a) {
    r.first[a] = std::max(0, maze.axis(a).slotAt(lower[a]));
    r.last[a] = std::min(maze.size()[a] - 1, maze.axis(a).slotAt(upper[a]));
  }
  return r;
}

template <typename Visit>
void forEachSolidTile(const Maze& maze, const TileRange& r, Visit visit) {
  for (int k = r.first.z(); k <= r.last.z(); ++k)
    for (int j = r.first.y(); j <= r.last.y(); ++j)
      for (int i = r.first.x(); i <= r.last.x(); ++i) {
        const Index3 t(i, j, k);
        if (maze.solid(t)) visit(t, maze.tileBox(t));
      }
}

/// Every solid tile within `reach` of grid point c along each axis, in the grid's order; none
/// when that cube misses the grid (a marble far above the board).
template <typename Visit>
void forEachSolidTileAround(const Maze& maze, const Vec3& c, double reach, Visit visit) {
  const Vec3 extent = Vec3::Constant(reach);
  if (overlapsGrid(maze, c - extent, c + extent))
    forEachSolidTile(maze, tileRange(maze, c - extent, c + extent), visit);
}

Vec3 closestPoint(const Box& box, const Vec3& p) {
  return p.cwiseMax(box.lower).cwiseMin(box.upper);
}

/// Whether the tile's closest feature to grid point c is on the surface of the union of tiles:
/// every axis on which c lies beyond the tile must face an empty neighbour. A face shared with a
/// solid neighbour is inside the union; the neighbour's own face is the surface there, so the
/// edges along a seam never produce a contact.
bool facesOpen(const Maze& maze, const Index3& t, const Box& box, const Vec3& c) {
  for (int a = 0; a < 3; ++a) {
    if (c[a] < box.lower[a] && !maze.faceOpen(t, a, -1)) return false;
    if (c[a] > box.upper[a] && !maze.faceOpen(t, a, 1)) return false;
  }
  return true;
}

/// Whether the near tiles' lowest layer fills its rectangle (NearTiles::full_bottom_layer), and
/// its bounds.
void markFullBottomLayer(NearTiles* near) {
  near->full_bottom_layer = false;
  if (near->tiles.empty()) return;
  near->bottom_end = near->layers.size() > 1 ? near->layers[1] : near->tiles.size();
  Index3& first = near->first;
  Index3& last = near->last;
  first = last = near->tiles.front().index;
  near->lower = near->tiles.front().box.lower;
  near->upper = near->tiles.front().box.upper;
  for (std::size_t i = 0; i < near->bottom_end; ++i) {
    const NearTiles::Tile& t = near->tiles[i];
    first = first.cwiseMin(t.index);
    last = last.cwiseMax(t.index);
    near->lower = near->lower.cwiseMin(t.box.lower);
    near->upper = near->upper.cwiseMax(t.box.upper);
  }
  // (Distinct tiles as many as the slots of their bounding rectangle fill it, row by row in the
  // grid's order.)
  const std::size_t slots = static_cast<std::size_t>(last.x() - first.x() + 1) *
                            static_cast<std::size_t>(last.y() - first.y() + 1);
  near->full_bottom_layer = near->bottom_end == slots;
}

/// The contacts of grid point c with the near tiles' full lowest layer, as looking at each of
/// its tiles gives them, bit for bit, when c lies above the layer and over its rectangle: the
/// top face of the first tile in the grid's order under c, or none when c is out of reach of
/// it. (Every other tile has a neighbour in the layer on the side towards c: its feature nearest
/// c lies on a face shared with a solid tile, inside the union.) False, with nothing found,
/// elsewhere, and where a tile above covers that top face (c is in it, or above a tile thinner
/// than the reach): the tiles are then looked at one by one. The layers above are left to the
/// caller; they come after this one in the grid's order, as their contacts do.
bool contactWithFullBottomLayer(const Maze& maze, NearTiles* near, const Vec3& c, double radius,
                                double reach, std::vector<Contact>* contacts) {
  if (!(c.x() >= near->lower.x() && c.x() <= near->upper.x() && c.y() >= near->lower.y() &&
        c.y() <= near->upper.y() && c.z() > near->upper.z()))
    return false;
  const double height = c.z() - near->upper.z();
  const double distance2 = height * height;
  // (Below the smallest normal number the look at each tile takes another branch.)
  if (distance2 < std::numeric_limits<double>::min()) return false;
  if (distance2 >= reach * reach) return true;  // out of reach: no contact
  // The tile under c: most often the one under the last query's centre (a marble moves a
  // millimetre or less a step over tiles of centimetres), when c lies inside it and off its
  // edges, where no seam rule or rounding of the slots' formula can pick another.
  const NearTiles::Tile* tile = &near->tiles[near->under];
  const Box& last = tile->box;
  if (!(c.x() > last.lower.x() && c.x() < last.upper.x() && c.y() > last.lower.y() &&
        c.y() < last.upper.y())) {
    // Else found by its slots rather than by a search whose end would move from query to query
    // (a branch the processor guesses wrong): on a seam c lies in the tiles either side of it,
    // and the lower one is the first in the grid's order.
    const int columns = near->last.x() - near->first.x() + 1;
    const auto at = [&](int i, int j) {
      return static_cast<std::size_t>((j - near->first.y()) * columns + i - near->first.x());
    };
    int i = std::clamp(maze.axis(0).slotAt(c.x()), near->first.x(), near->last.x());
    int j = std::clamp(maze.axis(1).slotAt(c.y()), near->first.y(), near->last.y());
    if (i > near->first.x() && c.x() <= near->tiles[at(i - 1, j)].box.upper.x()) --i;
    if (j > near->first.y() && c.y() <= near->tiles[at(i, j - 1)].box.upper.y()) --j;
    near->under = at(i, j);
    tile = &near->tiles[near->under];
  }
  // (The slots' formula and the tiles' bounds may round apart by a hair: then each tile is
  // looked at.)
  const Box& box = tile->box;
  if (!(c.x() >= box.lower.x() && c.x() <= box.upper.x() && c.y() >= box.lower.y() &&
        c.y() <= box.upper.y()))
    return false;
  // (Alone, the layer has nothing above it near enough to cover the tile within reach of c.)
  if (near->bottom_end < near->tiles.size() && !maze.faceOpen(tile->index, 2, 1)) return false;
  // (Made in place: built apart and copied in, its copy read what its stores had just written
  // in other pieces, and waited for them to reach the cache.)
  Contact& contact = contacts->emplace_back();
  contact.normal = Vec3::UnitZ();  // (the world's normal and the surface's velocity: below)
  contact.depth = radius - height;
  contact.grid_point = Vec3(c.x(), c.y(), box.upper.z());
  contact.tile = tile->index;
  return true;
}

/// For a centre inside a tile: the open face it is nearest to, as the outward normal and the
/// distance to that face. False when every face is shared (a tile buried in others).
bool nearestOpenFace(const Maze& maze, const Index3& t, const Box& box, const Vec3& c, Vec3* normal,
                     double* distance) {
  *distance = kNone;
  for (int a = 0; a < 3; ++a)
    for (int side : {-1, 1}) {
      if (!maze.faceOpen(t, a, side)) continue;
      const double d = side < 0 ? c[a] - box.lower[a] : box.upper[a] - c[a];
      if (d < *distance) {
        *distance = d;
        *normal = Vec3::Zero();
        (*normal)[a] = side;
      }
    }
  return *distance < kNone;
}

/// The one axis along which an offset from a box is not zero (the centre lies off a face), or -1.
int faceAxis(const Vec3& offset) {
  const int zeros = (offset.x() == 0) + (offset.y() == 0) + (offset.z() == 0);
  if (zeros != 2) return -1;
  return offset.x() != 0 ? 0 : offset.y() != 0 ? 1 : 2;
}

/// Keeps one contact per normal: coplanar tiles on either side of a seam give the same one.
void addContact(std::vector<Contact>* contacts, const Contact& c) {
  for (Contact& existing : *contacts)
    if (existing.normal.dot(c.normal) > 1.0 - 1e-9) {
      if (c.depth > existing.depth) existing = c;
      return;
    }
  contacts->push_back(c);
}

/// First time t in [0, 1] at which o + t d comes within r of point s, approaching it.
bool sphereImpact(const Vec3& o, const Vec3& d, const Vec3& s, double r, double* t) {
  const Vec3 m = o - s;
  const double b = m.dot(d);
  const double c = m.squaredNorm() - r * r;
  if (c <= 0 || b >= 0) return false;  // already touching, or moving away
  const double a = d.squaredNorm();
  const double disc = b * b - a * c;
  if (disc < 0) return false;
  *t = (-b - std::sqrt(disc)) / a;
  return *t <= 1;
}

/// First impact of o + t d against the capsule of radius r around the segment that starts at
/// `start` and runs `length` along `axis`; `point` gets the touched point of the segment.
bool capsuleImpact(const Vec3& o, const Vec3& d, const Vec3& start, int axis, double length,
                   double r, double* time, Vec3* point) {
  *time = kNone;
  // The side of the cylinder: distances across the axis only.
  Vec3 m = o - start, e = d;
  m[axis] = 0;
  e[axis] = 0;
  const double a = e.squaredNorm(), b = m.dot(e), c = m.squaredNorm() - r * r;
  if (a > 0 && c > 0 && b < 0) {
    const double disc = b * b - a * c;
    if (disc >= 0) {
      const double t = (-b - std::sqrt(disc)) / a;
      const double along = o[axis] + t * d[axis] - start[axis];
      if (t <= 1 && along >= 0 && along <= length) {
        *time = t;
        *point = start;
        (*point)[axis] += along;
      }
    }
  }
  // The rounded ends.
  for (double along : {0.0, length}) {
    Vec3 end = start;
    end[axis] += along;
    double t;
    if (sphereImpact(o, d, end, r, &t) && t < *time) {
      *time = t;
      *point = end;
    }
  }
  return *time < kNone;
}

/// Whether the segment from o by d meets the box grown by `grow` on every side, and the fraction
/// where it goes in (0 when it starts inside): the slab test.
bool segmentMeetsBox(const Vec3& o, const Vec3& d, const Box& box, double grow,
                     double* enter = nullptr) {
  double in = 0, out = 1;
  for (int a = 0; a < 3; ++a) {
    const double lo = box.lower[a] - grow, hi = box.upper[a] + grow;
    if (d[a] == 0) {
      if (o[a] < lo || o[a] > hi) return false;
      continue;
    }
    double t1 = (lo - o[a]) / d[a], t2 = (hi - o[a]) / d[a];
    if (t1 > t2) std::swap(t1, t2);
    in = std::max(in, t1);
    out = std::min(out, t2);
    if (in > out) return false;
  }
  if (enter) *enter = in;
  return true;
}

/// Whether the box lies wholly behind one of the planes the path keeps to. A box that reaches
/// less than the contact margin in front of one counts as behind it: the marble could at most
/// touch it by that much, a contact the next substep finds.
/// (Without branches: which tiles are behind changes from one substep to the next, and a branch
/// that guesses wrong costs more than the arithmetic.)
bool behindAPlane(const Sweep& w, const Box& box) {
  bool behind = false;
  for (int k = 0; k < w.planes; ++k) {
    const Vec3& n = w.plane_normal[k];
    double front = 0;  // the box's farthest reach along n
    for (int a = 0; a < 3; ++a) front += std::max(n[a] * box.lower[a], n[a] * box.upper[a]);
    behind |= front <= w.plane_offset[k] + w.margin;
  }
  return behind;
}

/// How far from its start the marble of a sweep can reach a tile: its radius plus how far the
/// path strays, |s path + s^2 bend| <= |path| + |bend| for s in [0, 1], with room for rounding
/// (which moves a tile's bounds and the path's extremes by some 1e-16 m). No tile farther than
/// this can be met. (The lengths bounded by the sums of their components' sizes, at most sqrt(3)
/// times more: two square roots one after the other held up every step that waits on the
/// answer, and a bound a little wide only leaves a few more tiles to the exact tests.)
double farthestReach(const Sweep& w) {
  return w.radius + w.path.lpNorm<1>() + w.bend.lpNorm<1>() + kRoundingRoom;
}

/// Whether a unit normal lies along grid axis a, either way. (Off-axis parts below 1e-12 move a
/// tile's reach across its plane by far less than the contact margin.)
bool alongAxis(const Vec3& n, int a) {
  return std::abs(n[a]) >= 1 - 1e-12 && std::abs(n[(a + 1) % 3]) <= 1e-12 &&
         std::abs(n[(a + 2) % 3]) <= 1e-12;
}

/// Narrows a range of tiles to those in front of the planes the path keeps to that face along a
/// grid axis (a floor, a wall): the tiles behind such a plane are not even looked up.
void narrowToPlanes(const Maze& maze, const Sweep& w, TileRange* range) {
  for (int k = 0; k < w.planes; ++k) {
    const Vec3& n = w.plane_normal[k];
    for (int a = 0; a < 3; ++a) {
      if (!alongAxis(n, a)) continue;
      const double plane = w.plane_offset[k] / n[a];
      if (n[a] > 0)
        range->first[a] = std::max(range->first[a], maze.axis(a).slotAt(plane + w.margin));
      else
        range->last[a] = std::min(range->last[a], maze.axis(a).slotAt(plane - w.margin));
    }
  }
}

/// Whether a bent path leaving a tile it touches (`away`: from the tile's nearest point to the
/// start) can come back to it within the stretch: it must be leaving clearly (a contact the
/// marble rolls on has no rate across it but for rounding) and bending back fast enough, as a
/// small bounce does.
bool comesBack(const Sweep& w, const Vec3& away) {
  const double length = away.norm();
  if (!(length > 0)) return false;
  const Vec3 n = away / length;
  const double rate = n.dot(w.rate(0)), bend = n.dot(w.bend);
  return rate > w.resting_rate && bend < 0 && rate <= -2 * bend;  // back by about s = 1
}

/// What the walk's tests of a tile take from its sweep, worked out once.
struct SweepReach {
  explicit SweepReach(const Sweep& w)
      : touching2((w.radius + w.margin) * (w.radius + w.margin)),
        farthest(farthestReach(w)),
        chord(w.path + w.bend),
        sag(0.25 * w.bend.norm()),  // the farthest a bent path strays from its chord
        bent(sag > 0) {}

  double touching2;  ///< a tile closer to the start than its square root is touched there
  double farthest;   ///< no tile farther from the start can be met
  Vec3 chord;
  double sag;
  bool bent;
};

/// Whether the walk passes over the tile before seeking any root: behind a plane the path keeps
/// to; touched at the start (a contact, left to findContacts) by a path that cannot come back to
/// it, as a bent path leaving it may within the stretch (a small bounce); beyond the marble's
/// farthest reach; or, the path's chord grown by the radius and the sag missing it, the slab test
/// with which the exact tests begin. `away` (from the tile to the start) and `touches`, when
/// asked for, are what the walk's exact tests go on with. (One function for the walk and
/// Sweep::clearOf, so that a path clearOf lets by is one the walk finds no impact on, to the bit.)
bool passedOver(const Sweep& w, const SweepReach& s, const Box& box, Vec3* away = nullptr,
                bool* touches = nullptr) {
  if (behindAPlane(w, box)) return true;
  const Vec3 gap = w.from - closestPoint(box, w.from);
  const bool touching = gap.squaredNorm() < s.touching2;
  if (away) *away = gap;
  if (touches) *touches = touching;
  if (touching && !(s.bent && comesBack(w, gap))) return true;
  if (gap.squaredNorm() > s.farthest * s.farthest) return true;
  if (touching) return false;  // a path leaving it may come back onto it: a root decides
  return s.bent ? !segmentMeetsBox(w.from, s.chord, box, w.radius + s.sag)
                : !segmentMeetsBox(w.from, w.path, box, w.radius);
}

/// The range of one coordinate of a bent path over s in [0, 1].
void coordinateRange(const Sweep& w, int a, double* lo, double* hi) {
  const double end = w.from[a] + w.path[a] + w.bend[a];
  *lo = std::min(w.from[a], end);
  *hi = std::max(w.from[a], end);
  if (w.bend[a] != 0) {
    const double s = -w.path[a] / (2 * w.bend[a]);
    if (s > 0 && s < 1) {
      const double turn = w.from[a] + s * (w.path[a] + s * w.bend[a]);
      *lo = std::min(*lo, turn);
      *hi = std::max(*hi, turn);
    }
  }
}

/// The quartic |P + Q s + R s^2|^2 - r^2 over the given axes: the squared distance of the path
/// from a box's edge (two axes) or corner (three) less the radius squared.
void distanceQuartic(const Sweep& w, const Vec3& feature, const int* axes, int count, double r,
                     double* c) {
  double pp = 0, pq = 0, qq = 0, pr = 0, qr = 0, rr = 0;
  for (int k = 0; k < count; ++k) {
    const int a = axes[k];
    const double p = w.from[a] - feature[a], q = w.path[a], b = w.bend[a];
    pp += p * p;
    pq += p * q;
    qq += q * q;
    pr += p * b;
    qr += q * b;
    rr += b * b;
  }
  c[0] = pp - r * r;
  c[1] = 2 * pq;
  c[2] = qq + 2 * pr;
  c[3] = 2 * qr;
  c[4] = rr;
}

/// The first s in (lo, hi] at which the quartic goes from positive to negative and `accept(s)`.
template <typename Accept>
bool firstDescentWhere(const double* c, double lo, double hi, Accept accept, double* s) {
  double roots[4];
  const int count = signChangesIn(c, 4, lo, hi, roots);
  double previous = lo;
  for (int k = 0; k < count; ++k) {
    const double before = evaluatePolynomial(c, 4, 0.5 * (previous + roots[k]));
    previous = roots[k];
    if (roots[k] > lo && before > 0 && accept(roots[k])) {
      *s = roots[k];
      return true;
    }
  }
  return false;
}

/// First impact, before `before`, of a bent path against a box grown by the radius with rounded
/// edges and corners. Its surface is made of the faces moved out by the radius, the edges'
/// cylinders and the corners' spheres: the path first meets it where it first goes into one of
/// them, at a root of a quadratic (faces) or a quartic (edges, corners).
bool bentSphereBoxImpact(const Maze& maze, const Index3& t, const Sweep& w, const Box& box,
                         double before, double* time, Vec3* point) {
  // A face shared with a solid neighbour is inside the union of tiles, and so is every edge and
  // corner on it: no path meets them first (the neighbour's own surface is met instead).
  const auto open = [&](int a, int side) { return maze.faceOpen(t, a, side); };
  const double r = w.radius;
  double best = before;
  Vec3 lo, hi;  // the path's bounding box: a feature beyond it is never reached
  for (int a = 0; a < 3; ++a) coordinateRange(w, a, &lo[a], &hi[a]);
  const auto beyond = [&](int a, int side) {
    return side < 0 ? lo[a] < box.lower[a] : hi[a] > box.upper[a];
  };
  const auto corner = [&](int a, int side) { return side < 0 ? box.lower[a] : box.upper[a]; };
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, d = (a + 2) % 3;
    for (int side : {-1, 1}) {
      // Faces: side * (x_a(s) - plane) falls through zero.
      if (!beyond(a, side) || !open(a, side)) continue;
      const double plane = corner(a, side) + side * r;
      const double c[3] = {side * (w.from[a] - plane), side * w.path[a], side * w.bend[a]};
      double s;
      if (!firstDescent(c, 2, 0, 1, &s) || s >= best) continue;
      Vec3 p = w.at(s);
      if (p[b] < box.lower[b] || p[b] > box.upper[b] || p[d] < box.lower[d] || p[d] > box.upper[d])
        continue;
      p[a] = corner(a, side);
      best = s;
      *point = p;
    }
    // The edges along axis a.
    for (int side_b : {-1, 1})
      for (int side_d : {-1, 1}) {
        if (!beyond(b, side_b) || !beyond(d, side_d) || !open(b, side_b) || !open(d, side_d))
          continue;
        Vec3 edge = Vec3::Zero();
        edge[b] = corner(b, side_b);
        edge[d] = corner(d, side_d);
        const int axes[2] = {b, d};
        double c[5], s;
        distanceQuartic(w, edge, axes, 2, r, c);
        // The path may go into the edge's cylinder beyond the edge's ends and again within.
        if (!firstDescentWhere(
                c, 0, std::min(1.0, best),
                [&](double t) {
                  const double along = w.at(t)[a];
                  return along >= box.lower[a] && along <= box.upper[a];
                },
                &s))
          continue;
        edge[a] = w.at(s)[a];
        best = s;
        *point = edge;
      }
  }
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      for (int sz : {-1, 1}) {
        if (!beyond(0, sx) || !beyond(1, sy) || !beyond(2, sz) || !open(0, sx) || !open(1, sy) ||
            !open(2, sz))
          continue;
        const Vec3 vertex(corner(0, sx), corner(1, sy), corner(2, sz));
        const int axes[3] = {0, 1, 2};
        double c[5], s;
        distanceQuartic(w, vertex, axes, 3, r, c);
        if (!firstDescent(c, 4, 0, 1, &s) || s >= best) continue;
        best = s;
        *point = vertex;
      }
  if (!(best < before)) return false;
  *time = best;
  return true;
}

}  // namespace

bool sphereBoxImpact(const Vec3& o, const Vec3& d, double radius, const Box& box, double* time,
                     Vec3* point) {
  // Where the path enters the box grown by the radius.
  double enter;
  if (!segmentMeetsBox(o, d, box, radius, &enter)) return false;
  // Beyond how many of the box's sides that point lies tells a face from an edge or a corner.
  const Vec3 p = o + enter * d;
  int outside[3], count = 0;
  Vec3 corner;
  for (int a = 0; a < 3; ++a) {
    corner[a] = p[a] < box.lower[a] ? box.lower[a] : box.upper[a];
    if (p[a] < box.lower[a] || p[a] > box.upper[a]) outside[count++] = a;
  }
  if (count == 0) return false;  // starts overlapping the box: a contact, not an impact
  if (count == 1) {
    *time = enter;
    *point = closestPoint(box, p);
    return true;
  }
  // On a rounded edge or corner: the capsules along the box edges that meet there.
  *time = kNone;
  for (int axis = 0; axis < 3; ++axis) {
    const bool along_outside_axis = std::find(outside, outside + count, axis) != outside + count;
    if (count == 2 && along_outside_axis) continue;  // an edge runs along the one inside axis
    Vec3 start = corner;
    start[axis] = box.lower[axis];
    double t;
    Vec3 q;
    if (capsuleImpact(o, d, start, axis, box.upper[axis] - box.lower[axis], radius, &t, &q) &&
        t < *time) {
      *time = t;
      *point = q;
    }
  }
  return *time < kNone;
}

void findContacts(const Maze& maze, const GridFrame& frame, const Vec3& centre, double radius,
                  double margin, std::vector<Contact>* contacts, NearTiles* near) {
  contacts->clear();
  const Vec3 c = frame.toGrid(centre);  // step 1: eq. (4)
  const double reach = radius + margin;
  // The contact test below takes only tiles within `reach`; the tiles looked at reach a little
  // farther, so that those a rounding error either side of it are looked at, gathered here or
  // kept from an earlier query alike, and the contacts do not depend on which.
  const double looked = reach + kRoundingRoom + (near ? near->skin : 0);
  const auto contactWith = [&](const Index3& t, const Box& box) {
    Vec3 q = closestPoint(box, c);  // step 4: the box's nearest point to the centre
    const Vec3 offset = c - q;
    const double distance2 = offset.squaredNorm();
    if (distance2 >= reach * reach) return;  // step 5: no contact beyond the radius
    if (!facesOpen(maze, t, box, c)) return;
    Contact contact;
    const int along = faceAxis(offset);
    if (along >= 0 && distance2 >= std::numeric_limits<double>::min()) {
      // Off a face: the normal is the face's, and the distance the one coordinate, which is
      // what the square root and the quotient below give to the bit (sqrt(x^2) = |x| when x^2
      // neither underflows nor overflows), without their wait.
      contact.normal = Vec3::Zero();
      contact.normal[along] = offset[along] > 0 ? 1 : -1;
      contact.depth = radius - std::abs(offset[along]);
    } else if (distance2 > 0) {
      const double distance = std::sqrt(distance2);
      contact.normal = offset / distance;
      contact.depth = radius - distance;
    } else {
      double inside;  // the centre is in the tile: leave through its nearest open face
      if (!nearestOpenFace(maze, t, box, c, &contact.normal, &inside)) return;
      q = c + contact.normal * inside;
      contact.depth = radius + inside;
    }
    contact.grid_point = q;
    contact.tile = t;
    addContact(contacts, contact);
  };
  // Steps 2 and 3: the index range of the marble's extent, and the tiles that exist in it. The
  // contacts are gathered in the grid frame (normal, nearest point) and taken into the world
  // once each, after coplanar tiles have been merged.
  if (!near) {
    forEachSolidTileAround(maze, c, looked, contactWith);
  } else {
    if (!((c - near->centre).cwiseAbs().maxCoeff() + looked <= near->reach)) {
      near->reach = looked + near->slack;
      near->centre = c;
      near->tiles.clear();
      near->layers.clear();
      near->under = 0;
      ++near->gathers;
      forEachSolidTileAround(maze, c, near->reach, [&](const Index3& t, const Box& box) {
        if (near->tiles.empty() || near->tiles.back().index.z() != t.z())
          near->layers.push_back(near->tiles.size());
        // (Built in place: push_back({box, t}) put a temporary on the stack, its index written
        // as three 4-byte stores and read back as one 8-byte load, which waited for them. The
        // box is copied as tileBox wrote it, a coordinate at a time, as it was timed.)
        NearTiles::Tile& kept = near->tiles.emplace_back();
        for (int a = 0; a < 3; ++a) {
          kept.box.lower[a] = box.lower[a];
          kept.box.upper[a] = box.upper[a];
        }
        kept.index = t;
      });
      markFullBottomLayer(near);
    }
    // (The lowest layer's tiles are answered for when its top gives their contacts.)
    const std::size_t answered =
        near->full_bottom_layer &&
                contactWithFullBottomLayer(maze, near, c, radius, reach, contacts)
            ? near->bottom_end
            : 0;
    for (std::size_t i = answered; i < near->tiles.size(); ++i)
      contactWith(near->tiles[i].index, near->tiles[i].box);
  }
  for (Contact& contact : *contacts) {
    contact.grid_normal = contact.normal;
    contact.normal = frame.rotation * contact.normal;
    // The board's velocity where the marble's surface meets the normal (not at the tile's
    // nearest point, up to the margin away, across the normal the same): so every contact of a
    // marble wedged on a turning board asks the same rigid motion of it, as it must to stay
    // wedged, instead of motions that differ by |w| times their depths.
    contact.surface_velocity = frame.surfaceVelocity(centre - radius * contact.normal);
  }
}

bool Sweep::clearOf(const NearTiles& near) const {
  const double farthest = farthestReach(*this);
  // A tile the near ones leave out lies beyond `near.reach` from where they were gathered
  // along some axis.
  const double moved = (from - near.centre).cwiseAbs().maxCoeff();
  if (!(moved + farthest < near.reach)) return false;
  // The layers wholly behind a floor the path keeps to are passed over at once, as the walk
  // passes over them (narrowToPlanes): a marble rolling on the floor has most near tiles there.
  double floor = -kNone;
  for (int k = 0; k < planes; ++k)
    if (alongAxis(plane_normal[k], 2) && plane_normal[k].z() > 0)
      floor = std::max(floor, plane_offset[k] / plane_normal[k].z() + margin);
  std::size_t first = 0;
  for (std::size_t i = 0; i < near.layers.size(); ++i) {
    if (!(near.tiles[near.layers[i]].box.upper.z() <= floor)) break;
    first = i + 1 < near.layers.size() ? near.layers[i + 1] : near.tiles.size();
  }
  bool clear = true;  // tile by tile without branches (see behindAPlane)
  for (std::size_t i = first; i < near.tiles.size(); ++i) {
    const Box& box = near.tiles[i].box;
    clear &= behindAPlane(*this, box) |
             ((from - closestPoint(box, from)).squaredNorm() > farthest * farthest);
  }
  if (clear) return true;
  // Some tile lies within the marble's reach: a marble rolling beside a wall it does not touch,
  // or towards one. The walk's own tests before any root then say whether its path can meet
  // them, without its walk of the grid's slots.
  const SweepReach sweep_reach(*this);
  for (std::size_t i = first; i < near.tiles.size(); ++i)
    if (!passedOver(*this, sweep_reach, near.tiles[i].box)) return false;
  return true;
}

ImpactState timeOfImpact(const Maze& maze, const GridFrame& frame, const Sweep& w, SweepHit* hit) {
  hit->tiles_visited = 0;
  const double radius = w.radius;
  // The whole path grown by the radius: when it stays clear of the grid (a marble in flight far
  // from the board) nothing more is worked out.
  {
    Vec3 lo, hi;
    for (int a = 0; a < 3; ++a) coordinateRange(w, a, &lo[a], &hi[a]);
    const Vec3 grow = Vec3::Constant(radius + w.margin);
    if (!overlapsGrid(maze, lo - grow, hi + grow)) return ImpactState::OffGrid;
  }
  // The path's speed along s is largest at an end (its norm is convex), which bounds its length.
  const double length = std::max(w.rate(0).norm(), w.rate(1).norm());
  if (!(length > 0)) return ImpactState::Still;
  // (Tiles beyond the marble's farthest reach, which the walk's boxes take in at their corners,
  // are passed over before any root is sought, with others no root can be found on.)
  const SweepReach sweep_reach(w);
  const double sag = sweep_reach.sag;
  const bool bent = sweep_reach.bent;
  const double needed = std::ceil(length / radius);
  if (needed > 1e6) return ImpactState::GaveUp;
  const int pieces = static_cast<int>(needed);
  double best = kNone;
  bool overlapped = false;
  const double overlap = std::max(0.0, radius - w.margin);
  Index3 best_tile = Index3::Zero();
  Vec3 best_point = Vec3::Zero(), best_normal = Vec3::Zero();
  for (int piece = 0; piece < pieces; ++piece) {
    const double s0 = static_cast<double>(piece) / pieces;
    const double s1 = static_cast<double>(piece + 1) / pieces;
    const Vec3 a = w.at(s0), b = w.at(s1);
    // A piece strays from its own chord by the path's sag times its share of s squared.
    const Vec3 grow = Vec3::Constant(radius + sag / (static_cast<double>(pieces) * pieces));
    TileRange range = tileRange(maze, a.cwiseMin(b) - grow, a.cwiseMax(b) + grow);
    narrowToPlanes(maze, w, &range);
    forEachSolidTile(maze, range, [&](const Index3& t, const Box& box) {
      ++hit->tiles_visited;
      Vec3 away = Vec3::Zero();
      bool touches = false;
      const bool passed = passedOver(w, sweep_reach, box, &away, &touches);
      overlapped = overlapped || (touches && away.squaredNorm() < overlap * overlap);
      if (passed) return;
      double time;
      Vec3 q;
      if (touches) {
        // Back onto the tile it is leaving (a small bounce): across the plane of its contact,
        // whose normal is `away`, a root of a quadratic.
        const Vec3 n = away.normalized();
        const double c[3] = {away.norm() - radius, n.dot(w.path), n.dot(w.bend)};
        if (!firstDescent(c, 2, 0, std::min(1.0, best), &time) || time >= best) return;
        q = closestPoint(box, w.at(time));
      } else if (bent) {
        if (!bentSphereBoxImpact(maze, t, w, box, best, &time, &q)) return;
      } else if (!sphereBoxImpact(w.from, w.path, radius, box, &time, &q) || time >= best) {
        return;
      }
      const Vec3 c = w.at(time);
      if (!facesOpen(maze, t, box, c)) return;  // a seam: the neighbour's face is hit instead
      const Vec3 normal = (c - q).normalized();
      const Vec3 rate = w.rate(time);
      // Grazing: an approach slower than resting is a contact the next substep finds, not an
      // impact (the path rolls over a seam onto a coplanar tile at rounding's height).
      if (normal.dot(rate) >= -std::max(w.resting_rate, 1e-12 * rate.norm())) return;
      best = time;
      best_tile = t;
      best_point = q;
      best_normal = normal;
    });
    // An impact within the pieces walked so far cannot be beaten by tiles further on.
    if (best <= s1) break;
  }
  if (best == kNone) return overlapped ? ImpactState::Overlapped : ImpactState::Separated;
  hit->fraction = best;
  hit->contact.grid_normal = best_normal;
  hit->contact.normal = frame.rotation * best_normal;
  hit->contact.grid_point = best_point;
  // Met at the radius: the marble's surface meets the normal at the tile's point.
  hit->contact.surface_velocity = frame.surfaceVelocity(frame.toWorld(best_point));
  hit->contact.depth = 0;
  hit->contact.tile = best_tile;
  return ImpactState::Hit;
}

}  // namespace marble_maze
