// The speed-accuracy trade, measured: every combination of model, integrator, step and substeps
// on a fixed set of scenarios, each with its cost (CPU time per simulated second on one core) and
// its error against a closed form or against a reference run. Writes CSV rows; make tradeoff
// turns them into doc/tradeoff.md and doc/tradeoff.png (scripts/plot_tradeoff.py).
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "marble_maze/maze_file.h"
#include "marble_maze/simulation.h"
#include "marble_maze/tilt_schedule.h"

namespace mm = marble_maze;

namespace {

constexpr double kRadius = 0.006;
constexpr double kGravity = 9.81;
constexpr double kMissing = 1.0;  // the relative error of a result that never came: 100%

/// One setting of the trade.
struct Option {
  mm::Model model;
  mm::IntegratorKind integrator;
  double step;
  int substeps;

  mm::Params params() const {
    mm::Params p;
    p.model = model;
    p.integrator = integrator;
    p.step = step;
    p.substeps = substeps;
    return p;
  }
};

// --- Scenes and runs -----------------------------------------------------------------------------

/// A floor of nx x ny square tiles on one 5 mm slab.
mm::Maze floorOf(int nx, int ny, double tile) {
  mm::Maze maze(mm::AxisSlots::uniform(tile, nx), mm::AxisSlots::uniform(tile, ny),
                mm::AxisSlots::uniform(0.005, 2));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) maze.setSolid({i, j, 0}, true);
  maze.setStart({nx / 2, ny / 2});
  return maze;
}

mm::Params placedAt(mm::Params p, const mm::Vec3& position, const mm::Vec3& velocity) {
  p.has_start_position = true;
  p.start_position = position;
  p.start_velocity = velocity;
  return p;
}

void run(mm::Simulation* sim, double seconds) {
  const auto steps = std::lround(seconds / sim->params().step);
  for (long i = 0; i < steps; ++i) sim->step();
}

double relative(double value, double exact) {
  return std::abs(value - exact) / std::abs(exact);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

/// The classic maze with its holes filled and no goal, so that the marble plays for the whole
/// run, rolling round its start corridor into walls and posts as the board circles (below).
mm::Scene playScene(const mm::Params& params) {
  const mm::Maze classic = mm::loadScene("classic").maze;
  mm::Maze maze(classic.axis(0), classic.axis(1), classic.axis(2));
  for (int k = 0; k < classic.size().z(); ++k)
    for (int j = 0; j < classic.size().y(); ++j)
      for (int i = 0; i < classic.size().x(); ++i)
        maze.setSolid({i, j, k}, classic.solid({i, j, k}) || k == 0);
  maze.setStart(classic.start());
  maze.setName("classic, holes filled, no goal");
  mm::Params p = params;
  p.restitution = 0.5;
  p.friction = 0.3;
  return {maze, p};
}

/// The board's tilt circling at 0.1 rad, one turn in 2 s from the angle `phase` (rad), given
/// every 0.25 s from a level start (a servo follows it): the marble is still rolling at 0.15 m/s
/// after 5 s and meets about seven walls a second. A controller reads it every kCommandPeriod
/// (below).
mm::TiltSchedule playProgramme(double phase) {
  std::string text;
  for (int k = 0; k <= 24; ++k) {
    const double t = 0.25 * k, angle = 3.14159265358979323846 * t + phase;
    text += number(t) + "," + (k == 0 ? "0" : number(0.1 * std::sin(angle))) + "," +
            (k == 0 ? "0" : number(0.1 * std::cos(angle))) + "\n";
  }
  return mm::TiltSchedule::parse(text, "the play programme");
}

// The play: 5 s from each of --starts phases of the programme, the marble's position taken at
// every whole second. Play is chaotic (a micrometre decides whether a slow impact bounces): an
// error at one instant of one run swings by two orders of magnitude from phase to phase, so the
// error is a statistic over all of them.
constexpr double kPlaySeconds = 5;

/// One run of play: where the marble is at each whole second, and when the first five impacts
/// came.
struct Play {
  std::vector<mm::Vec3> positions;
  std::vector<double> impacts;
  double cpu_seconds = 0;
};

double cpuNow() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The play's controller sends the programme's tilt at 50 Hz, about the real game's rate, at the
// same instants whatever the step (every step measured divides 20 ms): every option plays the
// same commands, and the play error is the physics' alone. (Sampled at each step's end instead,
// a longer step led the board by half a step: an error of order the step, which one substep
// happened to cancel and more substeps did not.)
constexpr double kCommandPeriod = 0.02;  // s

Play play(const mm::Params& params, double phase) {
  const mm::Scene scene = playScene(params);
  mm::Simulation sim(scene);
  const mm::TiltSchedule programme = playProgramme(phase);
  Play result;
  const auto steps = std::lround(kPlaySeconds / params.step);
  const auto second = std::lround(1.0 / params.step);
  const double start = cpuNow();
  for (long n = 1; n <= steps; ++n) {
    const double now = static_cast<double>(n - 1) * params.step;  // the step's start
    const auto tilt = programme.at(std::floor(now / kCommandPeriod + 1e-9) * kCommandPeriod);
    sim.setTargetTilt(tilt.roll, tilt.pitch);
    sim.step();
    for (const mm::Event& e : sim.events())
      if (e.kind == mm::EventKind::Collision && result.impacts.size() < 5)
        result.impacts.push_back(e.time);
    if (n % second == 0) result.positions.push_back(sim.marbleInBoard());
  }
  result.cpu_seconds = cpuNow() - start;
  return result;
}

/// The value below which a share q of the values lie (the nearest rank).
double quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  return values[std::max<std::size_t>(rank, 1) - 1];
}

// --- Closed forms --------------------------------------------------------------------------------

/// Rolling (5/7 g sin) or sliding (g sin) down a 10 degree incline from rest for 1 s.
double inclineError(const Option& o) {
  const double theta = 10 * 3.14159265358979323846 / 180;
  mm::Params p = placedAt(o.params(), {-0.95, 0, kRadius}, mm::Vec3::Zero());
  p.initial_pitch = theta;
  mm::Simulation sim({floorOf(200, 10, 0.01), p});
  const mm::Vec3 start = sim.marble().position;
  run(&sim, 1.0);
  const double a = (o.model == mm::Model::Rolling ? 5.0 / 7.0 : 1.0) * kGravity * std::sin(theta);
  return relative((sim.marble().position - start).norm(), 0.5 * a);
}

/// The first five apexes of a marble dropped from 5 cm (e = 0.7): h0 e^2k. Each is the height
/// its energy reaches, taken just after the bounce (the energy is taken where the integrator's
/// velocity belongs).
double bounceError(const Option& o) {
  const double h0 = 0.05, e = 0.7;
  mm::Params p = placedAt(o.params(), {0, 0, kRadius + h0}, mm::Vec3::Zero());
  p.restitution = e;
  mm::Simulation sim({floorOf(10, 10, 0.01), p});
  const double weight = p.marbleMass() * kGravity;
  std::vector<double> apexes(5, -1.0);
  int bounces = 0;
  while (bounces < 5 && sim.time() < 5) {
    sim.step();
    bounces += static_cast<int>(sim.events().size());
    if (!sim.events().empty() && bounces <= 5)
      apexes[bounces - 1] = sim.energy() / weight - kRadius;
  }
  double worst = 0;
  for (int k = 1; k <= 5; ++k)
    worst = std::max(
        worst, apexes[k - 1] < 0 ? kMissing : relative(apexes[k - 1], h0 * std::pow(e, 2 * k)));
  return worst;
}

/// A marble launched sliding at 0.7 m/s on a level floor rolls on at 5/7 of that.
double slipToRollError(const Option& o) {
  mm::Simulation sim(
      {floorOf(200, 10, 0.01), placedAt(o.params(), {-0.9, 0, kRadius}, {0.7, 0, 0})});
  run(&sim, 1.0);
  return relative(sim.marble().velocity.norm(), 0.5);
}

/// Rolling at 0.5 m/s against rolling resistance 0.01: v = 0.5 - (5/7) c_rr g t after 2 s.
double rollingResistanceError(const Option& o) {
  mm::Params p = placedAt(o.params(), {-0.9, 0, kRadius}, {0.5, 0, 0});
  p.rolling_resistance = 0.01;
  mm::Simulation sim({floorOf(200, 10, 0.01), p});
  sim.placeMarble(p.start_position, p.start_velocity, {0, 0.5 / kRadius, 0});
  run(&sim, 2.0);
  return relative(sim.marble().velocity.x(), 0.5 - 5.0 / 7.0 * 0.01 * kGravity * 2.0);
}

/// Quadratic air drag on a level floor from 20 m/s for 1 s: v = v0 / (1 + c k v0 t), with
/// k = rho C_d A / (2 m), c = 1 sliding and 5/7 rolling (the spin takes its share).
double dragError(const Option& o) {
  mm::Params p = placedAt(o.params(), {-24, 0, kRadius}, {20, 0, 0});
  p.drag_coefficient = 0.47;
  mm::Simulation sim({floorOf(50, 3, 1.0), p});
  if (o.model == mm::Model::Rolling)
    sim.placeMarble(p.start_position, {20, 0, 0}, {0, 20 / kRadius, 0});
  run(&sim, 1.0);
  const double k = p.air_density * p.drag_coefficient * 3.14159265358979323846 * kRadius * kRadius /
                   (2 * p.marbleMass());
  const double c = o.model == mm::Model::Rolling ? 5.0 / 7.0 : 1.0;
  return relative(sim.marble().velocity.x(), 20 / (1 + c * k * 20));
}

/// A marble from rest on a board pitching from level at 0.5 rad/s, 0.3 m from the pivot, for
/// 1 s: x'' = c (w^2 x + g sin(w t)) along the board (c = 1 sliding, 5/7 rolling), so with
/// k = w sqrt(c), x = x0 cosh(k t) + B sinh(k t) + D sin(w t), D = -c g / (w^2 + k^2),
/// B = -D w / k. The error is relative to the distance it moves along the board.
double turningBoardError(const Option& o) {
  const double w = 0.5, x0 = 0.3;
  mm::Params p = placedAt(o.params(), {x0, 0, kRadius}, {w * kRadius, 0, -w * x0});
  p.tilt_rate_limit = 0;
  p.tilt_limit = 1.0;
  mm::Simulation sim({floorOf(500, 10, 0.01), p});
  if (o.model == mm::Model::Rolling) sim.placeMarble(p.start_position, p.start_velocity, {0, w, 0});
  sim.setTiltRate(0, w);
  run(&sim, 1.0);
  const double c = o.model == mm::Model::Rolling ? 5.0 / 7.0 : 1.0, k = w * std::sqrt(c);
  const double d = -c * kGravity / (w * w + k * k), b = -d * w / k, t = sim.time();
  const double x = x0 * std::cosh(k * t) + b * std::sinh(k * t) + d * std::sin(w * t);
  return relative(sim.marbleInBoard().x() - x0, x - x0);
}

// --- The sweep -----------------------------------------------------------------------------------

const char* name(mm::Model m) {
  return m == mm::Model::Rolling ? "rolling" : "smooth";
}

const char* name(mm::IntegratorKind i) {
  switch (i) {
    case mm::IntegratorKind::SemiImplicitEuler:
      return "semi_implicit_euler";
    case mm::IntegratorKind::VelocityVerlet:
      return "velocity_verlet";
    case mm::IntegratorKind::RungeKutta4:
      return "rk4";
  }
  return "?";
}

/// The largest difference between the impact times of a run and the reference's (a missing
/// impact counts as the whole run).
double impactTimeError(const std::vector<double>& run, const std::vector<double>& reference) {
  double worst = 0;
  for (std::size_t k = 0; k < reference.size(); ++k)
    worst = std::max(worst, k < run.size() ? std::abs(run[k] - reference[k]) : kPlaySeconds);
  return worst;
}

/// The name of the preset that is this option, or "".
std::string presetOf(const Option& o) {
  for (const char* preset : {"realtime", "fast", "accurate"}) {
    mm::Params p;
    mm::setParam(p, "preset", preset);
    if (p.model == o.model && p.integrator == o.integrator && p.step == o.step &&
        p.substeps == o.substeps)
      return preset;
  }
  return "";
}

int usage() {
  std::cerr << "Usage: marble_maze_tradeoff [--quick] [--starts N] [--out FILE]\n"
               "  Measures cost and error for every model, integrator, step (1e-4 to 2e-2 s)\n"
               "  and substeps (1, 4, 16), and writes them as CSV (default: standard output).\n"
               "  --starts N: the play from N phases of its programme (default 16); the cost\n"
               "  is the median over them, the play error the median and 90th percentile.\n"
               "  --quick: two steps, one substep count, 4 starts (a check, in seconds).\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  int starts = 16;
  std::string out_path;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--quick") {
      quick = true;
      starts = 4;
    } else if (flag == "--starts" && i + 1 < argc) {
      starts = std::max(1, std::atoi(argv[++i]));
    } else if (flag == "--out" && i + 1 < argc) {
      out_path = argv[++i];
    } else {
      return usage();
    }
  }
  const std::vector<double> steps =
      quick ? std::vector<double>{1e-3, 1e-2}
            : std::vector<double>{1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2};
  const std::vector<int> substeps = quick ? std::vector<int>{1} : std::vector<int>{1, 4, 16};
  const mm::Model models[] = {mm::Model::Smooth, mm::Model::Rolling};
  const mm::IntegratorKind integrators[] = {mm::IntegratorKind::SemiImplicitEuler,
                                            mm::IntegratorKind::VelocityVerlet,
                                            mm::IntegratorKind::RungeKutta4};
  std::vector<Option> options;
  for (mm::Model m : models)
    for (mm::IntegratorKind i : integrators)
      for (int n : substeps)
        for (double h : steps) options.push_back({m, i, h, n});

  std::ofstream file;
  if (!out_path.empty()) {
    file.open(out_path);
    if (!file) {
      std::cerr << "marble_maze_tradeoff: cannot write '" << out_path << "'\n";
      return 1;
    }
  }
  std::ostream& out = out_path.empty() ? std::cout : file;
  out << "model,integrator,step,substeps,preset,ns_per_simulated_s,times_real_time,"
         "play_error_median_m,play_error_p90_m,play_impact_time_error_s,incline,bounce,"
         "slip_to_roll,rolling_resistance,drag,turning_board\n";

  // The reference of realistic play for each model and phase: the smallest step, the best
  // integrator.
  std::vector<double> phases;
  phases.reserve(static_cast<std::size_t>(starts));
  for (int k = 0; k < starts; ++k) phases.push_back(2 * 3.14159265358979323846 * k / starts);
  std::vector<Play> references[2];
  for (mm::Model m : models) {
    references[static_cast<int>(m)].reserve(phases.size());
    std::cerr << "reference runs (" << name(m) << ", rk4, 1e-4 s x 16, " << starts << " starts)\n";
    for (double phase : phases)
      references[static_cast<int>(m)].push_back(
          play(Option{m, mm::IntegratorKind::RungeKutta4, 1e-4, 16}.params(), phase));
  }
  int done = 0;
  for (const Option& o : options) {
    ++done;
    std::fprintf(stderr, "[%3d/%zu] %-8s %-20s step %-7g x %-2d\n", done, options.size(),
                 name(o.model), name(o.integrator), o.step, o.substeps);
    std::vector<double> costs, position_errors, impact_errors;
    costs.reserve(phases.size());
    impact_errors.reserve(phases.size());
    for (std::size_t k = 0; k < phases.size(); ++k) {
      const Play p = play(o.params(), phases[k]);
      const Play& reference = references[static_cast<int>(o.model)][k];
      costs.push_back(p.cpu_seconds / kPlaySeconds * 1e9);
      for (std::size_t i = 0; i < reference.positions.size(); ++i)
        position_errors.push_back((p.positions[i] - reference.positions[i]).norm());
      impact_errors.push_back(impactTimeError(p.impacts, reference.impacts));
    }
    const double cost = quantile(costs, 0.5);
    const bool rolling = o.model == mm::Model::Rolling;
    out << name(o.model) << ',' << name(o.integrator) << ',' << number(o.step) << ',' << o.substeps
        << ',' << presetOf(o) << ',' << number(cost) << ',' << number(1e9 / cost) << ','
        << number(quantile(position_errors, 0.5)) << ',' << number(quantile(position_errors, 0.9))
        << ',' << number(quantile(impact_errors, 0.5)) << ',' << number(inclineError(o)) << ','
        << number(bounceError(o)) << ',' << (rolling ? number(slipToRollError(o)) : "") << ','
        << (rolling ? number(rollingResistanceError(o)) : "") << ',' << number(dragError(o)) << ','
        << number(turningBoardError(o)) << std::endl;
  }
  return 0;
}
