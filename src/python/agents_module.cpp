// marble_maze._agents: the core's VectorAgentEnv for Python, on numpy arrays, stepped with the
// GIL released. python/marble_maze/agents.py puts Gymnasium's API over it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "marble_maze/agent_env.h"

namespace py = pybind11;
namespace mm = marble_maze;

namespace {

using Floats = py::array_t<float, py::array::c_style>;
using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Flags = py::array_t<bool, py::array::c_style>;

class VectorEnv {
 public:
  VectorEnv(int num_envs, const mm::AgentEnvOptions& options, int num_threads)
      : env_(num_envs, options, num_threads) {}

  Floats reset(std::optional<std::uint64_t> seed) {
    Floats obs({env_.size(), mm::AgentEnv::kObservationSize});
    {
      py::gil_scoped_release release;
      env_.reset(obs.mutable_data(), seed ? &*seed : nullptr);
    }
    return obs;
  }

  /// reset with a seed, or none, for each environment.
  Floats resetEach(const std::vector<std::optional<std::uint64_t>>& seeds) {
    Floats obs({env_.size(), mm::AgentEnv::kObservationSize});
    {
      py::gil_scoped_release release;
      env_.reset(obs.mutable_data(), seeds);
    }
    return obs;
  }

  /// (obs, rewards, terminated, truncated, final_obs, ended): `ended` lists the environments
  /// whose episode ended, the only rows of `final_obs` written.
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
    // (The environments whose episode ended, listed here: finding them in numpy costs a
    // call of one environment as much as its physics.)
    py::list ended;
    for (int i = 0; i < n; ++i)
      if (terminated.data()[i] || truncated.data()[i]) ended.append(i);
    return py::make_tuple(obs, rewards, terminated, truncated, final_obs, ended);
  }

  /// The environments' pictures, uint8 [N, channels, height, width], at `pixel` metres.
  py::array_t<std::uint8_t> images(double pixel) {
    if (!raster_ || raster_pixel_ != pixel) {
      raster_ = std::make_unique<mm::Raster>(simulation(0).maze(), pixel);
      raster_pixel_ = pixel;
    }
    const py::ssize_t n = env_.size(), h = raster_->height(), w = raster_->width();
    py::array_t<std::uint8_t> out({n, py::ssize_t{mm::Raster::kChannels}, h, w});
    std::uint8_t* data = out.mutable_data();
    {
      py::gil_scoped_release release;
      for (int i = 0; i < env_.size(); ++i)
        env_.env(i).draw(*raster_, data + py::ssize_t{i} * mm::Raster::kChannels * h * w);
    }
    return out;
  }

  int size() const { return env_.size(); }
  const mm::Simulation& simulation(int i) const { return env_.env(i).session().simulation(); }
  int stepsPerPeriod() const { return env_.env(0).stepsPerPeriod(); }
  double stepLength() const { return env_.env(0).step(); }

 private:
  static std::string shapeOf(const Doubles& a) {
    std::string s = "(";
    for (py::ssize_t k = 0; k < a.ndim(); ++k) s += (k ? ", " : "") + std::to_string(a.shape(k));
    return s + ")";
  }

  mm::VectorAgentEnv env_;
  std::unique_ptr<mm::Raster> raster_;  // the last pixel size's
  double raster_pixel_ = 0;
};

}  // namespace

PYBIND11_MODULE(_agents, m) {
  m.doc() = "The marble_maze core's environments for learning agents (see marble_maze.agents).";
  m.attr("OBSERVATION_SIZE") = mm::AgentEnv::kObservationSize;
  m.attr("IMAGE_CHANNELS") = mm::Raster::kChannels;
  py::register_exception<mm::ParamError>(m, "ParamError", PyExc_ValueError);
  py::register_exception<mm::MazeFileError>(m, "MazeFileError", PyExc_ValueError);
  py::class_<mm::AgentEnvOptions::Range>(m, "Range")
      .def(py::init([](const std::string& key, double low, double high) {
             return mm::AgentEnvOptions::Range{key, low, high};
           }),
           py::arg("key"), py::arg("low"), py::arg("high"));
  py::class_<mm::SensorOptions>(m, "SensorOptions")
      .def(py::init<>())
      .def_readwrite("delay_periods", &mm::SensorOptions::delay_periods)
      .def_readwrite("delay_jitter", &mm::SensorOptions::delay_jitter)
      .def_readwrite("camera_rate", &mm::SensorOptions::camera_rate)
      .def_readwrite("position_noise", &mm::SensorOptions::position_noise)
      .def_readwrite("tilt_quantum", &mm::SensorOptions::tilt_quantum);
  py::class_<mm::AgentEnvOptions>(m, "Options")
      .def(py::init<>())
      .def_readwrite("maze", &mm::AgentEnvOptions::maze)
      .def_readwrite("preset", &mm::AgentEnvOptions::preset)
      .def_readwrite("sets", &mm::AgentEnvOptions::sets)
      .def_readwrite("control_rate", &mm::AgentEnvOptions::control_rate)
      .def_readwrite("max_episode_seconds", &mm::AgentEnvOptions::max_episode_seconds)
      .def_readwrite("tilt_rates", &mm::AgentEnvOptions::tilt_rates)
      .def_readwrite("progress_reward", &mm::AgentEnvOptions::progress_reward)
      .def_readwrite("hole_penalty", &mm::AgentEnvOptions::hole_penalty)
      .def_readwrite("goal_bonus", &mm::AgentEnvOptions::goal_bonus)
      .def_readwrite("random_start", &mm::AgentEnvOptions::random_start)
      .def_readwrite("ranges", &mm::AgentEnvOptions::ranges)
      .def_readwrite("sensors", &mm::AgentEnvOptions::sensors)
      .def_readwrite("seed", &mm::AgentEnvOptions::seed);
  py::class_<VectorEnv>(m, "VectorEnv")
      .def(py::init<int, const mm::AgentEnvOptions&, int>(), py::arg("num_envs"),
           py::arg("options"), py::arg("num_threads"))
      .def("reset", &VectorEnv::reset, py::arg("seed") = py::none())
      .def("reset_each", &VectorEnv::resetEach, py::arg("seeds"))
      .def("step", &VectorEnv::step)
      .def("images", &VectorEnv::images, py::arg("pixel"))
      .def_property_readonly("num_envs", &VectorEnv::size)
      .def_property_readonly("steps_per_period", &VectorEnv::stepsPerPeriod)
      .def_property_readonly("step_length", &VectorEnv::stepLength)
      .def("simulated_time", [](const VectorEnv& e, int i) { return e.simulation(i).time(); })
      .def("params_text",
           [](const VectorEnv& e, int i) { return mm::paramsText(e.simulation(i).params()); });
}
