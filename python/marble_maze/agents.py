"""Environments for learning agents, with Gymnasium's API, over the marble_maze core: no ROS
master and no rospy needed.

    import marble_maze.agents as agents
    envs = agents.VectorMazeEnv(64, maze="classic", preset="fast", seed=1)
    obs, info = envs.reset()
    obs, reward, terminated, truncated, info = envs.step(actions)  # actions: (64, 2) in [-1, 1]

Each environment is a session of the core stepped one control period per action (55 Hz by
default, honoured exactly: the preset's step is shortened to the largest that divides the
period). An action is the target roll and pitch as fractions of the tilt limit (or, with
tilt_rates=True, tilt rates as fractions of the rate limit), clipped to [-1, 1]; a NaN is
refused.

The observation (float32, 10 values, SI units in the board frame): the marble's x, y; its
velocity vx, vy; the board's roll, pitch; the target roll, pitch; the next waypoint of the route
to the goal, dx, dy from the marble. The reward: progress_reward per metre nearer the goal along
the route planner's path, -hole_penalty on a hole or off the board, +goal_bonus at the goal.
An episode is terminated in a hole, off the board or at the goal, and truncated after
max_episode_seconds (infinity: never). Finished episodes start again at once, as Gymnasium
0.29's vector environments do; their last observation is in info["final_observation"], their
last info in info["final_info"] (the observation also in info["final_obs"], Gymnasium 1.x's
same-step autoreset).

Every episode starts with the marble at rest and the board level. randomize varies episodes:
{"start": "random"} puts the marble on a random open column with a route to the goal, and
{"friction": (0.2, 0.4), ...} draws each key of the key table uniformly from its range. The
n-th episode of environment i after reset(seed) depends on (seed, i, n) alone: the same bit for
bit whatever num_threads. reset(seed=[s0, s1, ...]), a seed or None for each environment, draws
environment i's from (s_i, 0, n), a MazeEnv's after reset(seed=s_i).

observation models the sensors of a real board: {"delay_periods": 2, "delay_jitter": 1} shows
the camera's values (x, y, vx, vy, dx, dy) 2 to 3 control periods late, a jitter drawn each
period that never shows an older frame after a newer one; {"camera_rate": 30} takes a frame 30
times a second and holds it between; {"position_noise": 0.001} adds Gaussian noise of 1 mm to
each frame's x and y; {"tilt_quantum": math.radians(1)} reports the board's roll and pitch in
whole degrees. The target tilt is the agent's own command, exact. Every draw comes from the
episode's seed.

images(pixel=0.002) gives what a camera above the board sees, for agents that learn from pixels:
uint8 [num_envs, 4, height, width] (MazeEnv: [4, height, width]), planes walls, holes, goals and
the marble (255 where each is), row 0 along the board's +y edge, at pixel metres a side; the
marble is where the camera's frame, as the observation model delivers it, has it. With
render_mode="rgb_array", render() draws those planes in colour, uint8 [height, width, 3].
"""
import operator

import numpy as np

from marble_maze import _agents

OBSERVATION_SIZE = _agents.OBSERVATION_SIZE
IMAGE_CHANNELS = _agents.IMAGE_CHANNELS
ACTION_SIZE = 2

try:  # the spaces and base classes of Gymnasium where it is installed, the same API where not
    import gymnasium
    from gymnasium.spaces import Box
    _EnvBase, _VectorEnvBase = gymnasium.Env, gymnasium.vector.VectorEnv
    # (Gymnasium 1.x's wrappers read how ended episodes start again from the metadata; 0.29
    # has no such key, and its layout is the one given.)
    _SAME_STEP = getattr(gymnasium.vector, "AutoresetMode", None)
    _SAME_STEP = _SAME_STEP.SAME_STEP if _SAME_STEP else "SameStep"
except ImportError:
    gymnasium = None
    _SAME_STEP = "SameStep"

    class Box:
        """A box of R^n, as gymnasium.spaces.Box describes one."""

        def __init__(self, low, high, shape, dtype):
            self.low = np.full(shape, low, dtype=dtype)
            self.high = np.full(shape, high, dtype=dtype)
            self.shape = tuple(shape)
            self.dtype = np.dtype(dtype)
            self._random = np.random.default_rng()

        def seed(self, seed=None):
            self._random = np.random.default_rng(seed)

        def sample(self):
            low = np.where(np.isfinite(self.low), self.low, -1.0)
            high = np.where(np.isfinite(self.high), self.high, 1.0)
            return self._random.uniform(low, high).astype(self.dtype)

        def contains(self, x):
            x = np.asarray(x)
            return x.shape == self.shape and bool(np.all(x >= self.low) and np.all(x <= self.high))

    class _EnvBase:
        """What gymnasium.Env and gymnasium.vector.VectorEnv give an environment: np_random,
        seeded by reset(seed=...) as Gymnasium seeds it (PCG64 from the seed), unwrapped, spec,
        and closing on leaving a with block."""

        metadata = {"render_modes": []}
        render_mode = None
        spec = None
        _np_random = None

        def reset(self, *, seed=None, options=None):
            if seed is not None:
                self._np_random = np.random.default_rng(seed)

        @property
        def np_random(self):
            if self._np_random is None:
                self._np_random = np.random.default_rng()
            return self._np_random

        @np_random.setter
        def np_random(self, value):
            self._np_random = value

        @property
        def unwrapped(self):
            return self

        def close(self, **kwargs):
            pass

        def __enter__(self):
            return self

        def __exit__(self, *args):
            self.close()
            return False

    _VectorEnvBase = _EnvBase


SENSOR_OPTIONS = ("delay_periods", "delay_jitter", "camera_rate", "position_noise",
                  "tilt_quantum")


def _seed(seed, name):
    """An integer seed as the core takes it (None as it is), or a ValueError naming the
    argument."""
    if seed is None:
        return None
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)) \
            or not 0 <= seed < 2**64:
        raise ValueError("%s: expected an integer from 0 to 2**64 - 1, got %r" % (name, seed))
    return int(seed)


def _whole(value, name):
    """An integer argument as it is (not a bool), or a ValueError naming it."""
    try:
        if isinstance(value, (bool, np.bool_)):
            raise TypeError
        return operator.index(value)
    except TypeError:
        raise ValueError("%s: expected a whole number, got %r" % (name, value)) from None


def _number(value, name):
    """A real argument as a float, or a ValueError naming it."""
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ValueError("%s: expected a number, got %r" % (name, value)) from None


def _numbers(values, name):
    """An array argument as float64, or a ValueError naming it."""
    try:
        return np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError("%s: expected numbers, got %r" % (name, values)) from None


def _no_options(options):
    """reset's options, which Gymnasium's API allows and these environments take none of."""
    if options:
        raise ValueError("reset: options: none are taken (the settings are the constructor's), "
                         "got %r" % (options,))


def _render_mode(render_mode):
    """The render mode, of those Gymnasium names, that these environments draw."""
    if render_mode not in (None, "rgb_array"):
        raise ValueError("render_mode: expected None or 'rgb_array', got %r" % (render_mode,))
    return render_mode


RENDER_PIXEL = 0.001  # metres a pixel side of render()'s pictures (276 x 231 for the classic)

# render()'s colours (RGB): the board, and over it the holes, goals, walls and marble planes.
_BOARD_COLOUR = (225, 190, 140)
_PLANE_COLOURS = ((1, (25, 25, 25)), (2, (40, 160, 60)), (0, (110, 75, 40)), (3, (190, 190, 200)))


def _frame(planes):
    """An RGB picture, uint8 [height, width, 3], of one environment's image planes."""
    frame = np.empty(planes.shape[1:] + (3,), np.uint8)
    frame[...] = _BOARD_COLOUR
    for plane, colour in _PLANE_COLOURS:
        frame[planes[plane] > 0] = colour
    return frame


def _make(num_envs, num_threads, maze, preset, control_rate, max_episode_seconds, tilt_rates,
          progress_reward, hole_penalty, goal_bonus, sets, randomize, observation, seed):
    o = _agents.Options()
    o.seed = _seed(seed, "seed") or 0
    o.maze, o.preset = str(maze), str(preset)
    o.control_rate = _number(control_rate, "control_rate")
    o.max_episode_seconds = _number(max_episode_seconds, "max_episode_seconds")
    o.tilt_rates = bool(tilt_rates)
    o.progress_reward = _number(progress_reward, "progress_reward")
    o.hole_penalty = _number(hole_penalty, "hole_penalty")
    o.goal_bonus = _number(goal_bonus, "goal_bonus")
    o.sets = [(str(k), str(v)) for k, v in (sets or {}).items()]
    randomize = dict(randomize or {})
    start = randomize.pop("start", "start")
    if start not in ("start", "random"):
        raise ValueError("randomize: start: expected 'start' or 'random', got %r" % (start,))
    o.random_start = start == "random"
    o.ranges = [_range(str(key), bounds) for key, bounds in randomize.items()]
    sensors = _agents.SensorOptions()
    for key, value in (observation or {}).items():
        if key not in SENSOR_OPTIONS:
            raise ValueError("observation: %r: expected one of %s"
                             % (key, ", ".join(SENSOR_OPTIONS)))
        name = "observation: " + key
        if key.startswith("delay"):
            value = _whole(value, name)
            if not -2**31 <= value < 2**31:  # (what the core's int holds; it checks the range)
                raise ValueError("%s: %d is out of range" % (name, value))
        else:
            value = _number(value, name)
        setattr(sensors, key, value)
    o.sensors = sensors
    return _agents.VectorEnv(_whole(num_envs, "num_envs"), o, _whole(num_threads, "num_threads"))


def _range(key, bounds):
    """randomize's range of a key, (low, high)."""
    name = "randomize: " + key
    try:
        low, high = bounds
    except (TypeError, ValueError):
        raise ValueError("%s: expected (low, high), got %r" % (name, bounds)) from None
    return _agents.Range(key, _number(low, name), _number(high, name))


class VectorMazeEnv(_VectorEnvBase):
    """num_envs environments stepped together in one C++ call, spread over num_threads."""

    metadata = {"render_modes": ["rgb_array"], "autoreset_mode": _SAME_STEP}
    is_vector_env = True  # (how Gymnasium 0.29's wrappers tell a vector environment)

    def __init__(self, num_envs, maze="classic", preset="fast", control_rate=55.0,
                 max_episode_seconds=60.0, seed=0, randomize=None, tilt_rates=False,
                 num_threads=1, progress_reward=10.0, hole_penalty=1.0, goal_bonus=1.0,
                 sets=None, observation=None, render_mode=None):
        self.render_mode = _render_mode(render_mode)
        self._env = _make(num_envs, num_threads, maze, preset, control_rate, max_episode_seconds,
                          tilt_rates, progress_reward, hole_penalty, goal_bonus, sets, randomize,
                          observation, seed)
        self.num_envs = self._env.num_envs
        self.single_observation_space = Box(-np.inf, np.inf, (OBSERVATION_SIZE,), np.float32)
        self.single_action_space = Box(-1.0, 1.0, (ACTION_SIZE,), np.float32)
        self.observation_space = Box(-np.inf, np.inf, (self.num_envs, OBSERVATION_SIZE),
                                     np.float32)
        self.action_space = Box(-1.0, 1.0, (self.num_envs, ACTION_SIZE), np.float32)
        if seed is not None:
            self.action_space.seed(int(seed))
        self.control_period = 1.0 / control_rate
        self.steps_per_period = self._env.steps_per_period
        self.step_length = self._env.step_length
        self.metadata = dict(self.metadata, render_fps=float(control_rate))
        self.closed = False

    def reset(self, seed=None, options=None):
        """seed: an integer, environment i's episodes drawn from (seed, i) from now on; or a list
        of an integer or None for each environment, as Gymnasium's vector environments take,
        environment i's drawn from (seed[i], 0), those of a MazeEnv reset with seed[i] (None: its
        episodes go on); or None, every environment's episodes go on. options: none are taken
        (the settings are the constructor's)."""
        _no_options(options)
        if isinstance(seed, (list, tuple, np.ndarray)):
            seeds = [_seed(s, "reset: seed[%d]" % i) for i, s in enumerate(seed)]
            if seeds and seeds[0] is not None:
                self.action_space.seed(seeds[0])
            return self._env.reset_each(seeds), {}
        seed = _seed(seed, "reset: seed")
        if seed is not None:
            self.action_space.seed(seed)
        return self._env.reset(seed), {}

    def step(self, actions):
        """actions: [num_envs, 2] numbers, clipped to [-1, 1] (a NaN is refused)."""
        obs, reward, terminated, truncated, final, ended = self._env.step(
            _numbers(actions, "actions"))
        info = {}
        if ended:
            # (Gymnasium 0.29's layout: object arrays, None where the episode goes on.)
            final_observation = np.empty(self.num_envs, dtype=object)
            final_info = np.empty(self.num_envs, dtype=object)
            for i in ended:
                final_observation[i] = final[i]
                final_info[i] = {}
            done = terminated | truncated
            info["final_observation"], info["_final_observation"] = final_observation, done
            info["final_info"], info["_final_info"] = final_info, done.copy()
            # (The same under Gymnasium 1.x's names for its same-step autoreset.)
            info["final_obs"], info["_final_obs"] = final_observation.copy(), done.copy()
        return obs, reward, terminated, truncated, info

    def images(self, pixel=0.002):
        """The top-down pictures of every environment: uint8 [num_envs, 4, height, width]."""
        return self._env.images(float(pixel))

    def render(self):
        """With render_mode="rgb_array", a tuple of each environment's picture, uint8 [height,
        width, 3], as images() sees it; else None."""
        if self.render_mode is None:
            return None
        return tuple(_frame(planes) for planes in self.images(RENDER_PIXEL))

    def simulated_time(self, i):
        """Simulated seconds of environment i since its creation (resets keep time going)."""
        return self._env.simulated_time(i)

    def params(self, i):
        """Environment i's physics in force, {key: text}, as simulate --set takes them."""
        return dict(line.split("=", 1) for line in self._env.params_text(i).splitlines())

    def close(self, **kwargs):
        self.closed = True


class MazeEnv(_EnvBase):
    """One environment with Gymnasium's Env API."""

    metadata = {"render_modes": ["rgb_array"]}

    def __init__(self, maze="classic", preset="fast", control_rate=55.0, max_episode_seconds=60.0,
                 seed=0, randomize=None, tilt_rates=False, progress_reward=10.0,
                 hole_penalty=1.0, goal_bonus=1.0, sets=None, observation=None,
                 render_mode=None):
        self.render_mode = _render_mode(render_mode)
        self._env = _make(1, 1, maze, preset, control_rate, max_episode_seconds, tilt_rates,
                          progress_reward, hole_penalty, goal_bonus, sets, randomize, observation,
                          seed)
        self.observation_space = Box(-np.inf, np.inf, (OBSERVATION_SIZE,), np.float32)
        self.action_space = Box(-1.0, 1.0, (ACTION_SIZE,), np.float32)
        if seed is not None:
            self.action_space.seed(int(seed))
        self.metadata = dict(self.metadata, render_fps=float(control_rate))

    def reset(self, seed=None, options=None):
        """seed: an integer, the episodes drawn from (seed, 0) from now on, and np_random
        seeded as Gymnasium seeds it; or None, the episodes go on. options: none are taken."""
        _no_options(options)
        seed = _seed(seed, "reset: seed")
        super().reset(seed=seed)
        if seed is not None:
            self.action_space.seed(seed)
        return self._env.reset(seed)[0], {}

    def step(self, action):
        """action: roll and pitch, clipped to [-1, 1] (a NaN is refused)."""
        action = _numbers(action, "action")
        if action.shape != (ACTION_SIZE,) or np.isnan(action).any():
            raise ValueError("action: expected %d numbers (clipped to [-1, 1]), got %r"
                             % (ACTION_SIZE, action))
        obs, reward, terminated, truncated, final, ended = self._env.step(
            action.reshape(1, ACTION_SIZE))
        # (Gymnasium's Env is reset by its caller: the episode's last observation is returned.)
        return (final[0] if ended else obs[0]), float(reward[0]), bool(terminated[0]), \
            bool(truncated[0]), {}

    def images(self, pixel=0.002):
        """The top-down picture: uint8 [4, height, width] (walls, holes, goals, marble)."""
        return self._env.images(float(pixel))[0]

    def render(self):
        """With render_mode="rgb_array", the picture, uint8 [height, width, 3], as images()
        sees it; else None."""
        if self.render_mode is None:
            return None
        return _frame(self.images(RENDER_PIXEL))


ENV_ID = "marble_maze/Maze-v0"
if gymnasium is not None and ENV_ID not in gymnasium.registry:
    # gymnasium.make(ENV_ID, ...) gives a MazeEnv, make_vec(ENV_ID, n) (1.x) a VectorMazeEnv;
    # "marble_maze.agents:" before the id imports this module first.
    gymnasium.register(ENV_ID, entry_point="marble_maze.agents:MazeEnv",
                       vector_entry_point="marble_maze.agents:VectorMazeEnv")
