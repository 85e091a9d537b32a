// Environments for learning agents: a session stepped one control period at a time, with an
// observation, a reward and episodes, and many of them stepped together. ROS-free; Python
// reaches them through marble_maze.agents (python/marble_maze/agents.py).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "marble_maze/maze_file.h"
#include "marble_maze/raster.h"
#include "marble_maze/route_planner.h"
#include "marble_maze/sensors.h"
#include "marble_maze/session.h"

namespace marble_maze {

struct AgentEnvOptions {
  std::string maze = "classic";  ///< a built-in maze or a maze file
  std::string preset = "fast";   ///< the physics' preset (params.h), before `sets`
  std::vector<std::pair<std::string, std::string>> sets;  ///< keys over the preset, as --set
  double control_rate = 55.0;                             ///< Hz: one action a period
  double max_episode_seconds = 60;  ///< then the episode is truncated (infinity: never)
  bool tilt_rates = false;          ///< actions are tilt rates (of tilt_rate_limit), not angles
  double progress_reward = 10.0;    ///< per metre nearer the goal along the route
  double hole_penalty = 1.0;        ///< on falling into a hole or off the board
  double goal_bonus = 1.0;          ///< on reaching the goal
  /// Per episode: the marble on a random open column with a route to a goal, not the start.
  bool random_start = false;
  /// Per episode: each key drawn uniformly from [low, high] (keys of the key table: marble_radius,
  /// friction, restitution, tilt_response_time, ...).
  struct Range {
    std::string key;
    double low = 0, high = 0;
  };
  std::vector<Range> ranges;
  /// What the agent's sensors make of the state: delay, camera rate, noise, tilt quantisation.
  SensorOptions sensors;
  /// Environment i's episodes are drawn from (seed, i) until a reset gives another seed.
  std::uint64_t seed = 0;
};

/// The route to the goal from every column of a maze, planned once: where the marble should go
/// next from a column and how far the goal is from there.
class RouteField {
 public:
  RouteField(const Maze& maze, double radius);
  /// The centres of the open columns from which a route leads to a goal.
  const std::vector<Vec2>& routedCentres() const { return routed_; }
  /// The next waypoint from a board-frame point (the goal's centre near the goal), and the
  /// route's length from that waypoint to the goal; false where no route leads to a goal.
  bool next(const Vec2& at, Vec2* waypoint, double* rest) const;
  /// The route's length from a board-frame point to the goal (infinite where there is none).
  double distance(const Vec2& at) const;

 private:
  std::size_t indexOf(const Maze::Cell& c) const;

  RoutePlanner planner_;
  int columns_x_ = 0;
  std::vector<Vec2> waypoint_;  // per column
  std::vector<double> rest_;    // per column; negative: no route
  std::vector<Vec2> routed_;
};

/// One environment: an episode of a session, advanced a control period per action.
class AgentEnv {
 public:
  /// The observation, in this order (SI units, board frame): the marble's x, y; its vx, vy; the
  /// board's roll, pitch; the target roll, pitch; the next waypoint's dx, dy from the marble.
  /// The marble's values and the waypoint's are the camera's frame as the sensors deliver it,
  /// the roll and pitch as the servos report them; the target is the agent's own command.
  static constexpr int kObservationSize = 10;
  static constexpr int kActionSize = 2;

  AgentEnv(const Scene& scene, std::shared_ptr<const RouteField> route,
           const AgentEnvOptions& options);

  /// Episodes from now on are drawn from `seed` (with the environment's `index`): the n-th
  /// episode after a seeding is the same whatever else runs beside it.
  void seed(std::uint64_t seed, std::uint64_t index);
  /// A new episode: the marble at rest on the start (or a random open column), the board level,
  /// the ranged keys drawn anew.
  void reset();
  struct Outcome {
    double reward = 0;
    bool terminated = false;  ///< in a hole, at the goal or off the board
    bool truncated = false;   ///< the episode's time ran out
  };
  /// One control period under `action` (roll, pitch in [-1, 1], scaled to the tilt limit, or
  /// to the tilt rate limit with tilt_rates; clipped to [-1, 1]). Throws ParamError, changing
  /// nothing, on a NaN.
  Outcome step(const double* action);
  void observe(float* out) const;
  /// The camera's values as they are, before the sensors: x, y, vx, vy, dx, dy.
  Sensors::Frame truth() const;
  /// The top-down picture of the maze (Raster's planes) with the marble where the camera's
  /// frame as the agent sees it has it.
  void draw(const Raster& raster, std::uint8_t* out) const {
    raster.draw(seen_[0], seen_[1], session_.simulation().params().marble_radius, out);
  }

  const Session& session() const { return session_; }
  /// The steps a control period takes, and their length: the preset's step shortened to the
  /// largest that divides the period exactly.
  int stepsPerPeriod() const { return steps_per_period_; }
  double step() const { return session_.simulation().params().step; }

 private:
  Session session_;
  std::shared_ptr<const RouteField> route_;
  AgentEnvOptions options_;
  int steps_per_period_ = 1;
  std::int64_t periods_ = 0;
  std::int64_t max_periods_ = 0;  // for a max_episode_seconds of infinity, the most there is
  double target_roll_ = 0, target_pitch_ = 0;
  double distance_ = 0;  // along the route, at the last period's end
  Params nominal_;       // the scene's physics, which the ranges vary about
  std::uint64_t seed_ = 0, index_ = 0, episode_ = 0;
  std::uint64_t random_ = 0;  // the episode's stream: its ranges, its start, its sensors' draws
  Sensors sensors_;
  Sensors::Frame seen_{};  // the camera's frame as the agent sees it now
};

/// The scene an environment runs: the maze with the preset and the sets over its physics, its
/// step shortened to divide the control period. Throws ParamError or MazeFileError naming what
/// is wrong in `options`: a period of more than kMostStepsPerCommand steps, an episode shorter
/// than a period, a weight of the reward that is not finite, a range that cannot be drawn from.
Scene agentScene(const AgentEnvOptions& options);

/// N environments stepped together, as Gymnasium's vector environments are: an episode that
/// ends is reset at once, its last observation kept for the caller. Each environment's episodes
/// are the same whatever the number of threads.
class VectorAgentEnv {
 public:
  VectorAgentEnv(int num_envs, const AgentEnvOptions& options, int num_threads = 1);
  int size() const { return static_cast<int>(envs_.size()); }
  /// Every environment back to a new episode; `obs` gets N x kObservationSize. With a seed,
  /// environment i's episodes are drawn from (seed, i) from now on.
  void reset(float* obs, const std::uint64_t* seed = nullptr);
  /// The same with a seed of its own for each environment that has one in `seeds` (N of them, as
  /// Gymnasium's vector environments take a list): environment i's episodes are drawn from
  /// (seeds[i], 0) from now on, those of a lone environment reset with that seed. Throws
  /// ParamError when there are not N.
  void reset(float* obs, const std::vector<std::optional<std::uint64_t>>& seeds);
  /// One control period of every environment under `actions` (N x kActionSize): fills `obs`,
  /// `rewards`, `terminated` and `truncated` (N each); where an episode ended, `final_obs` gets
  /// its last observation and `obs` the new episode's first. Throws ParamError, changing
  /// nothing, when an action holds a NaN.
  void step(const double* actions, float* obs, double* rewards, std::uint8_t* terminated,
            std::uint8_t* truncated, float* final_obs);
  /// Environment i; throws std::out_of_range naming i unless 0 <= i < size().
  const AgentEnv& env(int i) const;
  ~VectorAgentEnv();
  VectorAgentEnv(const VectorAgentEnv&) = delete;
  VectorAgentEnv& operator=(const VectorAgentEnv&) = delete;

 private:
  class Pool;
  /// What one thread's environments gave in a step, kept apart from the other threads'.
  struct alignas(64) Results {
    struct Row {
      int env = 0;
      AgentEnv::Outcome outcome;
      std::array<float, AgentEnv::kObservationSize> obs{}, final_obs{};
    };
    std::vector<Row> rows;  // room for every environment
    int count = 0;
  };
  /// Runs `work(thread, i)` for every environment i, spread over the threads (0 the caller's),
  /// then `finished(thread)` in each thread that ran.
  void forEachEnv(const std::function<void(int, int)>& work,
                  const std::function<void(int)>& finished);
  /// Every environment back to a new episode, each first given to `reseed(env, i)`.
  void resetEach(float* obs, const std::function<void(AgentEnv&, int)>& reseed);

  std::vector<std::unique_ptr<AgentEnv>> envs_;
  std::unique_ptr<Pool> pool_;    // the threads beside the caller's, waiting between calls
  std::vector<Results> results_;  // one for each thread
};

}  // namespace marble_maze
