// Collision detection against hand-worked geometry: normals and depths of faces, edges and
// corners, seams, large marbles, and the swept test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "bench_mazes.h"
#include "marble_maze/collision.h"
#include "scenes.h"

namespace marble_maze {
namespace {

constexpr double kTol = 1e-12;

/// The time of impact along a straight path, board at rest in the world's frame.
bool sweepStraight(const Maze& maze, const Vec3& from, const Vec3& path, double radius,
                   SweepHit* hit) {
  Sweep sweep;
  sweep.from = from;
  sweep.path = path;
  sweep.radius = radius;
  sweep.margin = 1e-9;
  return timeOfImpact(maze, GridFrame(), sweep, hit) == ImpactState::Hit;
}

/// A uniform 1 cm grid, 10 x 10 x 3, with the given solid tiles.
Maze grid(std::initializer_list<Index3> solid) {
  Maze maze(AxisSlots::uniform(0.01, 10), AxisSlots::uniform(0.01, 10),
            AxisSlots::uniform(0.01, 3));
  for (const Index3& t : solid) maze.setSolid(t, true);
  return maze;
}

std::vector<Contact> contactsAt(const Maze& maze, const Vec3& centre, double radius) {
  std::vector<Contact> contacts;
  findContacts(maze, GridFrame(), centre, radius, 1e-9, &contacts);
  return contacts;
}

TEST(FindContacts, FaceContactHasTheFaceNormalAndDepth) {
  const Maze maze = grid({{5, 5, 0}});
  const auto contacts = contactsAt(maze, {0.055, 0.055, 0.014}, 0.005);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR((contacts[0].normal - Vec3(0, 0, 1)).norm(), 0, kTol);
  EXPECT_NEAR(contacts[0].depth, 0.001, kTol);
  EXPECT_NEAR((contacts[0].grid_point - Vec3(0.055, 0.055, 0.01)).norm(), 0, kTol);
  EXPECT_EQ(contacts[0].tile, Index3(5, 5, 0));
}

TEST(FindContacts, EdgeAndCornerContactsPointFromTheFeatureToTheCentre) {
  const Maze maze = grid({{5, 5, 0}});
  const double d = 0.003;  // offset beyond the top edge along x and z
  auto contacts = contactsAt(maze, {0.06 + d, 0.055, 0.01 + d}, 0.005);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR((contacts[0].normal - Vec3(1, 0, 1).normalized()).norm(), 0, kTol);
  EXPECT_NEAR(contacts[0].depth, 0.005 - d * std::sqrt(2.0), kTol);
  contacts = contactsAt(maze, {0.06 + d, 0.06 + d, 0.01 + d}, 0.006);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR((contacts[0].normal - Vec3(1, 1, 1).normalized()).norm(), 0, kTol);
  EXPECT_NEAR(contacts[0].depth, 0.006 - d * std::sqrt(3.0), kTol);
}

TEST(FindContacts, NoContactBeyondTheRadius) {
  const Maze maze = grid({{5, 5, 0}});
  EXPECT_TRUE(contactsAt(maze, {0.055, 0.055, 0.0151}, 0.005).empty());
  EXPECT_TRUE(contactsAt(maze, {0.064, 0.055, 0.014}, 0.005).empty());  // 5.66 mm from the edge
}

TEST(FindContacts, SeamsBetweenFloorTilesActAsOneFlatFloor) {
  const Maze maze = grid({{4, 5, 0}, {5, 5, 0}, {4, 4, 0}, {5, 4, 0}});
  // A slightly sunk marble near a seam, near the corner where four tiles meet, and on it.
  for (const Vec3& centre :
       {Vec3(0.0501, 0.055, 0.01499), Vec3(0.0499, 0.0501, 0.01499), Vec3(0.05, 0.05, 0.01499)}) {
    const auto contacts = contactsAt(maze, centre, 0.005);
    ASSERT_EQ(contacts.size(), 1u) << centre.transpose();
    EXPECT_EQ(contacts[0].normal, Vec3(0, 0, 1)) << centre.transpose();
    EXPECT_NEAR(contacts[0].depth, 1e-5, kTol);
  }
}

TEST(FindContacts, SeamsInAWallActAsOneFlatWall) {
  // A wall of tiles along y at x slot 5, layer 1, on a floor.
  Maze maze = grid({});
  for (int j = 0; j < 10; ++j) {
    maze.setSolid({5, j, 1}, true);
    for (int i = 0; i < 10; ++i) maze.setSolid({i, j, 0}, true);
  }
  const auto contacts = contactsAt(maze, {0.06 + 0.0049, 0.05, 0.015}, 0.005);
  ASSERT_EQ(contacts.size(), 2u);  // the floor and the wall, nothing from the seams
  for (const Contact& c : contacts)
    EXPECT_TRUE(c.normal == Vec3(1, 0, 0) || c.normal == Vec3(0, 0, 1)) << c.normal.transpose();
}

TEST(FindContacts, AMarbleLargerThanACellFindsEveryTileItTouches) {
  Maze maze(AxisSlots::uniform(0.002, 20), AxisSlots::uniform(0.002, 20),
            AxisSlots::uniform(0.002, 20));
  maze.setSolid({0, 10, 10}, true);   // 18.5 mm from the centre along -x
  maze.setSolid({19, 10, 10}, true);  // 17.5 mm along +x
  const double radius = 0.019;        // nine and a half slots
  const auto contacts = contactsAt(maze, {0.0205, 0.021, 0.021}, radius);
  ASSERT_EQ(contacts.size(), 2u);
  for (const Contact& c : contacts) EXPECT_NEAR(std::abs(c.normal.x()), 1.0, kTol);
}

TEST(FindContacts, ACentreInsideATileLeavesThroughTheNearestOpenFace) {
  const Maze maze = grid({{5, 5, 0}, {6, 5, 0}});
  const auto contacts = contactsAt(maze, {0.059, 0.055, 0.006}, 0.005);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].normal, Vec3(0, 0, 1));  // the +x face is shared with a tile
  EXPECT_NEAR(contacts[0].depth, 0.005 + 0.004, kTol);
}

TEST(FindContacts, FollowsTheBoardFrameByEquationFour) {
  const Maze maze = grid({{5, 5, 0}});
  GridFrame frame;
  frame.rotation = Eigen::AngleAxisd(0.3, Vec3::UnitY()).toRotationMatrix();
  frame.grid_pivot = Vec3(0.1, -0.2, 0.05);
  const Vec3 grid_centre(0.055, 0.055, 0.014);
  std::vector<Contact> contacts;
  findContacts(maze, frame, frame.toWorld(grid_centre), 0.005, 1e-9, &contacts);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR((contacts[0].normal - frame.rotation.col(2)).norm(), 0, kTol);
  EXPECT_NEAR(contacts[0].depth, 0.001, kTol);
}

TEST(GridFrame, HeightsCarryNoRoundingThatGrowsWithTheMaze) {
  // A marble near the pivot of mazes 0.3 m, 8 m and 27 m wide, on a board tilted up to 0.1 rad:
  // its height in the grid rounds as it does near a small grid's corner (eq. (4) about the
  // pivot; about the grid's corner it rounded by 3e-16 m in the 8 m maze and 1e-15 m in the
  // 27 m one).
  for (const double half : {0.14, 4.07, 13.6}) {
    GridFrame frame;
    frame.grid_pivot = Vec3(half, half, 0.005);
    double worst = 0;
    for (int k = 0; k < 1000; ++k) {
      const double roll = 0.1 * std::sin(k), pitch = 0.1 * std::cos(1.7 * k);
      frame.rotation =
          (Eigen::AngleAxisd(pitch, Vec3::UnitY()) * Eigen::AngleAxisd(roll, Vec3::UnitX()))
              .toRotationMatrix();
      const Vec3 world = frame.rotation * Vec3(0.01 * std::sin(3.1 * k), 0.01, 0.006);
      long double exact = 0;  // the height above the pivot, z' . p, in extended precision
      for (int i = 0; i < 3; ++i)
        exact += static_cast<long double>(frame.rotation(i, 2)) * world[i];
      worst =
          std::max(worst, std::abs(static_cast<double>(frame.toGrid(world).z() - 0.005L - exact)));
    }
    EXPECT_LT(worst, 5e-18) << "a grid " << 2 * half << " m wide";
  }
}

TEST(SphereBoxImpact, FaceEdgeAndCornerTimesMatchHandWorkedValues) {
  const Box box{{0, 0, 0}, {0.01, 0.01, 0.01}};
  double t;
  Vec3 q;
  // Face: from x = -0.02 towards +x, radius 0.005: touches at x = -0.005, t = 0.015 / 0.03.
  ASSERT_TRUE(sphereBoxImpact({-0.02, 0.005, 0.005}, {0.03, 0, 0}, 0.005, box, &t, &q));
  EXPECT_NEAR(t, 0.5, kTol);
  EXPECT_NEAR(q.x(), 0.0, kTol);
  // Edge along z at (0, 0): centre path y = -0.003 moving +x: touches when x = -0.004.
  ASSERT_TRUE(sphereBoxImpact({-0.02, -0.003, 0.005}, {0.02, 0, 0}, 0.005, box, &t, &q));
  EXPECT_NEAR(t, (0.02 - 0.004) / 0.02, kTol);
  EXPECT_NEAR((q - Vec3(0, 0, 0.005)).norm(), 0, kTol);
  // Corner: along the diagonal towards (0, 0, 0).
  const Vec3 dir = Vec3(1, 1, 1).normalized();
  ASSERT_TRUE(sphereBoxImpact(-0.02 * dir, 0.02 * dir, 0.005, box, &t, &q));
  EXPECT_NEAR(t, 0.75, kTol);
  EXPECT_NEAR(q.norm(), 0, kTol);
  // A miss beside the rounded edge.
  EXPECT_FALSE(sphereBoxImpact({-0.02, -0.004, -0.004}, {0.04, 0, 0}, 0.005, box, &t, &q));
}

/// Whether two queries found the same contacts, bit for bit, in the same order.
::testing::AssertionResult sameContacts(const std::vector<Contact>& a,
                                        const std::vector<Contact>& b) {
  if (a.size() != b.size())
    return ::testing::AssertionFailure() << a.size() << " contacts against " << b.size();
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].normal != b[i].normal || a[i].grid_normal != b[i].grid_normal ||
        a[i].grid_point != b[i].grid_point || a[i].surface_velocity != b[i].surface_velocity ||
        a[i].depth != b[i].depth || a[i].tile != b[i].tile)
      return ::testing::AssertionFailure()
             << "contact " << i << " differs: tile " << a[i].tile.transpose() << " against "
             << b[i].tile.transpose() << ", depth " << a[i].depth << " against " << b[i].depth;
  return ::testing::AssertionSuccess();
}

TEST(FindContacts, KeptNearTilesGiveTheContactsOfAFreshLook) {
  // A marble wandering over a generated maze in steps of up to 2 mm, near the floor and the
  // walls and sometimes into them, on a tilted board: the contacts found with the near tiles kept
  // from earlier queries (gathered anew only now and then) are those of a query that looks at the
  // grid afresh, bit for bit, and the kept tiles hold every solid tile the query needs.
  const Maze maze = bench::generatedMaze(10);
  const double r = 0.006, margin = 1e-7;
  GridFrame frame;
  frame.rotation = Eigen::AngleAxisd(0.1, Vec3(1, 2, 0).normalized()).toRotationMatrix();
  frame.grid_pivot = maze.pivot();
  frame.angular_velocity = Vec3(0.3, -0.2, 0);
  std::mt19937 random(11);
  const auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * std::generate_canonical<double, 53>(random);
  };
  NearTiles kept;
  kept.slack = 0.5 * r;
  Vec3 grid(maze.axis(0).centre(1), maze.axis(1).centre(1), maze.floorTop() + r);
  int contacts_seen = 0;
  for (int n = 0; n < 20000; ++n) {
    const Vec3 move(uniform(-2e-3, 2e-3), uniform(-2e-3, 2e-3), uniform(-1e-3, 1e-3));
    grid = (grid + move).cwiseMax(Vec3(0, 0, maze.floorTop() + 0.5 * r));
    grid = grid.cwiseMin(Vec3(maze.extent().x(), maze.extent().y(), maze.floorTop() + 2 * r));
    if (n % 3 == 0) grid.z() = maze.floorTop() + r;  // resting on the floor, exactly
    const Vec3 centre = frame.toWorld(grid);
    kept.skin = uniform(0, r);
    std::vector<Contact> with_kept, fresh;
    findContacts(maze, frame, centre, r, margin, &with_kept, &kept);
    findContacts(maze, frame, centre, r, margin, &fresh);
    ASSERT_TRUE(sameContacts(with_kept, fresh)) << "at " << grid.transpose();
    contacts_seen += static_cast<int>(fresh.size());
    // Every solid tile within the skin beyond the contacts' reach is among the kept ones.
    const Vec3 c = frame.toGrid(centre);
    EXPECT_LE((c - kept.centre).cwiseAbs().maxCoeff() + r + margin + kept.skin, kept.reach);
  }
  EXPECT_GT(contacts_seen, 10000);
  EXPECT_LT(kept.gathers, 15000u);  // kept for some queries: 0 would test nothing
}

TEST(FindContacts, AFullBottomLayerOfNearTilesGivesTheContactsOfAFreshLook) {
  // Over a floor of many tiles the near tiles' lowest layer is often full, and the query answers
  // for it from its top without looking at each of its tiles: it must find what a fresh look
  // finds, bit for bit, on an open floor, beside a hole in it, over its edge where the board
  // ends (a floor with no walls round it, the marble also beyond it), among walls standing on
  // it (the marble beside them and in them, where a wall covers the floor under it), among walls
  // 3 mm high (the marble over them too, in reach of their tops and of the floor, the deeper of
  // the two upward contacts kept), resting on it, in flight, in it.
  Maze walled = bench::generatedMaze(6, false);
  Maze mazed = bench::generatedMaze(6);
  Maze low(mazed.axis(0), mazed.axis(1), AxisSlots(0.005, 0.003, 2));
  for (int j = 0; j < mazed.size().y(); ++j)
    for (int i = 0; i < mazed.size().x(); ++i)
      for (int k = 0; k < 2; ++k) low.setSolid({i, j, k}, mazed.solid({i, j, k}));
  Maze holed = walled;
  holed.setSolid({5, 5, 0}, false);
  Maze bare(AxisSlots(0.005, 0.0221, 9), AxisSlots(0.005, 0.02325, 9), AxisSlots(0.005, 0.012, 2));
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 9; ++i) bare.setSolid({i, j, 0}, true);
  const double r = 0.006, margin = 1e-7;
  std::mt19937 random(5);
  const auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * std::generate_canonical<double, 53>(random);
  };
  for (const Maze* maze : {&walled, &holed, &bare, &mazed, &low}) {
    GridFrame frame;
    frame.rotation = Eigen::AngleAxisd(0.05, Vec3(2, -1, 0).normalized()).toRotationMatrix();
    frame.grid_pivot = maze->pivot();
    frame.angular_velocity = Vec3(-0.1, 0.4, 0);
    NearTiles kept;
    kept.slack = 0.5 * r;
    const double top = maze->floorTop();
    Vec3 grid(maze->axis(0).centre(5), maze->axis(1).centre(5), top + r);
    int full_bottom = 0, with_walls = 0, contacts_seen = 0;
    for (int n = 0; n < 20000; ++n) {
      const Vec3 move(uniform(-2e-3, 2e-3), uniform(-2e-3, 2e-3), uniform(-1e-3, 1e-3));
      grid = (grid + move).cwiseMax(Vec3(-2 * r, -2 * r, top - 0.5 * r));
      grid =
          grid.cwiseMin(Vec3(maze->extent().x() + 2 * r, maze->extent().y() + 2 * r, top + 2 * r));
      if (n % 3 == 0) grid.z() = top + r;  // resting on the floor, exactly
      // On the seam between floor tiles nearest to it (the walk stays free to wander).
      const auto seam = [&](int axis) {
        const AxisSlots& slots = maze->axis(axis);
        const int i = slots.slotAt(grid[axis]);
        const double lower = slots.lower(i), upper = slots.upper(i);
        grid[axis] = grid[axis] - lower < upper - grid[axis] ? lower : upper;
      };
      if (n % 7 == 0) seam(0);
      if (n % 11 == 0) seam(1);
      const Vec3 centre = frame.toWorld(grid);
      kept.skin = uniform(0, r);
      std::vector<Contact> with_kept, fresh;
      findContacts(*maze, frame, centre, r, margin, &with_kept, &kept);
      findContacts(*maze, frame, centre, r, margin, &fresh);
      full_bottom += kept.full_bottom_layer;
      with_walls += kept.full_bottom_layer && kept.layers.size() > 1;
      ASSERT_TRUE(sameContacts(with_kept, fresh)) << "at " << grid.transpose();
      contacts_seen += static_cast<int>(fresh.size());
    }
    // A fifth of the queries or more with a full bottom layer (beside the hole and over the
    // board's edge it is not), and half of them touching the floor.
    EXPECT_GT(full_bottom, 4000) << "maze "
                                 << (maze == &walled  ? "walled"
                                     : maze == &holed ? "holed"
                                     : maze == &bare  ? "bare"
                                     : maze == &mazed ? "mazed"
                                                      : "low");
    EXPECT_GT(contacts_seen, 10000);
    // Among the walls, most with walls near: the layer above the floor looked at tile by tile.
    if (maze == &mazed || maze == &low) {
      EXPECT_GT(with_walls, 10000);
    }
  }
}

TEST(SweepSphere, AFastMarbleNeverPassesAThinWall) {
  Maze maze(AxisSlots(0.005, 0.02, 11), AxisSlots(0.005, 0.02, 5), AxisSlots::uniform(0.01, 1));
  maze.setSolid({6, 2, 0}, true);  // a 5 mm thin slot, x from 0.075 to 0.08
  SweepHit hit;
  // 100 m/s over 1 ms: 10 cm in one step, straight through the wall's place.
  ASSERT_TRUE(sweepStraight(maze, {0.01, 0.0275, 0.005}, {0.1, 0, 0}, 0.005, &hit));
  EXPECT_NEAR(0.01 + 0.1 * hit.fraction, 0.075 - 0.005, 1e-12);
  EXPECT_EQ(hit.contact.normal, Vec3(-1, 0, 0));
  EXPECT_EQ(hit.contact.tile, Index3(6, 2, 0));
}

TEST(TimeOfImpact, SaysWhyItFoundNothing) {
  Maze maze(AxisSlots(0.005, 0.02, 11), AxisSlots(0.005, 0.02, 5), AxisSlots::uniform(0.01, 1));
  maze.setSolid({6, 2, 0}, true);  // a wall across the path, x from 0.075 to 0.08
  const auto state = [&](const Vec3& from, const Vec3& path) {
    Sweep sweep;
    sweep.from = from;
    sweep.path = path;
    sweep.radius = 0.005;
    sweep.margin = 1e-9;
    SweepHit hit;
    return timeOfImpact(maze, GridFrame(), sweep, &hit);
  };
  EXPECT_EQ(state({0.01, 0.0275, 0.005}, {0.1, 0, 0}), ImpactState::Hit);
  EXPECT_EQ(state({0.01, 0.0275, 0.005}, {0.03, 0, 0}), ImpactState::Separated);  // short of it
  EXPECT_EQ(state({0.01, 0.0275, 1.0}, {0.1, 0, 0}), ImpactState::OffGrid);       // a metre above
  EXPECT_EQ(state({0.01, 0.0275, 0.005}, {0, 0, 0}), ImpactState::Still);
  // 2 mm from the wall's face, 3 mm inside it: the overlap is findContacts' to resolve.
  EXPECT_EQ(state({0.073, 0.0275, 0.005}, {-0.03, 0, 0}), ImpactState::Overlapped);
  EXPECT_EQ(state({0.073, 0.0275, 0.005}, {0.001, 0, 0}), ImpactState::Overlapped);
  // Two million radii in one sweep: more pieces than a walk takes.
  EXPECT_EQ(state({0.01, 0.0275, 0.005}, {1e4, 0, 0}), ImpactState::GaveUp);
}

TEST(SweepSphere, RollingOverSeamsOfASunkenFloorHitsNothing) {
  Maze maze(AxisSlots(0.005, 0.02, 41), AxisSlots::uniform(0.02, 3), AxisSlots::uniform(0.01, 1));
  for (int i = 0; i < 41; ++i) maze.setSolid({i, 1, 0}, true);
  SweepHit hit;
  // 1 nm below resting height, across twenty seams.
  EXPECT_FALSE(sweepStraight(maze, {0.01, 0.03, 0.016 - 1e-9}, {0.4, 0, 0}, 0.006, &hit));
  // A tile standing 1 mm proud of the floor is hit, on its top edge.
  Maze step_up(AxisSlots(0.005, 0.02, 41), AxisSlots::uniform(0.02, 3), AxisSlots(0.01, 0.001, 2));
  for (int i = 0; i < 41; ++i) step_up.setSolid({i, 1, 0}, true);
  step_up.setSolid({20, 1, 1}, true);
  ASSERT_TRUE(sweepStraight(step_up, {0.01, 0.03, 0.016}, {0.4, 0, 0}, 0.006, &hit));
  EXPECT_EQ(hit.contact.tile, Index3(20, 1, 1));
}

TEST(TimeOfImpact, ABentPathMeetsAnEdgeWhereItsDistanceFirstReachesTheRadius) {
  // A falling arc past a post's top edge: the first s where the distance from the box reaches
  // the radius, found by bisection of that distance, is the time of impact.
  Maze maze(AxisSlots::uniform(0.01, 5), AxisSlots::uniform(0.01, 5), AxisSlots::uniform(0.01, 3));
  maze.setSolid({2, 2, 0}, true);  // one box [0.02, 0.03]^2 x [0, 0.01]
  Sweep sweep;
  sweep.from = {0.0, 0.025, 0.018};
  sweep.path = {0.04, 0, 0.0};
  sweep.bend = {0, 0, -0.02};
  sweep.radius = 0.005;
  sweep.margin = 1e-9;
  SweepHit hit;
  ASSERT_EQ(timeOfImpact(maze, GridFrame(), sweep, &hit), ImpactState::Hit);
  const Box box = maze.tileBox({2, 2, 0});
  const auto gap = [&](double s) {
    const Vec3 c = sweep.at(s);
    return (c - c.cwiseMax(box.lower).cwiseMin(box.upper)).norm() - sweep.radius;
  };
  double lo = 0, hi = 0;
  while (gap(hi) > 0) {  // the first of 10^4 samples that touches, then bisection
    lo = hi;
    hi += 1e-4;
  }
  while (hi - lo > 1e-15) (gap(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  EXPECT_NEAR(hit.fraction, hi, 1e-12);
  // It touched the top edge along y (x = 0.02, z = 0.01), not a face.
  EXPECT_NEAR(hit.contact.grid_point.x(), 0.02, 1e-15);
  EXPECT_NEAR(hit.contact.grid_point.z(), 0.01, 1e-15);
  EXPECT_LT(hit.contact.normal.x(), -0.1);  // from the edge towards the centre: up and back
  EXPECT_GT(hit.contact.normal.z(), 0.1);
}

TEST(SweepClearOf, LetsByAPathBesideAWallThatItDoesNotMeet) {
  // A marble rolling on the floor 50 um from the face of a wall, half a millimetre a stretch:
  // the wall lies within its reach (radius plus path), so only the walk's own tests before any
  // root can tell whether the path meets it. Along the wall it does not, nor bent away from it
  // (its sag, 25 um, well inside the gap); towards it it does, and bent towards it by more than
  // the gap. And touching the wall, leaving it: a path that bends back onto it within the
  // stretch (a small bounce) meets it again, one that bends back too little does not.
  Maze maze(AxisSlots::uniform(0.01, 10), AxisSlots::uniform(0.01, 10),
            AxisSlots::uniform(0.01, 3));
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) maze.setSolid({i, j, 0}, true);
  for (int j = 2; j < 8; ++j) maze.setSolid({6, j, 1}, true);  // its face at x = 0.06
  const double r = 0.004;
  struct Case {
    double gap;  // from the wall's face, m
    Vec3 path, bend;
    bool meets;
  };
  for (const Case& c : {Case{50e-6, {0, 5e-4, 0}, Vec3::Zero(), false},    // along the wall
                        Case{50e-6, {0, -5e-4, 0}, {-1e-4, 0, 0}, false},  // bent away from it
                        Case{50e-6, {5e-4, 0, 0}, Vec3::Zero(), true},     // towards it
                        Case{50e-6, {0, 5e-4, 0}, {2e-4, 0, 0}, true},     // bent onto it
                        Case{0, {-2e-4, 0, 0}, {3e-4, 0, 0}, true},        // back by s = 2/3
                        Case{0, {-2e-4, 0, 0}, {0.5e-4, 0, 0}, false}}) {  // not back
    Sweep sweep;
    sweep.radius = r;
    sweep.margin = 1e-7;
    sweep.from = Vec3(0.06 - r - c.gap, 0.045, 0.01 + r);
    sweep.path = c.path;
    sweep.bend = c.bend;
    sweep.keepTo(Vec3::UnitZ(), Vec3(0, 0, 0.01));
    std::vector<Contact> contacts;
    NearTiles near;
    near.skin = r;
    findContacts(maze, GridFrame(), sweep.from, r, sweep.margin, &contacts, &near);
    EXPECT_EQ(contacts.size(), c.gap > 0 ? 1u : 2u);  // the floor, and the wall when touching
    SweepHit hit;
    EXPECT_EQ(timeOfImpact(maze, GridFrame(), sweep, &hit) == ImpactState::Hit, c.meets)
        << c.path.transpose();
    if (c.meets && c.gap == 0) {
      EXPECT_NEAR(hit.fraction, 2.0 / 3.0, 1e-9);
    }
    EXPECT_EQ(sweep.clearOf(near), !c.meets) << c.path.transpose();
  }
}

TEST(SweepClearOf, SaysClearOnlyWhereTheWalkFindsNoImpact) {
  // Paths up to 4 mm long, straight and bent, from 20,000 starts scattered over a generated
  // maze near the floor and the walls, some above the grid; some keep to the floor, some to the
  // face of a wall they touch, and some start up to a skin away from where the near tiles were
  // gathered: where the near tiles say a path meets nothing, the walk of the grid finds no
  // impact either. Most short paths are clear; some meet a wall, so both answers are exercised.
  const Maze maze = bench::generatedMaze(10);
  const double r = 0.006, floor_top = maze.floorTop();
  std::mt19937 random(7);
  const auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * std::generate_canonical<double, 53>(random);
  };
  int clear = 0, hits = 0;
  for (int n = 0; n < 20000; ++n) {
    const bool on_floor = n % 2 == 0;
    Sweep sweep;
    sweep.radius = r;
    sweep.margin = 1e-7;
    const double height = n % 7 == 0 ? uniform(0.01, 0.05) : uniform(0, 0.005);  // or above
    sweep.from = {uniform(0, maze.extent().x()), uniform(0, maze.extent().y()),
                  on_floor ? floor_top + r : floor_top + r + height};
    const double length = uniform(0, 0.004);
    const double angle = uniform(0, 2 * test::kPi);
    sweep.path = length * Vec3(std::cos(angle), std::sin(angle), on_floor ? 0 : uniform(-1, 1));
    if (n % 3 == 0) sweep.bend = {0, 0, on_floor ? 0 : -uniform(0, 1e-4)};
    if (on_floor) sweep.keepTo(Vec3::UnitZ(), Vec3(0, 0, floor_top));
    NearTiles near;
    near.skin = uniform(0, r);
    std::vector<Contact> contacts;
    GridFrame frame;  // the grid at the world's origin, at rest
    frame.grid_pivot = Vec3::Zero();
    findContacts(maze, frame, sweep.from, r, sweep.margin, &contacts, &near);
    for (const Contact& c : contacts)  // keep to the face of a wall it touches, as a held one
      if (n % 5 == 1 && std::abs(c.normal.z()) < 1e-12 &&
          std::abs(std::abs(c.normal.x()) + std::abs(c.normal.y()) - 1) < 1e-12) {
        sweep.path -= sweep.path.dot(c.normal) * c.normal;
        sweep.keepTo(c.normal, c.grid_point);
      }
    if (n % 4 == 3)  // started elsewhere than where the near tiles were gathered
      sweep.from += near.skin * Vec3(uniform(-1, 1), uniform(-1, 1), on_floor ? 0 : uniform(-1, 1));
    SweepHit hit;
    const bool meets = timeOfImpact(maze, frame, sweep, &hit) == ImpactState::Hit;
    hits += meets;
    if (!sweep.clearOf(near)) continue;
    ++clear;
    EXPECT_FALSE(meets) << "from " << sweep.from.transpose() << " path " << sweep.path.transpose()
                        << " skin " << near.skin;
  }
  EXPECT_GT(clear, 6000);  // 7978 today (3363 with distances from the start alone)
  EXPECT_GT(hits, 500);
}

}  // namespace
}  // namespace marble_maze
