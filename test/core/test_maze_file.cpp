// Maze files: the built-in mazes, the format's mapping to the grid, and clear errors for bad files.
#include <gtest/gtest.h>

#include <deque>
#include <string>
#include <vector>

#include "marble_maze/in_quotes.h"
#include "marble_maze/maze_file.h"
#include "marble_maze/simulation.h"

namespace marble_maze {
namespace {

// A valid grid (lines 1-4) and layout (lines 5-8) that the malformed files below build on, so
// that each of them breaks one thing at a known line.
const std::string kGrid =
    "grid:\n"
    "  x: [0.005, 0.02]\n"
    "  y: [0.005, 0.02]\n"
    "  z: [0.005, 0.012]\n";
const std::string kLayout =
    "layout: |\n"
    "  +-+-+\n"
    "  |S G|\n"
    "  +-+-+\n";

/// what() of the MazeFileError that parsing `text` as "bad.yaml" throws.
std::string errorOf(const std::string& text, const Params& defaults = Params()) {
  try {
    parseScene(text, "bad.yaml", defaults);
  } catch (const MazeFileError& e) {
    return e.what();
  }
  return "(no error)";
}

/// Whether a simulation of `scene` refuses its start (checked against the maze) with a
/// MazeFileError whose message begins with `prefix` ("bad.yaml:LINE:COLUMN: KEY: ...").
::testing::AssertionResult startRefusedWith(const Scene& scene, const std::string& prefix) {
  std::string what = "(no error)";
  try {
    Simulation sim(scene);
  } catch (const MazeFileError& e) {
    what = e.what();
  } catch (const std::exception& e) {
    what = std::string("(not a MazeFileError: ") + e.what() + ")";
  }
  if (what.rfind(prefix, 0) == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected '" << prefix << "...', got '" << what << "'";
}

/// Whether `text` fails at `location` ("bad.yaml:LINE:COLUMN:") with a message containing `phrase`.
::testing::AssertionResult failsWith(const std::string& text, const std::string& location,
                                     const std::string& phrase, const Params& defaults = Params()) {
  const std::string what = errorOf(text, defaults);
  if (what.rfind(location + " ", 0) == 0 && what.find(phrase) != std::string::npos)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "expected '" << location << " ...'" << phrase << "...', got '" << what << "'";
}

/// Whether the marble can roll from the start column to a goal column: a breadth-first search over
/// the slots of the wall layer (1), where a slot is passable if it is empty there and no hole.
bool routeExists(const Maze& maze) {
  const auto passable = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < maze.size().x() && j < maze.size().y() &&
           !maze.solid({i, j, 1}) && !maze.isHole({i, j});
  };
  std::vector<bool> seen(static_cast<std::size_t>(maze.size().x()) * maze.size().y(), false);
  std::deque<Maze::Cell> queue;
  if (!passable(maze.start().i, maze.start().j)) return false;
  queue.push_back(maze.start());
  seen[maze.start().j * maze.size().x() + maze.start().i] = true;
  while (!queue.empty()) {
    const Maze::Cell c = queue.front();
    queue.pop_front();
    if (maze.isGoal(c)) return true;
    const Maze::Cell next[] = {{c.i + 1, c.j}, {c.i - 1, c.j}, {c.i, c.j + 1}, {c.i, c.j - 1}};
    for (const auto& n : next) {
      if (!passable(n.i, n.j) || seen[n.j * maze.size().x() + n.i]) continue;
      seen[n.j * maze.size().x() + n.i] = true;
      queue.push_back(n);
    }
  }
  return false;
}

// --- the built-in mazes --------------------------------------------------------------------------

TEST(MazeFile, BuiltInMazesLoadClassicFirst) {
  const auto names = embeddedSceneNames();
  ASSERT_GE(names.size(), 2u);
  EXPECT_EQ(names[0], "classic");
  for (const auto& name : names) {
    const Scene scene = loadScene(name);
    EXPECT_EQ(scene.maze.name(), name);
  }
}

TEST(MazeFile, ClassicIsSizedLikeTheRealGame) {
  const Maze maze = loadScene("classic").maze;
  EXPECT_EQ(maze.size(), Index3(21, 17, 2));
  EXPECT_NEAR(maze.extent().x(), 0.276, 1e-9);
  EXPECT_NEAR(maze.extent().y(), 0.231, 1e-9);
  EXPECT_NEAR(maze.axis(2).thin(), 0.005, 1e-12);
  EXPECT_NEAR(maze.axis(2).wide(), 0.012, 1e-12);
}

TEST(MazeFile, ClassicHasPostsOuterWallsHolesStartAndGoal) {
  const Maze maze = loadScene("classic").maze;
  for (int j = 0; j < 17; j += 2)
    for (int i = 0; i < 21; i += 2) EXPECT_TRUE(maze.solid({i, j, 1})) << "post " << i << "," << j;
  for (int i = 0; i < 21; ++i) EXPECT_TRUE(maze.solid({i, 0, 1}) && maze.solid({i, 16, 1}));
  for (int j = 0; j < 17; ++j) EXPECT_TRUE(maze.solid({0, j, 1}) && maze.solid({20, j, 1}));

  const auto holes = maze.holes();
  EXPECT_GE(holes.size(), 4u);
  EXPECT_LE(holes.size(), 8u);
  for (const auto& h : holes) EXPECT_TRUE(h.i % 2 == 1 && h.j % 2 == 1) << h.i << "," << h.j;

  EXPECT_FALSE(maze.isHole(maze.start()));
  EXPECT_EQ(maze.goals().size(), 1u);
  // Start and goal sit near opposite corners.
  EXPECT_LT(maze.start().i, 7);
  EXPECT_GT(maze.start().j, 10);
  EXPECT_GT(maze.goals()[0].i, 14);
  EXPECT_LT(maze.goals()[0].j, 6);
}

TEST(MazeFile, ClassicHasARouteAroundTheHoles) {
  EXPECT_TRUE(routeExists(loadScene("classic").maze));
}

TEST(MazeFile, RouteSearchSeesABlockingHole) {
  // Guards the search above: it must not find a route through a hole.
  const Scene scene = parseScene(kGrid + "layout: |\n  +-+-+-+\n  |S O G|\n  +-+-+-+\n", "t");
  EXPECT_FALSE(routeExists(scene.maze));
}

TEST(MazeFile, ClassicStatesRollingPhysics) {
  const Params p = loadScene("classic").params;
  EXPECT_EQ(p.model, Model::Rolling);
  EXPECT_DOUBLE_EQ(p.restitution, 0.5);
  EXPECT_DOUBLE_EQ(p.friction, 0.3);
}

TEST(MazeFile, PrototypeRemakesTheSeedLevel) {
  const Scene scene = loadScene("prototype");
  const Maze& maze = scene.maze;
  ASSERT_EQ(maze.size(), Index3(11, 7, 5));
  EXPECT_NEAR(maze.extent().x(), 6 * 0.004 + 5 * 0.02, 1e-12);
  ASSERT_EQ(maze.holes().size(), 1u);
  EXPECT_TRUE(maze.holes()[0].i % 2 == 1 && maze.holes()[0].j % 2 == 1);
  for (int k = 1; k < 5; ++k) {
    for (int j = 0; j < 7; ++j) EXPECT_TRUE(maze.solid({0, j, k}) && maze.solid({10, j, k}));
    for (int i = 0; i < 11; ++i) EXPECT_TRUE(maze.solid({i, 6, k}));
    for (int i = 1; i < 10; ++i) EXPECT_FALSE(maze.solid({i, 0, k})) << "the -y side is open";
  }
  EXPECT_FALSE(maze.isHole(maze.start()));
  EXPECT_EQ(maze.goals().size(), 1u);
  EXPECT_EQ(scene.params.model, Model::Smooth);
  EXPECT_DOUBLE_EQ(scene.params.restitution, 0.7);
  EXPECT_DOUBLE_EQ(scene.params.friction, 0.0);
  EXPECT_DOUBLE_EQ(scene.params.marble_radius, 0.009);
}

// --- the format ----------------------------------------------------------------------------------

TEST(MazeFile, LayoutTopLineIsTheLargestY) {
  const Scene scene = parseScene(kGrid +
                                     "layout: |\n"
                                     "  +-+-+\n"   // y = 3
                                     "  |S O|\n"   // y = 2
                                     "  + +-+\n"   // y = 1
                                     "  |. G|\n",  // y = 0
                                 "t");
  const Maze& maze = scene.maze;
  ASSERT_EQ(maze.size(), Index3(5, 4, 2));
  EXPECT_EQ(maze.start(), (Maze::Cell{1, 2}));
  ASSERT_EQ(maze.goals().size(), 1u);
  EXPECT_EQ(maze.goals()[0], (Maze::Cell{3, 0}));
  // Wall characters are solid in both layers.
  EXPECT_TRUE(maze.solid({0, 3, 0}) && maze.solid({0, 3, 1}));
  EXPECT_TRUE(maze.solid({2, 1, 0}) && maze.solid({2, 1, 1}));
  // Open floor, '.', start and goal are solid at layer 0 only.
  for (const Index3& t : {Index3(1, 1, 0), Index3(1, 0, 0), Index3(1, 2, 0), Index3(3, 0, 0)}) {
    EXPECT_TRUE(maze.solid(t));
    EXPECT_FALSE(maze.solid(t + Index3(0, 0, 1)));
  }
  // 'O' leaves both layers empty: a hole.
  EXPECT_FALSE(maze.solid({3, 2, 0}) || maze.solid({3, 2, 1}));
  ASSERT_EQ(maze.holes().size(), 1u);
  EXPECT_EQ(maze.holes()[0], (Maze::Cell{3, 2}));
  EXPECT_EQ(maze.axis(0).thin(), 0.005);
  EXPECT_EQ(maze.axis(0).wide(), 0.02);
}

TEST(MazeFile, LayersStackPlansBottomFirst) {
  const Scene scene = parseScene(kGrid +
                                     "layers:\n"
                                     "  - |  # floor\n"
                                     "    ##O\n"
                                     "    ###\n"
                                     "  - |\n"
                                     "    S.#\n"
                                     "    .G#\n"
                                     "  - |\n"
                                     "    ...\n"
                                     "    ..+\n",
                                 "t");
  const Maze& maze = scene.maze;
  ASSERT_EQ(maze.size(), Index3(3, 2, 3));
  EXPECT_EQ(maze.start(), (Maze::Cell{0, 1}));
  ASSERT_EQ(maze.goals().size(), 1u);
  EXPECT_EQ(maze.goals()[0], (Maze::Cell{1, 0}));
  ASSERT_EQ(maze.holes().size(), 1u);
  EXPECT_EQ(maze.holes()[0], (Maze::Cell{2, 1}));
  int solid = 0;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) solid += maze.solid({i, j, k}) ? 1 : 0;
  EXPECT_EQ(solid, 5 + 2 + 1);
  EXPECT_FALSE(maze.solid({0, 1, 1})) << "the start marks a column; its tile is empty";
  EXPECT_TRUE(maze.solid({2, 0, 2}));
}

TEST(MazeFile, OneNumberMakesAUniformAxis) {
  const Scene scene = parseScene("grid: {x: 0.01, y: [0.005, 0.02], z: 0.004}\n" + kLayout, "t");
  EXPECT_TRUE(scene.maze.axis(0).isUniform());
  EXPECT_NEAR(scene.maze.extent().x(), 0.05, 1e-12);
  EXPECT_FALSE(scene.maze.axis(1).isUniform());
  EXPECT_NEAR(scene.maze.extent().z(), 0.008, 1e-12);
}

TEST(MazeFile, NameDefaultsToTheFileName) {
  EXPECT_EQ(parseScene(kGrid + kLayout, "some/dir/my_maze.yaml").maze.name(), "my_maze");
  EXPECT_EQ(parseScene("name: mine\n" + kGrid + kLayout, "x.yaml").maze.name(), "mine");
}

TEST(MazeFile, PhysicsOverridesTheDefaults) {
  Params defaults;
  defaults.gravity = 5.0;
  defaults.restitution = 0.1;
  const Scene scene = parseScene(kGrid + kLayout +
                                     "physics:\n"
                                     "  model: smooth\n"
                                     "  restitution: 0.9\n"
                                     "  start_position: [0.01, 0.02, 0.03]\n",
                                 "t", defaults);
  EXPECT_EQ(scene.params.model, Model::Smooth);
  EXPECT_DOUBLE_EQ(scene.params.restitution, 0.9);
  EXPECT_DOUBLE_EQ(scene.params.gravity, 5.0);
  EXPECT_TRUE(scene.params.has_start_position);
  EXPECT_DOUBLE_EQ(scene.params.start_position.y(), 0.02);
  EXPECT_DOUBLE_EQ(parseScene(kGrid + kLayout, "t", defaults).params.restitution, 0.1);
}

// --- malformed files: each error points at the culprit and says what was expected --------------

// A start_position the file sets is checked against the maze only when a simulation starts from
// it; the error still points at the value in the file, and not once the key is set over it.
TEST(MazeFileError, AStartPositionInAWallNamesItsPlaceInTheFile) {
  // (The left wall spans x = -0.0275 to -0.0225 m from the pivot.)
  const Scene scene =
      parseScene(kGrid + kLayout + "physics:\n  start_position: [-0.025, 0, 0.006]\n", "bad.yaml");
  EXPECT_TRUE(startRefusedWith(scene,
                               "bad.yaml:10:19: start_position: a marble of radius "
                               "0.006 m cannot start there: inside tile"));
  Scene over = scene;
  overrideParam(&over, "start_position", "-0.025,0,0.006");
  EXPECT_EQ(findFileKey(over, "start_position"), nullptr);
  EXPECT_THROW(Simulation{over}, ParamError);
  Scene replaced = scene;
  replaceParams(&replaced, scene.params);
  EXPECT_THROW(Simulation{replaced}, ParamError);
  // A start the maze allows is taken from the file as before.
  overrideParam(&over, "start_position", "-0.0125,0,0.006");
  EXPECT_NO_THROW(Simulation{over});
  // The file's start refused for a radius set over the file's: the radius is said.
  Scene wider =
      parseScene(kGrid + kLayout + "physics:\n  start_position: [-0.0125, 0, 0.006]\n", "bad.yaml");
  EXPECT_NO_THROW(Simulation{wider});
  overrideParam(&wider, "marble_radius", "0.009");
  EXPECT_TRUE(startRefusedWith(wider,
                               "bad.yaml:10:19: start_position: a marble of radius "
                               "0.009 m cannot start there: inside tile"));
}

// A marble_radius the file sets too wide for its start cell: the error points at the value too.
TEST(MazeFileError, AMarbleWiderThanItsStartCellNamesTheRadiusPlaceInTheFile) {
  const Scene scene =
      parseScene(kGrid + kLayout + "physics:\n  marble_radius: 0.011\n", "bad.yaml");
  EXPECT_TRUE(startRefusedWith(scene,
                               "bad.yaml:10:18: marble_radius: a marble of radius 0.011 "
                               "m does not fit the start cell (1, 1, the 'S' at "
                               "bad.yaml:7:4)"));
  // Set over the file's (a --set, a node's parameter), it is no longer the file's to answer for.
  Scene over = scene;
  overrideParam(&over, "marble_radius", "0.011");
  EXPECT_THROW(Simulation{over}, ParamError);
  overrideParam(&over, "marble_radius", "0.006");
  EXPECT_NO_THROW(Simulation{over});
}

TEST(MazeFileError, UnknownPhysicsKeyNamesTheKeyAndLine) {
  EXPECT_TRUE(failsWith(kGrid + kLayout + "physics:\n  model: smooth\n  restitutoin: 0.2\n",
                        "bad.yaml:11:3:", "'restitutoin': unknown parameter"));
}

TEST(MazeFileError, BadPhysicsValue) {
  EXPECT_TRUE(failsWith(kGrid + kLayout + "physics:\n  restitution: 2\n",
                        "bad.yaml:10:16:", "restitution: 2 is out of range"));
}

TEST(MazeFileError, PhysicsThatFailsValidationPointsAtTheKeyItNames) {
  // The rule (a threshold of at least 2 g h) is over several keys; it names bounce_threshold,
  // set on line 11, not on the section's line.
  EXPECT_TRUE(failsWith(
      kGrid + kLayout + "physics:\n  integrator: semi_implicit_euler\n  bounce_threshold: 0.001\n",
      "bad.yaml:11:21:", "bounce_threshold"));
  // A key the file does not set: the section.
  Params threshold_given;
  threshold_given.bounce_threshold_auto = false;
  threshold_given.bounce_threshold = 0.001;
  EXPECT_TRUE(failsWith(kGrid + kLayout + "physics:\n  integrator: semi_implicit_euler\n",
                        "bad.yaml:9:1:", "bounce_threshold", threshold_given));
  Params defaults;
  defaults.integrator = IntegratorKind::SemiImplicitEuler;
  defaults.bounce_threshold_auto = false;
  defaults.bounce_threshold = 0.0;
  EXPECT_TRUE(failsWith(kGrid + kLayout, "bad.yaml:1:1:", "bounce_threshold", defaults));
}

TEST(MazeFileError, YamlSyntaxError) {
  // An unclosed '[': yaml-cpp notices on the next line, and its mark is reported as it is.
  EXPECT_TRUE(failsWith("grid:\n  x: [0.005, 0.02\n  y: 0.01\n",
                        "bad.yaml:3:4:", "YAML syntax error: end of sequence flow not found"));
}

TEST(MazeFileError, EmptyFile) {
  EXPECT_TRUE(failsWith("# nothing\n", "bad.yaml:1:1:", "the file is empty"));
}

TEST(MazeFileError, UnknownTopLevelKey) {
  EXPECT_TRUE(failsWith(kGrid + kLayout + "physic:\n  model: smooth\n", "bad.yaml:9:1:",
                        "unknown key 'physic' at the top level; expected one of: name, grid"));
}

TEST(MazeFileError, RepeatedKey) {
  EXPECT_TRUE(failsWith(kGrid + kLayout + "grid: {x: 1, y: 1, z: 1}\n", "bad.yaml:9:1:",
                        "key 'grid' given twice at the top level (first at line 1)"));
}

TEST(MazeFileError, MissingGrid) {
  EXPECT_TRUE(failsWith(kLayout, "bad.yaml:1:1:", "missing key 'grid'"));
}

TEST(MazeFileError, MissingGridAxis) {
  EXPECT_TRUE(
      failsWith("grid:\n  x: 0.01\n  y: 0.01\n" + kLayout, "bad.yaml:1:1:", "grid: missing 'z'"));
}

TEST(MazeFileError, NegativeWidth) {
  EXPECT_TRUE(failsWith("grid:\n  x: [-0.005, 0.02]\n  y: 0.01\n  z: 0.01\n" + kLayout,
                        "bad.yaml:2:7:", "grid.x[0] (thin): expected a positive width"));
}

TEST(MazeFileError, WidthThatIsNotANumberNamesTheKey) {
  EXPECT_TRUE(failsWith("grid:\n  x: 0.01\n  y: wide\n  z: 0.01\n" + kLayout,
                        "bad.yaml:3:6:", "grid.y: expected a width in metres, found 'wide'"));
}

TEST(MazeFileError, GridListOfThreeNumbers) {
  EXPECT_TRUE(failsWith("grid:\n  x: 0.01\n  y: [0.005, 0.02, 0.03]\n  z: 0.01\n" + kLayout,
                        "bad.yaml:3:6:", "grid.y: expected a list of 2 widths [thin, wide]"));
}

TEST(MazeFileError, UnknownLayoutCharacterPointsAtTheCharacter) {
  EXPECT_TRUE(failsWith(kGrid + "layout: |\n  +-+-+\n  |SxG|\n  +-+-+\n", "bad.yaml:7:5:",
                        "unknown character 'x' in layout; expected one of '+-|# .OSG'"));
  // Deeper indentation, a comment after '|' and Windows line ends move nothing.
  EXPECT_TRUE(
      failsWith(kGrid + "layout: |  # plan\r\n      +-+-+\r\n      |S G|\r\n      +-*-+\r\n",
                "bad.yaml:8:9:", "unknown character '*'"));
}

TEST(MazeFileError, UnknownCharacterInALaterPlanOfLayers) {
  // A UTF-8 block character counts as one column, as in an editor.
  EXPECT_TRUE(failsWith(kGrid + "layers:\n  - |\n    ##\n  - |\n    S\xE2\x96\x88\n",
                        "bad.yaml:9:6:", "unknown character '\xE2\x96\x88' in layers plan 1"));
}

TEST(MazeFileError, AliasesRepeatingAPlanBeyondTheLargestFilesTilesAreRefused) {
  // 20 KB of YAML naming one 130 x 130 floor plan (an anchor, &f) 1000 times (aliases, *f): 17
  // million tiles, more than a 16 MB file can draw without aliases. Unbounded, a million
  // aliases of a 300 x 300 plan asked for 90 GB.
  std::string text = "grid: {x: 0.01, y: 0.01, z: 0.01}\nlayers:\n  - &f\n    |\n";
  for (int j = 0; j < 130; ++j) text += "    " + std::string(130, '#') + "\n";
  for (int k = 0; k < 999; ++k) text += "  - *f\n";
  EXPECT_TRUE(failsWith(text, "bad.yaml:2:1:",
                        "layers: 1000 plans of 130 x 130 characters are 16900000 tiles; at most "
                        "16777216 (as many as a file of the largest size, 16 MB, draws)"));
}

TEST(MazeFileError, RaggedRow) {
  EXPECT_TRUE(failsWith(kGrid + "layout: |\n  +-+-+\n  |S G |\n  +-+-+\n", "bad.yaml:7:3:",
                        "layout: expected every row 5 characters long like the first, found 6"));
}

TEST(MazeFileError, FoldedBlock) {
  EXPECT_TRUE(failsWith(kGrid + "layout: >\n  +-+-+\n  |S G|\n  +-+-+\n",
                        "bad.yaml:5:9:", "expected a literal block '|', found a folded block '>'"));
}

TEST(MazeFileError, NoStart) {
  EXPECT_TRUE(failsWith(kGrid + "layout: |\n  +-+-+\n  |  G|\n  +-+-+\n",
                        "bad.yaml:5:1:", "layout: no start 'S' found; expected exactly one"));
}

TEST(MazeFileError, TwoStarts) {
  EXPECT_TRUE(failsWith(kGrid + "layout: |\n  +-+-+-+\n  |S S G|\n  +-+-+-+\n",
                        "bad.yaml:7:6:", "a second start 'S' (the first is at line 7, column 4)"));
}

TEST(MazeFileError, NoGoal) {
  EXPECT_TRUE(failsWith(kGrid + "layout: |\n  +-+-+\n  |S  |\n  +-+-+\n",
                        "bad.yaml:5:1:", "layout: no goal 'G' found; expected at least one"));
}

TEST(MazeFileError, StartInAHole) {
  EXPECT_TRUE(failsWith(kGrid + "layers:\n  - |\n    #O#\n  - |\n    .SG\n",
                        "bad.yaml:9:6:", "the start 'S' is above a hole"));
}

TEST(MazeFileError, HoleAboveTheFloorPlan) {
  EXPECT_TRUE(failsWith(kGrid + "layers:\n  - |\n    ###\n  - |\n    SOG\n",
                        "bad.yaml:9:6:", "layers plan 1: 'O' (a hole) belongs in plan 0"));
}

TEST(MazeFileError, BothLayoutAndLayers) {
  EXPECT_TRUE(failsWith(kGrid + kLayout + "layers:\n  - |\n    #\n",
                        "bad.yaml:9:1:", "both 'layout' and 'layers' given; expected exactly one"));
}

TEST(MazeFileError, NeitherLayoutNorLayers) {
  EXPECT_TRUE(failsWith(kGrid, "bad.yaml:1:1:", "missing key 'layout' (a plan) or 'layers'"));
}

TEST(MazeFileError, LayersPlansOfDifferentSizes) {
  EXPECT_TRUE(failsWith(
      kGrid + "layers:\n  - |\n    ###\n    ###\n  - |\n    SG\n    ..\n",
      "bad.yaml:9:5:", "layers plan 1: expected 3 x 2 characters like plan 0, found 2 x 2"));
}

TEST(MazeFileError, AFileThatIsNoMazeIsQuotedOnlyInPart) {
  // A file of some other kind (load_maze takes any path the node can read) is one long plain
  // scalar to YAML: its message shows the start of it and its size, never the whole of it.
  std::string other;
  for (int line = 0; line < 100; ++line)
    other += "user" + std::to_string(line) + ":x:1000:1000::/home/user:/bin/bash\n";
  other += "the last line";
  const std::string what = errorOf(other);
  EXPECT_TRUE(failsWith(other, "bad.yaml:1:1:",
                        "expected a mapping of keys at the top level, found "
                        "'user0:x:1000:1000::/home/user:/bin/bash user1:x:1000:1000::/...' ("))
      << what;
  EXPECT_NE(what.find(" bytes)"), std::string::npos) << what;
  EXPECT_EQ(what.find("the last line"), std::string::npos);
  EXPECT_LT(what.size(), 200u);
}

TEST(InQuotes, ShowsAShortTextWholeWithItsControlCharactersEscaped) {
  EXPECT_EQ(inQuotes("wide"), "'wide'");
  EXPECT_EQ(inQuotes(""), "''");
  EXPECT_EQ(inQuotes("a\tb\r\nc\x01\x7f"), "'a\\tb\\r\\nc\\x01\\x7F'");
  EXPECT_EQ(inQuotes("\xC3\xA9t\xC3\xA9"), "'\xC3\xA9t\xC3\xA9'");  // UTF-8 as it is
  const std::string sixty(kMostQuotedCharacters, 'x');
  EXPECT_EQ(inQuotes(sixty), "'" + sixty + "'");  // at the bound: whole
}

TEST(InQuotes, ClipsALongTextAtAWholeCharacterAndSaysItsSize) {
  EXPECT_EQ(inQuotes(std::string(1234, 'x')),
            "'" + std::string(kMostQuotedCharacters, 'x') + "...' (1,234 bytes)");
  // Sixty two-byte characters and more: the sixtieth is shown whole, the next not at all.
  std::string accents;
  for (int i = 0; i < 70; ++i) accents += "\xC3\xA9";
  EXPECT_EQ(inQuotes(accents),
            "'" + accents.substr(0, 2 * kMostQuotedCharacters) + "...' (140 bytes)");
  // A text of control characters shows sixty escapes, not more.
  std::string escapes;
  for (std::size_t i = 0; i < kMostQuotedCharacters; ++i) escapes += "\\n";
  EXPECT_EQ(inQuotes(std::string(100, '\n')), "'" + escapes + "...' (100 bytes)");
  EXPECT_EQ(inQuotes(std::string(1234567, 'y')).substr(2 + kMostQuotedCharacters + 3),
            " (1,234,567 bytes)");
}

TEST(MazeFileError, MissingFile) {
  const std::string path = ::testing::TempDir() + "marble_maze_no_such_maze.yaml";
  try {
    loadScene(path);
    FAIL() << "expected a MazeFileError";
  } catch (const MazeFileError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": neither a built-in maze (classic, brio, prototype) nor a file that exists");
    EXPECT_EQ(e.line, 0);
    EXPECT_EQ(e.source, path);
  }
}

}  // namespace
}  // namespace marble_maze
