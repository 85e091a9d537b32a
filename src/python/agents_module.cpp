// marble_maze._agents: the core's VectorAgentEnv for Python, on numpy arrays, stepped with the
// GIL released. python/marble_maze/agents.py puts Gymnasium's API over it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <string>

#include "marble_maze/agent_env.h"

namespace py = pybind11;
namespace mm = marble_maze;

namespace {

using Floats = py::array_t<float, py::array::c_style>;
using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Flags = py::array_t<bool, py::array::c_style>;

class VectorEnv {
 public:
  VectorEnv(int num_envs, const std::string& maze, const std::string& preset, double control_rate,
            double max_episode_seconds, bool tilt_rates, int num_threads, double progress_reward,
            double hole_penalty, double goal_bonus, const std::map<std::string, std::string>& sets)
      : env_(num_envs,
             options(maze, preset, control_rate, max_episode_seconds, tilt_rates, progress_reward,
                     hole_penalty, goal_bonus, sets),
             num_threads) {}

  Floats reset() {
    Floats obs({env_.size(), mm::AgentEnv::kObservationSize});
    {
      py::gil_scoped_release release;
      env_.reset(obs.mutable_data());
    }
    return obs;
  }

  py::tuple step(const Doubles& actions) {
    const int n = env_.size();
    if (actions.ndim() != 2 || actions.shape(0) != n ||
        actions.shape(1) != mm::AgentEnv::kActionSize)
      throw py::value_error("actions: expected shape (" + std::to_string(n) + ", 2), got " +
                            shapeOf(actions));
    Floats obs({n, mm::AgentEnv::kObservationSize});
    Floats final_obs({n, mm::AgentEnv::kObservationSize});
    Doubles rewards(n);
    Flags terminated(n), truncated(n);
    {
      py::gil_scoped_release release;
      env_.step(actions.data(), obs.mutable_data(), rewards.mutable_data(),
                reinterpret_cast<std::uint8_t*>(terminated.mutable_data()),
                reinterpret_cast<std::uint8_t*>(truncated.mutable_data()),
                final_obs.mutable_data());
    }
    return py::make_tuple(obs, rewards, terminated, truncated, final_obs);
  }

  int size() const { return env_.size(); }
  int stepsPerPeriod() const { return env_.env(0).stepsPerPeriod(); }
  double stepLength() const { return env_.env(0).step(); }
  double tiltLimit() const { return env_.env(0).session().simulation().params().tilt_limit; }
  double simulatedTime(int i) const { return env_.env(i).session().simulation().time(); }

 private:
  static mm::AgentEnvOptions options(const std::string& maze, const std::string& preset,
                                     double control_rate, double max_episode_seconds,
                                     bool tilt_rates, double progress_reward, double hole_penalty,
                                     double goal_bonus,
                                     const std::map<std::string, std::string>& sets) {
    mm::AgentEnvOptions o;
    o.maze = maze;
    o.preset = preset;
    o.control_rate = control_rate;
    o.max_episode_seconds = max_episode_seconds;
    o.tilt_rates = tilt_rates;
    o.progress_reward = progress_reward;
    o.hole_penalty = hole_penalty;
    o.goal_bonus = goal_bonus;
    o.sets.assign(sets.begin(), sets.end());
    return o;
  }
  static std::string shapeOf(const Doubles& a) {
    std::string s = "(";
    for (py::ssize_t k = 0; k < a.ndim(); ++k) s += (k ? ", " : "") + std::to_string(a.shape(k));
    return s + ")";
  }

  mm::VectorAgentEnv env_;
};

}  // namespace

PYBIND11_MODULE(_agents, m) {
  m.doc() = "The marble_maze core's environments for learning agents (see marble_maze.agents).";
  m.attr("OBSERVATION_SIZE") = mm::AgentEnv::kObservationSize;
  py::register_exception<mm::ParamError>(m, "ParamError", PyExc_ValueError);
  py::register_exception<mm::MazeFileError>(m, "MazeFileError", PyExc_ValueError);
  py::class_<VectorEnv>(m, "VectorEnv")
      .def(py::init<int, const std::string&, const std::string&, double, double, bool, int, double,
                    double, double, const std::map<std::string, std::string>&>(),
           py::arg("num_envs"), py::arg("maze"), py::arg("preset"), py::arg("control_rate"),
           py::arg("max_episode_seconds"), py::arg("tilt_rates"), py::arg("num_threads"),
           py::arg("progress_reward"), py::arg("hole_penalty"), py::arg("goal_bonus"),
           py::arg("sets"))
      .def("reset", &VectorEnv::reset)
      .def("step", &VectorEnv::step)
      .def_property_readonly("num_envs", &VectorEnv::size)
      .def_property_readonly("steps_per_period", &VectorEnv::stepsPerPeriod)
      .def_property_readonly("step_length", &VectorEnv::stepLength)
      .def_property_readonly("tilt_limit", &VectorEnv::tiltLimit)
      .def("simulated_time", &VectorEnv::simulatedTime);
}
