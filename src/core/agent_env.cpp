#include "marble_maze/agent_env.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <mutex>
#include <thread>

namespace marble_maze {

RouteField::RouteField(const Maze& maze, double radius) : planner_(maze, radius) {
  columns_x_ = maze.size().x();
  const int columns = maze.size().x() * maze.size().y();
  waypoint_.assign(static_cast<std::size_t>(columns), Vec2::Zero());
  rest_.assign(static_cast<std::size_t>(columns), -1.0);
  for (int j = 0; j < maze.size().y(); ++j)
    for (int i = 0; i < maze.size().x(); ++i) {
      const Maze::Cell cell{i, j};
      if (!planner_.open(cell)) continue;
      const Route route = planner_.plan(planner_.centre(cell));
      if (!route.found()) continue;
      // The waypoint after the column's own centre (the goal's, when it is the last), and the
      // route's length from there.
      const std::size_t next = std::min<std::size_t>(1, route.waypoints.size() - 1);
      double rest = 0;
      for (std::size_t k = next + 1; k < route.waypoints.size(); ++k)
        rest += (route.waypoints[k] - route.waypoints[k - 1]).norm();
      const std::size_t index = indexOf(cell);
      waypoint_[index] = route.waypoints[next];
      rest_[index] = rest;
      routed_.push_back(planner_.centre(cell));
    }
}

std::size_t RouteField::indexOf(const Maze::Cell& c) const {
  return static_cast<std::size_t>(c.j) * static_cast<std::size_t>(columns_x_) +
         static_cast<std::size_t>(c.i);
}

bool RouteField::next(const Vec2& at, Vec2* waypoint, double* rest) const {
  const Maze::Cell c = planner_.columnAt(at);
  if (c.i < 0 || c.j < 0 || c.i >= columns_x_ || indexOf(c) >= rest_.size()) return false;
  const std::size_t index = indexOf(c);
  if (rest_[index] < 0) return false;
  *waypoint = waypoint_[index];
  *rest = rest_[index];
  return true;
}

double RouteField::distance(const Vec2& at) const {
  Vec2 waypoint;
  double rest = 0;
  if (!next(at, &waypoint, &rest)) return std::numeric_limits<double>::infinity();
  return (waypoint - at).norm() + rest;
}

namespace {

/// Throws ParamError unless each key of `ranges` can be drawn per episode from its range over
/// `params`: a number, within the key's bounds at both ends, and not the step, which the control
/// period fixes.
void checkRanges(const std::vector<AgentEnvOptions::Range>& ranges, const Params& params) {
  for (const AgentEnvOptions::Range& r : ranges) {
    if (r.key == "step")
      throw ParamError(
          "step: cannot be drawn per episode: the step divides the control period "
          "(set it with sets)");
    const std::vector<ParamInfo>& infos = paramInfos();
    const auto info = std::find_if(infos.begin(), infos.end(),
                                   [&](const ParamInfo& i) { return i.key == r.key; });
    if (info != infos.end() &&
        (info->type == ParamInfo::Type::Whole || info->type == ParamInfo::Type::Choice))
      throw ParamError(r.key + ": cannot be drawn from a range: it takes " +
                       (info->type == ParamInfo::Type::Whole ? "whole numbers" : "names") +
                       " (set it with sets)");
    if (!(r.low <= r.high))
      throw ParamError(r.key + ": expected a range [low, high] with low <= high, got [" +
                       exactText(r.low) + ", " + exactText(r.high) + "]");
    Params probe = params;
    setParam(probe, r.key, exactText(r.low));
    setParam(probe, r.key, exactText(r.high));
    validate(probe);
  }
}

}  // namespace

Scene agentScene(const AgentEnvOptions& options) {
  if (!(options.control_rate > 0 && options.control_rate <= 1e4))
    throw ParamError("control_rate: expected a rate in (0, 10000] Hz");
  Scene scene = loadScene(options.maze);
  overrideParam(&scene, "preset", options.preset);
  for (const auto& [key, value] : options.sets) overrideParam(&scene, key, value);
  // Exact control periods: the step shortened to the largest that divides the period (55 Hz at
  // 5 ms: four steps of 4.545 ms), so that every action acts for exactly its period.
  const double period = 1.0 / options.control_rate;
  scene.params.step = stepDividing(period, scene.params.step);
  validate(scene.params);
  const std::string why =
      whyTooMuchWork(period / scene.params.step, scene.params,
                     "control_rate: " + exactText(options.control_rate) + " Hz at a step of " +
                         exactText(scene.params.step) + " s makes");
  if (!why.empty()) throw ParamError(why);
  // At least one period (infinite: never truncated).
  if (!(std::round(options.max_episode_seconds * options.control_rate) >= 1))
    throw ParamError("max_episode_seconds: expected at least one control period (" +
                     exactText(1 / options.control_rate) + " s), got " +
                     exactText(options.max_episode_seconds));
  for (const auto& [key, weight] :
       {std::pair<const char*, double>{"progress_reward", options.progress_reward},
        {"hole_penalty", options.hole_penalty},
        {"goal_bonus", options.goal_bonus}})
    if (!std::isfinite(weight))
      throw ParamError(std::string(key) + ": expected a finite number, got " + exactText(weight));
  checkRanges(options.ranges, scene.params);
  return scene;
}

AgentEnv::AgentEnv(const Scene& scene, std::shared_ptr<const RouteField> route,
                   const AgentEnvOptions& options)
    : session_(scene),
      route_(std::move(route)),
      options_(options),
      nominal_(scene.params),
      seed_(options.seed),
      sensors_(options.sensors, options.control_rate) {
  steps_per_period_ = static_cast<int>(std::llround(1.0 / options.control_rate / step()));
  const double periods = std::round(options.max_episode_seconds * options.control_rate);
  max_periods_ = periods < 0x1p62 ? static_cast<std::int64_t>(periods)
                                  : std::numeric_limits<std::int64_t>::max();
  reset();
}

void AgentEnv::seed(std::uint64_t seed, std::uint64_t index) {
  seed_ = seed;
  index_ = index;
  episode_ = 0;
}

void AgentEnv::reset() {
  random_ = splitMix64(splitMix64(splitMix64(seed_) ^ index_) ^ episode_++);
  const auto uniform = [this] { return uniformDraw(&random_); };
  if (!options_.ranges.empty()) {
    Params params = nominal_;
    for (const AgentEnvOptions::Range& r : options_.ranges)
      setParam(params, r.key, exactText(r.low + (r.high - r.low) * uniform()));
    session_.setParams(params);
  }
  session_.reset();
  if (options_.random_start && !route_->routedCentres().empty()) {
    const std::vector<Vec2>& open = route_->routedCentres();
    const auto pick = static_cast<std::size_t>(uniform() * static_cast<double>(open.size()));
    const Vec2 at = open[std::min(open.size() - 1, pick)];
    const double radius = session_.simulation().params().marble_radius;
    session_.place(Vec3(at.x(), at.y(), radius), Vec3::Zero(), Vec3::Zero());
  }
  periods_ = 0;
  target_roll_ = target_pitch_ = 0;
  const Vec3 p = session_.simulation().marbleInBoard();
  distance_ = route_->distance(Vec2(p.x(), p.y()));
  seen_ = sensors_.restart(truth(), &random_);
}

namespace {

/// The first of `count` values that is NaN, or -1. An action beyond [-1, 1], an infinite one
/// too, is clipped to it; a NaN gives no direction to tilt, and is refused.
int firstNaN(const double* values, int count) {
  for (int k = 0; k < count; ++k)
    if (std::isnan(values[k])) return k;
  return -1;
}

const char* const kNotANumber = ": expected a number (clipped to [-1, 1]), got nan";

}  // namespace

AgentEnv::Outcome AgentEnv::step(const double* action) {
  if (const int k = firstNaN(action, kActionSize); k >= 0)
    throw ParamError("action[" + std::to_string(k) + "]" + kNotANumber);
  const Params& params = session_.simulation().params();
  const double a0 = std::clamp(action[0], -1.0, 1.0);
  const double a1 = std::clamp(action[1], -1.0, 1.0);
  TiltCommand command;
  command.step = session_.steps();
  if (options_.tilt_rates) {
    command.kind = TiltCommand::Kind::Rates;
    command.roll = a0 * params.tilt_rate_limit;
    command.pitch = a1 * params.tilt_rate_limit;
  } else {
    command.roll = target_roll_ = a0 * params.tilt_limit;
    command.pitch = target_pitch_ = a1 * params.tilt_limit;
  }
  session_.command(command);
  session_.run(static_cast<std::uint64_t>(steps_per_period_));
  ++periods_;

  Outcome outcome;
  const Vec3 p = session_.simulation().marbleInBoard();
  const double distance = route_->distance(Vec2(p.x(), p.y()));
  // Progress along the route (none counted across a column with no route, whose distance is
  // infinite, nor out of one).
  if (std::isfinite(distance) && std::isfinite(distance_))
    outcome.reward += options_.progress_reward * (distance_ - distance);
  distance_ = distance;
  switch (session_.simulation().marble().phase) {
    case MarblePhase::Free:
      break;
    case MarblePhase::AtGoal:
      outcome.reward += options_.goal_bonus;
      outcome.terminated = true;
      break;
    case MarblePhase::InHole:
    case MarblePhase::OffBoard:
      outcome.reward -= options_.hole_penalty;
      outcome.terminated = true;
      break;
  }
  outcome.truncated = !outcome.terminated && periods_ >= max_periods_;
  seen_ = sensors_.see(truth(), &random_);
  return outcome;
}

Sensors::Frame AgentEnv::truth() const {
  const Simulation& sim = session_.simulation();
  const Vec3 p = sim.marbleInBoard();
  const Vec3 v = sim.board().rotation().transpose() * sim.marble().velocity;
  Vec2 waypoint(p.x(), p.y());
  double rest = 0;
  route_->next(Vec2(p.x(), p.y()), &waypoint, &rest);
  return {p.x(), p.y(), v.x(), v.y(), waypoint.x() - p.x(), waypoint.y() - p.y()};
}

void AgentEnv::observe(float* out) const {
  const Board& board = session_.simulation().board();
  const double values[kObservationSize] = {seen_[0],
                                           seen_[1],
                                           seen_[2],
                                           seen_[3],
                                           sensors_.measuredTilt(board.roll()),
                                           sensors_.measuredTilt(board.pitch()),
                                           target_roll_,
                                           target_pitch_,
                                           seen_[4],
                                           seen_[5]};
  for (int k = 0; k < kObservationSize; ++k) out[k] = static_cast<float>(values[k]);
}

/// The threads beside the caller's, which wait between calls: a step of many environments costs
/// no thread's start. Each thread steps the environments of its own slice one at a time, and
/// then takes what is left of the others': a period costs some environments several times what
/// it costs others, and with fixed slices every thread would wait for the one that drew them. An
/// environment mostly stays with one thread, and so in its core's cache.
class VectorAgentEnv::Pool {
 public:
  explicit Pool(int helpers) : slices_(static_cast<std::size_t>(helpers) + 1) {
    for (int t = 1; t <= helpers; ++t) threads_.emplace_back([this, t] { serve(t); });
  }
  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
      generation_.fetch_add(1);
    }
    start_.notify_all();
    for (std::thread& t : threads_) t.join();
  }
  /// `work(thread, i)` for every i below n, spread over the threads (0 the caller's), then
  /// `finished(thread)` in each.
  void run(int n, const std::function<void(int, int)>& work,
           const std::function<void(int)>& finished) {
    work_ = &work;
    finished_ = &finished;
    n_ = n;
    for (int s = 0; s < slices(); ++s) slices_[static_cast<std::size_t>(s)].next.store(begin(s));
    pending_.store(static_cast<int>(threads_.size()));
    {
      std::lock_guard<std::mutex> lock(mutex_);
      generation_.fetch_add(1);
    }
    start_.notify_all();
    take(0);
    spinWhile([this] { return pending_.load() != 0; });
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return pending_.load() == 0; });
  }

 private:
  int slices() const { return static_cast<int>(slices_.size()); }
  int begin(int slice) const { return n_ * slice / slices(); }

  /// Steps the environments left in the thread's own slice, then in each of the others.
  void take(int own) {
    for (int k = 0; k < slices(); ++k) {
      const int s = (own + k) % slices();
      std::atomic<int>& next = slices_[static_cast<std::size_t>(s)].next;
      const int end = begin(s + 1);
      for (int i = next.fetch_add(1); i < end; i = next.fetch_add(1)) (*work_)(own, i);
    }
    (*finished_)(own);
  }

  /// A call's work is some tens of microseconds, and waking a sleeping thread can take as long:
  /// so each side first watches `busy` for up to a millisecond, without yielding: a thread
  /// that yields on a loaded machine gives its core away for a whole time slice, milliseconds,
  /// each time, where one that sleeps is woken at once.
  template <typename Busy>
  static void spinWhile(const Busy& busy) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(1);
    while (busy() && std::chrono::steady_clock::now() < until) {
    }
  }

  void serve(int slice) {
    std::uint64_t seen = 0;
    for (;;) {
      spinWhile([&] { return generation_.load() == seen; });
      {
        std::unique_lock<std::mutex> lock(mutex_);
        start_.wait(lock, [&] { return generation_.load() != seen; });
        if (stop_) return;
        seen = generation_.load();
      }
      take(slice);
      if (pending_.fetch_sub(1) == 1) {
        std::lock_guard<std::mutex> lock(mutex_);
        done_.notify_one();
      }
    }
  }

  /// The next environment of a slice to be taken, on a cache line of its own.
  struct alignas(64) Slice {
    std::atomic<int> next{0};
  };

  std::vector<Slice> slices_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(int, int)>* work_ = nullptr;
  const std::function<void(int)>* finished_ = nullptr;
  int n_ = 0;
  std::atomic<int> pending_{0};
  std::atomic<std::uint64_t> generation_{0};
  bool stop_ = false;
};

VectorAgentEnv::VectorAgentEnv(int num_envs, const AgentEnvOptions& options, int num_threads) {
  if (num_envs < 1) throw ParamError("num_envs: expected at least 1");
  if (num_threads < 1) throw ParamError("num_threads: expected at least 1");
  const Scene scene = agentScene(options);
  const auto route = std::make_shared<const RouteField>(scene.maze, scene.params.marble_radius);
  for (int i = 0; i < num_envs; ++i) {
    envs_.push_back(std::make_unique<AgentEnv>(scene, route, options));
    envs_.back()->seed(options.seed, static_cast<std::uint64_t>(i));
  }
  // (Each environment is stepped by one thread alone and touches nothing shared: the same
  // episodes whatever the split.)
  const int helpers = std::min(num_threads, num_envs) - 1;
  if (helpers > 0) pool_ = std::make_unique<Pool>(helpers);
  results_.resize(static_cast<std::size_t>(helpers) + 1);
  for (Results& r : results_) r.rows.resize(envs_.size());
}

VectorAgentEnv::~VectorAgentEnv() = default;

const AgentEnv& VectorAgentEnv::env(int i) const {
  if (i < 0 || i >= size())
    throw std::out_of_range("environment " + std::to_string(i) + ": expected 0 to " +
                            std::to_string(size() - 1));
  return *envs_[static_cast<std::size_t>(i)];
}

void VectorAgentEnv::forEachEnv(const std::function<void(int, int)>& work,
                                const std::function<void(int)>& finished) {
  if (pool_) {
    pool_->run(size(), work, finished);
  } else {
    for (int i = 0; i < size(); ++i) work(0, i);
    finished(0);
  }
}

namespace {

/// Where environment i's row of `size` values starts in an array of them.
std::ptrdiff_t slot(int i, int size) {
  return static_cast<std::ptrdiff_t>(i) * size;
}

}  // namespace

void VectorAgentEnv::resetEach(float* obs, const std::function<void(AgentEnv&, int)>& reseed) {
  forEachEnv(
      [&](int, int i) {
        AgentEnv& env = *envs_[static_cast<std::size_t>(i)];
        reseed(env, i);
        env.reset();
        env.observe(obs + slot(i, AgentEnv::kObservationSize));
      },
      [](int) {});
}

void VectorAgentEnv::reset(float* obs, const std::uint64_t* seed) {
  resetEach(obs, [&](AgentEnv& env, int i) {
    if (seed) env.seed(*seed, static_cast<std::uint64_t>(i));
  });
}

void VectorAgentEnv::reset(float* obs, const std::vector<std::optional<std::uint64_t>>& seeds) {
  if (seeds.size() != envs_.size())
    throw ParamError("seed: expected " + std::to_string(size()) +
                     " seeds, one an environment, got " + std::to_string(seeds.size()));
  resetEach(obs, [&](AgentEnv& env, int i) {
    if (const auto& seed = seeds[static_cast<std::size_t>(i)]) env.seed(*seed, 0);
  });
}

void VectorAgentEnv::step(const double* actions, float* obs, double* rewards,
                          std::uint8_t* terminated, std::uint8_t* truncated, float* final_obs) {
  // (Checked before any environment moves: a refused call changes nothing.)
  if (const int k = firstNaN(actions, size() * AgentEnv::kActionSize); k >= 0)
    throw ParamError("actions[" + std::to_string(k / AgentEnv::kActionSize) + "][" +
                     std::to_string(k % AgentEnv::kActionSize) + "]" + kNotANumber);
  // Each thread keeps its environments' results apart, and writes them out once it has stepped
  // them all: written one environment at a time, the flags of environments of both threads, on
  // one cache line, would pass between the cores for every one.
  forEachEnv(
      [&](int thread, int i) {
        AgentEnv& env = *envs_[static_cast<std::size_t>(i)];
        Results& results = results_[static_cast<std::size_t>(thread)];
        Results::Row& row = results.rows[static_cast<std::size_t>(results.count++)];
        row.env = i;
        row.outcome = env.step(actions + slot(i, AgentEnv::kActionSize));
        env.observe(row.obs.data());
        if (row.outcome.terminated || row.outcome.truncated) {
          row.final_obs = row.obs;
          env.reset();
          env.observe(row.obs.data());
        }
      },
      [&](int thread) {
        Results& results = results_[static_cast<std::size_t>(thread)];
        for (int k = 0; k < results.count; ++k) {
          const Results::Row& row = results.rows[static_cast<std::size_t>(k)];
          const int i = row.env;
          rewards[i] = row.outcome.reward;
          terminated[i] = row.outcome.terminated;
          truncated[i] = row.outcome.truncated;
          std::copy(row.obs.begin(), row.obs.end(), obs + slot(i, AgentEnv::kObservationSize));
          if (row.outcome.terminated || row.outcome.truncated)
            std::copy(row.final_obs.begin(), row.final_obs.end(),
                      final_obs + slot(i, AgentEnv::kObservationSize));
        }
        results.count = 0;
      });
}

}  // namespace marble_maze
