// Maze files: YAML with a grid of slot widths, a plan (or a stack of plans) drawn in characters
// and optional physics. The format is described in doc/maze_format.md.
#include "marble_maze/maze_file.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

#include "marble_maze/embedded_mazes.h"
#include "marble_maze/in_quotes.h"
#include "marble_maze/maze_generator.h"
#include "marble_maze/text_file.h"

namespace marble_maze {
namespace {

constexpr char kPlanChars[] = "+-|# .OSG";

bool isWall(char c) {
  return c == '+' || c == '-' || c == '|' || c == '#';
}

std::string prefix(const std::string& source, int line, int column) {
  if (line <= 0) return source + ": ";
  return source + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ";
}

/// A 1-based position in the file.
struct Location {
  int line = 1;
  int column = 1;
};

/// One key of a YAML mapping with its nodes, kept to report errors at the key or at the value.
struct Entry {
  std::string key;
  YAML::Node key_node;
  YAML::Node value;
};

const Entry* findEntry(const std::vector<Entry>& entries, const std::string& key) {
  for (const auto& e : entries)
    if (e.key == key) return &e;
  return nullptr;
}

std::string joined(const std::vector<std::string>& words) {
  std::string result;
  for (const auto& w : words) result += (result.empty() ? "" : ", ") + w;
  return result;
}

/// What a node is, for "found ..." in messages.
std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return inQuotes(node.Scalar());
    case YAML::NodeType::Sequence:
      return "a list of " + std::to_string(node.size()) + (node.size() == 1 ? " item" : " items");
    case YAML::NodeType::Map:
      return "a mapping";
    default:
      return "nothing";
  }
}

/// A plan character for a message; tabs and UTF-8 sequences would otherwise print badly.
std::string describeChar(const std::string& row, std::size_t at) {
  const unsigned char c = static_cast<unsigned char>(row[at]);
  if (c == '\t') return "'\\t' (a tab)";
  if (c < 0x80) return std::string("'") + row[at] + "'";
  std::size_t end = at + 1;
  while (end < row.size() && (static_cast<unsigned char>(row[end]) & 0xC0) == 0x80) ++end;
  return "'" + row.substr(at, end - at) + "'";
}

/// The default maze name: the file name without directory and extension.
std::string nameFromSource(const std::string& source) {
  const std::string embedded = "<embedded:";
  if (source.rfind(embedded, 0) == 0 && source.back() == '>')
    return source.substr(embedded.size(), source.size() - embedded.size() - 1);
  std::string name = source.substr(source.find_last_of('/') + 1);
  const auto dot = name.find_last_of('.');
  if (dot != std::string::npos && dot > 0) name.erase(dot);
  return name;
}

/// One plan as drawn: rows[0] is the top line of the drawing, the largest y slot.
struct Plan {
  YAML::Node node;
  std::vector<std::string> rows;
  std::string what;  ///< "layout" or "layers plan K", for messages
};

/// Where the start and goals were drawn, to report duplicates and a start above a hole.
struct Markers {
  bool has_start = false;
  Maze::Cell start;
  Location start_at;
  std::vector<Maze::Cell> goals;
};

/// Parses one maze file. It keeps the raw text because yaml-cpp marks a block scalar only at its
/// '|' indicator, and an error about one character of a plan must point at that character.
class SceneParser {
 public:
  SceneParser(const std::string& text, const std::string& source, const Params& defaults)
      : text_(text), source_(source), defaults_(defaults) {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines_.push_back(line);
    }
  }

  Scene parse() {
    try {
      return parseRoot(load());
    } catch (const YAML::Exception& e) {
      // A YAML error the checks did not foresee (a bad alias, say): still report where it is.
      fail(at(e.mark), e.msg);
    }
  }

 private:
  Scene parseRoot(const YAML::Node& root) const {
    const auto top =
        readMapping(root, "at the top level", {"name", "grid", "layout", "layers", "physics"});
    Scene scene;
    Location start;
    scene.maze = readMaze(root, top, &start);
    scene.start_in_file = prefix(source_, start.line, start.column);
    scene.start_in_file.resize(scene.start_in_file.size() - 2);  // without prefix's ": "
    scene.maze.setName(readName(findEntry(top, "name")));
    scene.params = readPhysics(findEntry(top, "physics"), &scene.physics_keys);
    return scene;
  }

  [[noreturn]] void fail(const Location& at, const std::string& message) const {
    throw MazeFileError(source_, at.line, at.column, message);
  }

  Location at(const YAML::Mark& mark) const {
    if (mark.is_null()) return {};
    return {mark.line + 1, mark.column + 1};
  }
  Location at(const YAML::Node& node) const { return at(node.Mark()); }

  YAML::Node load() const {
    YAML::Node root;
    try {
      root = YAML::Load(text_);
    } catch (const YAML::Exception& e) {
      fail(at(e.mark), "YAML syntax error: " + e.msg);
    }
    if (root.IsNull())
      fail({}, "the file is empty; expected a mapping with the keys grid and layout (or layers)");
    return root;
  }

  /// The keys of a mapping in file order; an unknown or repeated key is an error, since yaml-cpp
  /// would otherwise keep a typo silently or let a repeated key hide the first.
  std::vector<Entry> readMapping(const YAML::Node& map, const std::string& what,
                                 const std::vector<std::string>& allowed) const {
    if (!map.IsMap())
      fail(at(map), "expected a mapping of keys " + what + ", found " + describe(map));
    std::vector<Entry> entries;
    for (const auto& item : map) {
      if (!item.first.IsScalar()) fail(at(item.first), "expected a key name " + what);
      const std::string key = item.first.Scalar();
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), key) == allowed.end())
        fail(at(item.first),
             "unknown key " + inQuotes(key) + " " + what + "; expected one of: " + joined(allowed));
      if (const Entry* first = findEntry(entries, key))
        fail(at(item.first), "key " + inQuotes(key) + " given twice " + what + " (first at line " +
                                 std::to_string(at(first->key_node).line) + ")");
      entries.push_back({key, item.first, item.second});
    }
    return entries;
  }

  std::string readName(const Entry* name) const {
    if (!name) return nameFromSource(source_);
    if (!name->value.IsScalar() || name->value.Scalar().empty())
      fail(at(name->key_node), "name: expected a text, found " + describe(name->value));
    return name->value.Scalar();
  }

  // --- grid -------------------------------------------------------------------------------

  double readWidth(const YAML::Node& node, const std::string& what) const {
    double width = 0;
    try {
      if (!node.IsScalar()) throw YAML::BadConversion(node.Mark());
      width = node.as<double>();
    } catch (const YAML::BadConversion&) {
      fail(at(node), what + ": expected a width in metres, found " + describe(node));
    }
    if (!std::isfinite(width) || width <= 0)
      fail(at(node),
           what + ": expected a positive width in metres, found " + inQuotes(node.Scalar()));
    // Slots from a micrometre to a kilometre: beyond, a board's extent loses the precision a
    // marble on it needs, or overflows.
    if (width < 1e-6 || width > 1e3)
      fail(at(node), what + ": " + node.Scalar() + " m is out of range [1e-06, 1000] m");
    return width;
  }

  /// The thin and wide slot widths of one axis: [thin, wide] or one number for a uniform axis.
  std::pair<double, double> readWidths(const Entry& axis) const {
    const std::string what = "grid." + axis.key;
    if (!axis.value.IsSequence()) {
      if (!axis.value.IsScalar())
        fail(at(axis.key_node),
             what + ": expected a width or a list [thin, wide], found " + describe(axis.value));
      const double width = readWidth(axis.value, what);
      return {width, width};
    }
    if (axis.value.size() != 2)
      fail(at(axis.value), what + ": expected a list of 2 widths [thin, wide], found a list of " +
                               std::to_string(axis.value.size()));
    return {readWidth(axis.value[0], what + "[0] (thin)"),
            readWidth(axis.value[1], what + "[1] (wide)")};
  }

  /// The slot widths of x, y and z, indexed by axis.
  std::vector<std::pair<double, double>> readGrid(const YAML::Node& root,
                                                  const std::vector<Entry>& top) const {
    const Entry* grid = findEntry(top, "grid");
    if (!grid)
      fail(at(root), "missing key 'grid' (the slot widths in metres per axis: x, y and z)");
    const auto axes = readMapping(grid->value, "in grid", {"x", "y", "z"});
    std::vector<std::pair<double, double>> widths;
    for (const char* name : {"x", "y", "z"}) {
      const Entry* axis = findEntry(axes, name);
      if (!axis)
        fail(at(grid->key_node), std::string("grid: missing '") + name +
                                     "' (a width, or a list [thin, wide] of widths in metres)");
      widths.push_back(readWidths(*axis));
    }
    return widths;
  }

  // --- plans ------------------------------------------------------------------------------

  /// Whether the scalar is a literal block ('|'), whose rows are suffixes of the raw lines below
  /// its indicator; only then can a character be located exactly.
  bool isLiteralBlock(const YAML::Node& node) const { return rawCharAt(node.Mark()) == '|'; }

  /// The character of the raw text at a mark: a scalar's first one tells its style.
  char rawCharAt(const YAML::Mark& mark) const {
    if (mark.is_null() || mark.line >= static_cast<int>(lines_.size())) return '\0';
    const std::string& line = lines_[mark.line];
    return mark.column < static_cast<int>(line.size()) ? line[mark.column] : '\0';
  }

  /// Where character `column` of plan row `row` is in the file (the scalar's start if unknown).
  Location charAt(const Plan& plan, int row, std::size_t column) const {
    if (!isLiteralBlock(plan.node)) return at(plan.node);
    const std::size_t line_index = plan.node.Mark().line + 1 + row;
    const std::string& text = plan.rows[row];
    if (line_index >= lines_.size()) return at(plan.node);
    const std::string& line = lines_[line_index];
    if (line.size() < text.size() ||
        line.compare(line.size() - text.size(), text.size(), text) != 0)
      return at(plan.node);
    // Count characters, not bytes, so that the column matches an editor's on a UTF-8 line.
    const std::size_t byte = line.size() - text.size() + column;
    const auto chars = std::count_if(line.begin(), line.begin() + byte, [](char c) {
      return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    });
    return {static_cast<int>(line_index) + 1, static_cast<int>(chars) + 1};
  }

  /// `owner` is the key or list the plan belongs to: yaml-cpp marks a missing value at whatever
  /// follows it, so a missing plan is reported at its owner instead.
  Plan readPlan(const YAML::Node& node, const std::string& what, const YAML::Node& owner) const {
    if (!node.IsScalar())
      fail(at(node.IsNull() ? owner : node),
           what + ": expected a plan drawn in a block '|', found " + describe(node));
    if (rawCharAt(node.Mark()) == '>')
      fail(at(node), what + ": expected a literal block '|', found a folded block '>' (it would " +
                         "join the rows into one line)");
    Plan plan{node, {}, what};
    std::istringstream in(node.Scalar());
    for (std::string row; std::getline(in, row);) plan.rows.push_back(row);
    // Characters first: a non-ASCII one would otherwise show up as a confusing row length.
    checkPlanChars(plan);
    checkPlanShape(plan);
    return plan;
  }

  void checkPlanChars(const Plan& plan) const {
    for (std::size_t r = 0; r < plan.rows.size(); ++r) {
      const std::string& row = plan.rows[r];
      for (std::size_t i = 0; i < row.size(); ++i)
        if (row[i] == '\0' || !std::strchr(kPlanChars, row[i])) failUnknownChar(plan, r, i);
    }
  }

  void checkPlanShape(const Plan& plan) const {
    if (plan.rows.empty())
      fail(at(plan.node), plan.what + ": expected at least one row, found none");
    const std::size_t width = plan.rows[0].size();
    if (width == 0) fail(charAt(plan, 0, 0), plan.what + ": the first row is empty");
    for (std::size_t r = 1; r < plan.rows.size(); ++r) {
      if (plan.rows[r].size() == width) continue;
      fail(charAt(plan, r, 0), plan.what + ": expected every row " + std::to_string(width) +
                                   " characters long like the first, found " +
                                   std::to_string(plan.rows[r].size()) +
                                   " (use '.' for open floor at the end of a row, since editors " +
                                   "may strip trailing spaces)");
    }
  }

  int planRows(const Plan& plan) const { return static_cast<int>(plan.rows.size()); }
  int planColumns(const Plan& plan) const { return static_cast<int>(plan.rows[0].size()); }

  [[noreturn]] void failUnknownChar(const Plan& plan, int row, int column) const {
    fail(charAt(plan, row, column), "unknown character " + describeChar(plan.rows[row], column) +
                                        " in " + plan.what + "; expected one of '" + kPlanChars +
                                        "'");
  }

  void markStart(Markers& markers, const Plan& plan, int row, int column,
                 const Maze::Cell& cell) const {
    const Location here = charAt(plan, row, column);
    if (markers.has_start)
      fail(here, "a second start 'S' (the first is at line " +
                     std::to_string(markers.start_at.line) + ", column " +
                     std::to_string(markers.start_at.column) + "); expected exactly one");
    markers.has_start = true;
    markers.start = cell;
    markers.start_at = here;
  }

  void markGoal(Markers& markers, const Maze::Cell& cell) const {
    // A column marked in several plans is still one goal.
    if (std::find(markers.goals.begin(), markers.goals.end(), cell) == markers.goals.end())
      markers.goals.push_back(cell);
  }

  /// The 2-D form: layer 0 is the floor, layer 1 the walls.
  void fillLayout(Maze& maze, const Plan& plan, Markers& markers) const {
    for (int r = 0; r < planRows(plan); ++r) {
      const int j = planRows(plan) - 1 - r;
      for (int i = 0; i < planColumns(plan); ++i) {
        const char c = plan.rows[r][i];
        if (isWall(c)) {
          maze.setSolid({i, j, 0}, true);
          maze.setSolid({i, j, 1}, true);
        } else if (c != 'O') {  // open floor, start or goal
          maze.setSolid({i, j, 0}, true);
          if (c == 'S') markStart(markers, plan, r, i, {i, j});
          if (c == 'G') markGoal(markers, {i, j});
        }
      }
    }
  }

  /// One plan of the 3-D form, at layer k.
  void fillLayer(Maze& maze, const Plan& plan, int k, Markers& markers) const {
    for (int r = 0; r < planRows(plan); ++r) {
      const int j = planRows(plan) - 1 - r;
      for (int i = 0; i < planColumns(plan); ++i) {
        const char c = plan.rows[r][i];
        if (isWall(c)) {
          maze.setSolid({i, j, k}, true);
        } else if (c == 'O' && k > 0) {
          fail(charAt(plan, r, i), plan.what + ": 'O' (a hole) belongs in plan 0, the floor; " +
                                       "use ' ' or '.' for an empty tile above it");
        } else if ((c == 'S' || c == 'G') && k == 0) {
          fail(charAt(plan, r, i), plan.what + ": '" + c + "' marks a column above the floor; " +
                                       "put it in plan 1 or higher");
        } else if (c == 'S') {
          markStart(markers, plan, r, i, {i, j});
        } else if (c == 'G') {
          markGoal(markers, {i, j});
        }  // else empty: ' ', '.' or a hole 'O' in plan 0
      }
    }
  }

  std::vector<Plan> readLayers(const Entry& layers) const {
    if (!layers.value.IsSequence() || layers.value.size() == 0)
      fail(at(layers.key_node), "layers: expected a list of plans, bottom (the floor) first, " +
                                    std::string("found ") + describe(layers.value));
    std::vector<Plan> plans;
    for (std::size_t k = 0; k < layers.value.size(); ++k) {
      plans.push_back(readPlan(layers.value[k], "layers plan " + std::to_string(k), layers.value));
      const Plan& first = plans.front();
      // YAML's aliases (*name) let a small file repeat one plan a million times: the count of
      // tiles is bounded as a file of the largest size drawn without them would bound it.
      const double tiles = static_cast<double>(planRows(first)) * planColumns(first) *
                           static_cast<double>(layers.value.size());
      if (k == 0 && tiles > static_cast<double>(kMostTextFileBytes)) {
        std::ostringstream count;
        count << std::fixed << std::setprecision(0) << tiles;
        fail(at(layers.key_node),
             "layers: " + std::to_string(layers.value.size()) + " plans of " +
                 std::to_string(planColumns(first)) + " x " + std::to_string(planRows(first)) +
                 " characters are " + count.str() + " tiles; at most " +
                 std::to_string(kMostTextFileBytes) + " (as many as a file of the largest size, " +
                 std::to_string(kMostTextFileBytes >> 20) + " MB, draws)");
      }
      const Plan& plan = plans.back();
      if (planRows(plan) != planRows(first) || planColumns(plan) != planColumns(first))
        fail(at(plan.node),
             plan.what + ": expected " + std::to_string(planColumns(first)) + " x " +
                 std::to_string(planRows(first)) + " characters like plan 0, found " +
                 std::to_string(planColumns(plan)) + " x " + std::to_string(planRows(plan)));
    }
    return plans;
  }

  Maze makeMaze(const std::vector<std::pair<double, double>>& widths, const Plan& plan,
                int layers) const {
    return Maze(AxisSlots(widths[0].first, widths[0].second, planColumns(plan)),
                AxisSlots(widths[1].first, widths[1].second, planRows(plan)),
                AxisSlots(widths[2].first, widths[2].second, layers));
  }

  Maze readMaze(const YAML::Node& root, const std::vector<Entry>& top, Location* start) const {
    const auto widths = readGrid(root, top);
    const Entry* layout = findEntry(top, "layout");
    const Entry* layers = findEntry(top, "layers");
    if (layout && layers) {
      const Entry* second = at(layout->key_node).line > at(layers->key_node).line ? layout : layers;
      fail(at(second->key_node), "both 'layout' and 'layers' given; expected exactly one");
    }
    if (!layout && !layers)
      fail(at(root), "missing key 'layout' (a plan) or 'layers' (a list of plans, bottom first)");
    Markers markers;
    Maze maze;
    if (layout) {
      const Plan plan = readPlan(layout->value, "layout", layout->key_node);
      maze = makeMaze(widths, plan, 2);
      fillLayout(maze, plan, markers);
    } else {
      const auto plans = readLayers(*layers);
      maze = makeMaze(widths, plans[0], static_cast<int>(plans.size()));
      for (std::size_t k = 0; k < plans.size(); ++k)
        fillLayer(maze, plans[k], static_cast<int>(k), markers);
    }
    placeMarkers(maze, markers, layout ? *layout : *layers);
    *start = markers.start_at;
    return maze;
  }

  void placeMarkers(Maze& maze, const Markers& markers, const Entry& plans) const {
    if (!markers.has_start)
      fail(at(plans.key_node), plans.key + ": no start 'S' found; expected exactly one");
    if (markers.goals.empty())
      fail(at(plans.key_node), plans.key + ": no goal 'G' found; expected at least one");
    // Both lie inside the grid by construction: they were read from the plans that sized it.
    if (maze.isHole(markers.start))
      fail(markers.start_at, "the start 'S' is above a hole: expected a floor tile '#' under it");
    maze.setStart(markers.start);
    for (const auto& goal : markers.goals) maze.addGoal(goal);
  }

  // --- physics ----------------------------------------------------------------------------

  /// A physics value as setParam's text; a list [x, y, z] becomes "x,y,z".
  std::string physicsText(const Entry& entry) const {
    if (entry.value.IsScalar()) return entry.value.Scalar();
    if (entry.value.IsSequence()) {
      std::string text;
      for (const auto& item : entry.value) {
        if (!item.IsScalar())
          fail(at(item),
               "physics." + entry.key + ": expected numbers in the list, found " + describe(item));
        text += (text.empty() ? "" : ",") + item.Scalar();
      }
      return text;
    }
    fail(at(entry.key_node),
         "physics." + entry.key + ": expected a value, found " + describe(entry.value));
  }

  static bool isParamKey(const std::string& key) {
    const auto& infos = paramInfos();
    return std::any_of(infos.begin(), infos.end(),
                       [&](const ParamInfo& info) { return info.key == key; });
  }

  Params readPhysics(const Entry* physics, std::vector<Scene::FileKey>* keys) const {
    Params params = defaults_;
    std::map<std::string, Location> where;  // each key's value in the file
    if (physics && !physics->value.IsNull()) {
      for (const auto& entry : readMapping(physics->value, "in physics", {})) {
        const std::string text = physicsText(entry);
        try {
          setParam(params, entry.key, text);
          where[entry.key] = at(entry.value);
          keys->push_back({entry.key, where[entry.key].line, where[entry.key].column});
        } catch (const ParamError& e) {
          fail(isParamKey(entry.key) ? at(entry.value) : at(entry.key_node), e.what());
        }
      }
    }
    try {
      validate(params);
    } catch (const ParamError& e) {
      // A rule over several keys names the one it faults first ("bounce_threshold: ..."): the
      // error points at it where the file sets it, else at the section.
      const std::string what = e.what();
      const auto named = where.find(what.substr(0, what.find(':')));
      fail(named != where.end() ? named->second
           : physics            ? at(physics->key_node)
                                : Location{},
           what);
    }
    return params;
  }

  const std::string& text_;
  const std::string& source_;
  const Params& defaults_;
  std::vector<std::string> lines_;
};

}  // namespace

void overrideParam(Scene* scene, const std::string& key, const std::string& value) {
  setParam(scene->params, key, value);
  auto& keys = scene->physics_keys;
  keys.erase(std::remove_if(keys.begin(), keys.end(),
                            [&](const Scene::FileKey& k) { return k.key == key; }),
             keys.end());
}

void replaceParams(Scene* scene, const Params& params) {
  scene->params = params;
  scene->physics_keys.clear();
}

const Scene::FileKey* findFileKey(const Scene& scene, const std::string& key) {
  for (const Scene::FileKey& k : scene.physics_keys)
    if (k.key == key) return &k;
  return nullptr;
}

MazeFileError::MazeFileError(const std::string& source, int line, int column,
                             const std::string& message)
    : std::runtime_error(prefix(source, line, column) + message),
      source(source),
      line(line),
      column(column) {}

Scene parseScene(const std::string& text, const std::string& source, const Params& defaults) {
  Scene scene = SceneParser(text, source, defaults).parse();
  scene.text = text;
  scene.source = source;
  return scene;
}

Scene loadSceneFile(const std::string& path, const Params& defaults) {
  std::string text;
  try {
    text = readTextFile(path);
  } catch (const TextFileError& e) {
    throw MazeFileError(path, 0, 0, e.reason);
  }
  return parseScene(text, path, defaults);
}

std::vector<std::string> embeddedSceneNames() {
  std::vector<std::string> names;
  for (const auto& maze : embeddedMazes()) names.push_back(maze.first);
  return names;
}

std::string embeddedSceneList() {
  return joined(embeddedSceneNames());
}

Scene loadScene(const std::string& name_or_path, const Params& defaults) {
  if (isGeneratedMazeName(name_or_path))
    return parseScene(generatedMazeText(name_or_path), "<" + name_or_path + ">", defaults);
  for (const auto& maze : embeddedMazes())
    if (maze.first == name_or_path)
      return parseScene(maze.second, "<embedded:" + maze.first + ">", defaults);
  std::error_code error;
  if (!std::filesystem::exists(name_or_path, error) && !error) {  // (else the read says why)
    // A misspelt built-in name reads as a missing file: say what was looked for.
    throw MazeFileError(
        name_or_path, 0, 0,
        "neither a built-in maze (" + embeddedSceneList() + ") nor a file that exists");
  }
  return loadSceneFile(name_or_path, defaults);
}

}  // namespace marble_maze
