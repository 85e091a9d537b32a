#!/usr/bin/env python3
"""marble_maze.agents as an agent's author uses it, with no ROS master: Gymnasium's shapes and
dtypes, exact control periods, the same episodes whatever the threads, episodes that end and
start again, and a reward that pays for progress along the route."""
import os
import sys
import unittest

import numpy as np

import marble_maze.agents as agents

HERE = os.path.dirname(os.path.abspath(__file__))
HOLE_BESIDE = os.path.join(HERE, "..", "ros", "hole_beside.yaml")


def steer(obs):
    """A P-D controller towards the next waypoint: pitch lowers the board's +x edge (the marble
    rolls to +x), roll raises its +y edge (the marble rolls to -y)."""
    ax = 20 * obs[:, 8] - 3 * obs[:, 2]
    ay = 20 * obs[:, 9] - 3 * obs[:, 3]
    return np.clip(np.stack([-ay, ax], axis=1), -1, 1)


class AgentsTest(unittest.TestCase):
    def test_the_shapes_and_dtypes_are_gymnasiums(self):
        envs = agents.VectorMazeEnv(4)
        obs, info = envs.reset(seed=1)
        self.assertEqual(obs.shape, (4, agents.OBSERVATION_SIZE))
        self.assertEqual(obs.dtype, np.float32)
        self.assertEqual(info, {})
        obs, reward, terminated, truncated, info = envs.step(np.zeros((4, 2)))
        self.assertEqual(obs.shape, (4, 10))
        self.assertEqual((reward.shape, reward.dtype), ((4,), np.float64))
        self.assertEqual((terminated.dtype, truncated.dtype), (np.bool_, np.bool_))
        self.assertTrue(envs.single_action_space.contains(np.array([1, -1], np.float32)))
        # On the start at rest, the board level: the marble at the start cell's centre.
        self.assertAlmostEqual(float(obs[0, 4]), 0.0, places=12)
        env = agents.MazeEnv()
        first, _ = env.reset(seed=3)
        self.assertEqual(first.shape, (10,))
        after, reward, terminated, truncated, _ = env.step(np.array([0.2, -0.1]))
        self.assertIsInstance(reward, float)
        self.assertFalse(terminated or truncated)

    def test_55_hz_is_honoured_exactly(self):
        envs = agents.VectorMazeEnv(1, control_rate=55.0, preset="fast")
        # The 5 ms step shortened to the largest that divides 1/55 s: four of 4.545 ms.
        self.assertEqual(envs.steps_per_period, 4)
        self.assertAlmostEqual(envs.steps_per_period * envs.step_length, 1 / 55, delta=1e-18)
        envs.reset()
        for _ in range(550):
            envs.step(np.zeros((1, 2)))
        self.assertAlmostEqual(envs.simulated_time(0), 10.0, delta=1e-12)
        realtime = agents.VectorMazeEnv(1, control_rate=55.0, preset="realtime")
        self.assertEqual(realtime.steps_per_period, 19)  # 1 ms shortened to 0.957 ms

    def test_the_same_episodes_whatever_the_threads(self):
        rng = np.random.default_rng(5)
        actions = rng.uniform(-1, 1, (300, 8, 2))
        runs = []
        for threads in (1, 2, 3):
            envs = agents.VectorMazeEnv(8, num_threads=threads, max_episode_seconds=2.0)
            obs, _ = envs.reset(seed=5)
            trace = [obs]
            for a in actions:
                obs, reward, terminated, truncated, _ = envs.step(a)
                trace += [obs, reward, terminated, truncated]
            runs.append(trace)
        for other in runs[1:]:
            for a, b in zip(runs[0], other):
                np.testing.assert_array_equal(a, b)

    def test_an_episode_ends_in_a_hole_and_starts_again(self):
        envs = agents.VectorMazeEnv(2, maze=HOLE_BESIDE, hole_penalty=1.0)
        start, _ = envs.reset()
        for period in range(200):  # the board lowered towards +x, into the hole beside the start
            obs, reward, terminated, truncated, info = envs.step(np.array([[0, 1], [0, 1]]))
            if terminated.any():
                break
        self.assertTrue(terminated.all(), "no hole in 200 periods")
        self.assertFalse(truncated.any())
        self.assertLessEqual(float(reward[0]), -1.0 + 1e-9)  # the penalty, no progress (no route)
        final = info["final_observation"][0]
        self.assertGreater(float(final[0]), float(start[0, 0]) + 0.01)  # over the hole
        np.testing.assert_array_equal(obs, start)  # the new episode's first observation

    def test_the_final_observation_is_only_where_an_episode_ended(self):
        envs = agents.VectorMazeEnv(3, maze=HOLE_BESIDE)
        envs.reset()
        for period in range(200):  # the first into the hole, the others level
            obs, _, terminated, _, info = envs.step(np.array([[0, 1], [0, 0], [0, 0]]))
            if terminated.any():
                break
        np.testing.assert_array_equal(terminated, [True, False, False])
        np.testing.assert_array_equal(info["_final_observation"], [True, False, False])
        final = info["final_observation"]
        self.assertEqual(final.dtype, object)
        self.assertEqual(final[0].shape, (agents.OBSERVATION_SIZE,))
        self.assertIsNone(final[1])
        self.assertIsNone(final[2])
        self.assertEqual(list(info["final_info"]), [{}, None, None])
        np.testing.assert_array_equal(info["_final_info"], [True, False, False])
        # Gymnasium 1.x's names for the same (its wrappers read the mode from the metadata), in
        # an array of its own: a wrapper that transforms one in place leaves the other.
        self.assertIsNot(info["final_obs"], final)
        self.assertEqual([None if o is None else o.tolist() for o in info["final_obs"]],
                         [final[0].tolist(), None, None])
        np.testing.assert_array_equal(info["_final_obs"], [True, False, False])
        self.assertEqual(getattr(envs.metadata["autoreset_mode"], "value",
                                 envs.metadata["autoreset_mode"]), "SameStep")
        self.assertTrue(envs.is_vector_env)

    def test_a_single_env_returns_the_last_observation_of_its_episode(self):
        single, vector = agents.MazeEnv(maze=HOLE_BESIDE), agents.VectorMazeEnv(1, maze=HOLE_BESIDE)
        start, _ = single.reset()
        vector.reset()
        for period in range(200):  # into the hole beside the start, both alike
            obs, _, terminated, _, _ = single.step(np.array([0, 1]))
            _, _, ended_too, _, info = vector.step(np.array([[0, 1]]))
            if terminated:
                break
        self.assertTrue(terminated, "no hole in 200 periods")
        self.assertTrue(ended_too[0], "the vector environment went on")
        self.assertGreater(float(obs[0]), float(start[0]) + 0.01)  # over the hole, not reset
        np.testing.assert_array_equal(obs, info["final_observation"][0])

    def test_an_episode_is_truncated_at_its_time_limit(self):
        envs = agents.VectorMazeEnv(1, max_episode_seconds=0.2)
        envs.reset()
        ends = [envs.step(np.zeros((1, 2)))[3][0] for _ in range(23)]
        self.assertEqual([k for k, t in enumerate(ends) if t], [10, 21])  # 11 periods of 1/55 s

    def test_steering_along_the_route_is_paid_and_random_play_is_not(self):
        def total(policy, seconds=4.0):
            envs = agents.VectorMazeEnv(4, max_episode_seconds=60.0)
            obs, _ = envs.reset(seed=2)
            rng = np.random.default_rng(2)
            paid = np.zeros(4)
            for _ in range(int(seconds * 55)):
                obs, reward, _, _, _ = envs.step(policy(obs, rng))
                paid += reward
            return paid.mean()

        steered = total(lambda obs, rng: steer(obs))
        random = total(lambda obs, rng: rng.uniform(-1, 1, (4, 2)))
        print("return over 4 s: steered %.3f, random %.3f" % (steered, random))
        self.assertGreater(steered, 0.5)  # half a metre of the route, at 10 a metre
        self.assertGreater(steered, random + 0.5)

    def test_randomised_episodes_keep_to_their_ranges_and_their_seed(self):
        ranges = {"friction": (0.2, 0.4), "restitution": (0.3, 0.7),
                  "tilt_response_time": (0.02, 0.08), "marble_radius": (0.0055, 0.0065)}

        def episodes(seed, threads):
            envs = agents.VectorMazeEnv(6, seed=seed, num_threads=threads,
                                        randomize=dict(start="random", **ranges))
            firsts, drawn = [], []
            for _ in range(3):
                obs, _ = envs.reset() if not firsts else envs.reset(seed=seed + len(firsts))
                firsts.append(obs)
                drawn.append([envs.params(i) for i in range(6)])
            return firsts, drawn

        firsts, drawn = episodes(7, 1)
        for params in sum(drawn, []):
            for key, (low, high) in ranges.items():
                self.assertTrue(low <= float(params[key]) <= high, (key, params[key]))
        values = {params["friction"] for params in sum(drawn, [])}
        self.assertGreater(len(values), 10)  # drawn anew for each environment and episode
        starts = {tuple(np.round(obs[i, :2], 6)) for obs in firsts for i in range(6)}
        self.assertGreater(len(starts), 5)  # random open columns, not the maze's start alone
        for obs in firsts:  # each at rest on an open column
            np.testing.assert_array_equal(obs[:, 2:4], 0)
        again, drawn_again = episodes(7, 3)
        for a, b in zip(firsts, again):
            np.testing.assert_array_equal(a, b)  # the same seed: the same episodes, any threads
        self.assertEqual(drawn, drawn_again)
        other, _ = episodes(8, 1)
        self.assertFalse(np.array_equal(firsts[0], other[0]))

    def test_a_seed_for_each_environment_gives_it_a_lone_environments_episodes(self):
        settings = dict(randomize={"start": "random", "friction": (0.2, 0.4)},
                        max_episode_seconds=0.5)
        actions = np.random.default_rng(3).uniform(-1, 1, (60, 4, 2))

        def play(envs, first, columns):
            """Observations, rewards and ends under the actions of environments `columns`."""
            trace = [first]
            for a in actions:
                obs, reward, terminated, truncated, _ = envs.step(a[columns])
                trace += [obs, reward, terminated, truncated]
            return trace

        for threads in (1, 2):
            # Seeded as Gymnasium's vector environments are: a list, None where the episodes go
            # on (here from the constructor's seed, 9).
            envs = agents.VectorMazeEnv(4, seed=9, num_threads=threads, **settings)
            trace = play(envs, envs.reset(seed=[11, None, 12, 11])[0], [0, 1, 2, 3])
            going_on = agents.VectorMazeEnv(4, seed=9, **settings)
            kept = play(going_on, going_on.reset()[0], [0, 1, 2, 3])
            for i, seed in enumerate([11, None, 12, 11]):
                if seed is None:
                    reference, row = kept, i
                else:
                    lone = agents.VectorMazeEnv(1, seed=seed, **settings)
                    reference, row = play(lone, lone.reset()[0], [i]), 0
                for a, b in zip(trace, reference):  # the episodes (and resets) bit for bit
                    np.testing.assert_array_equal(a[i], b[row])
            self.assertTrue(any(t[1] for t in trace[3::4]))  # episodes ended within the play
        self.assertFalse(np.array_equal(trace[0][0], trace[0][2]))  # 11 and 12 differ
        self.assertEqual(agents.MazeEnv(**settings).reset(seed=11)[0].tolist(),
                         trace[0][0].tolist())
        with self.assertRaisesRegex(ValueError, "seed: expected 4 seeds, one an environment, "
                                    "got 3"):
            envs.reset(seed=[1, 2, 3])
        with self.assertRaisesRegex(ValueError, r"reset: seed\[1\]: expected an integer"):
            envs.reset(seed=[1, -2, 3, 4])
        with self.assertRaisesRegex(ValueError, "reset: seed: expected an integer"):
            envs.reset(seed=2.5)
        with self.assertRaisesRegex(ValueError, "seed: expected an integer"):
            agents.MazeEnv(seed="one")
        with self.assertRaisesRegex(ValueError, "reset: options: none are taken"):
            agents.MazeEnv().reset(options={"start": "random"})
        self.assertEqual(envs.reset(seed=1, options={})[0].shape, (4, 10))

    def test_a_generated_maze_is_played_like_any(self):
        envs = agents.VectorMazeEnv(2, maze="generated:seed=3,cells=5x5")
        obs, _ = envs.reset()
        self.assertTrue(np.all(np.isfinite(obs)))
        self.assertTrue(np.any(obs[:, 8:10] != 0))  # a route to follow
        again = agents.VectorMazeEnv(2, maze="generated:seed=3,cells=5x5").reset()[0]
        np.testing.assert_array_equal(obs, again)

    def observed(self, observation, periods=300, envs=8):
        """The observations of environments with `observation`'s sensors beside exact ones, both
        steered by the exact ones (so the same physics): arrays [period, env, value], and
        whether each environment is still in its first episode at each period."""
        exact = agents.VectorMazeEnv(envs, seed=4, randomize={"start": "random"})
        model = agents.VectorMazeEnv(envs, seed=4, randomize={"start": "random"},
                                     observation=observation)
        truth, seen = [exact.reset()[0]], [model.reset()[0]]
        alive = [np.ones(envs, bool)]
        rng = np.random.default_rng(2)
        for _ in range(periods):
            actions = np.clip(steer(truth[-1]) + rng.normal(0, 0.3, (envs, 2)), -1, 1)
            obs, _, terminated, truncated, _ = exact.step(actions)
            truth.append(obs)
            seen.append(model.step(actions)[0])
            alive.append(alive[-1] & ~(terminated | truncated))
        alive = np.array(alive)
        self.assertGreater(alive.sum(), 1000)  # enough periods to measure
        return np.array(truth), np.array(seen), alive

    def test_a_delay_shows_the_camera_periods_late_and_the_tilt_at_once(self):
        truth, seen, alive = self.observed({"delay_periods": 2})
        camera = [0, 1, 2, 3, 8, 9]
        late = alive[2:]
        np.testing.assert_array_equal(seen[2:][late][:, camera], truth[:-2][late][:, camera])
        np.testing.assert_array_equal(seen[alive][:, 4:8], truth[alive][:, 4:8])  # the tilt
        self.assertFalse(np.array_equal(seen[2:][late][:, 0], truth[2:][late][:, 0]))  # lagged

    def test_jitter_draws_each_lag_in_its_range(self):
        truth, seen, alive = self.observed({"delay_periods": 1, "delay_jitter": 2})
        lags = set()
        for k, i in zip(*np.nonzero(alive)):
            if k < 3:
                continue
            lag = [d for d in (1, 2, 3) if seen[k, i, 0] == truth[k - d, i, 0]]
            self.assertTrue(lag, "period %d env %d: a frame not 1 to 3 periods old" % (k, i))
            lags.add(lag[0])
        self.assertEqual(lags, {1, 2, 3})

    def test_a_slower_camera_holds_its_frame(self):
        truth, seen, alive = self.observed({"camera_rate": 11.0})  # every fifth period at 55 Hz
        for k, i in zip(*np.nonzero(alive)):
            np.testing.assert_array_equal(seen[k, i, :4], truth[k - k % 5, i, :4])

    def test_position_noise_has_its_deviation(self):
        truth, seen, alive = self.observed({"position_noise": 0.001})
        noise = (seen[alive][:, :2] - truth[alive][:, :2]).ravel()
        print("position noise: mean %.2e m, deviation %.4e m over %d" %
              (noise.mean(), noise.std(), noise.size))
        self.assertLess(abs(noise.mean()), 4 * 0.001 / np.sqrt(noise.size))
        self.assertAlmostEqual(noise.std(), 0.001, delta=0.0001)  # float32 and sampling: 10%
        np.testing.assert_array_equal(seen[alive][:, 2:8], truth[alive][:, 2:8])  # the rest

    def test_the_tilt_is_reported_in_whole_degrees(self):
        quantum = np.radians(1.0)
        truth, seen, alive = self.observed({"tilt_quantum": quantum})
        tilt = seen[alive][:, 4:6].astype(np.float64)
        exact = truth[alive][:, 4:6].astype(np.float64)
        np.testing.assert_allclose(tilt / quantum, np.round(tilt / quantum), atol=1e-5)
        self.assertLessEqual(np.abs(tilt - exact).max(), quantum / 2 + 1e-6)
        self.assertGreater(len(np.unique(np.round(tilt / quantum))), 3)  # the board did turn
        np.testing.assert_array_equal(seen[alive][:, 6:8], truth[alive][:, 6:8])  # the target

    def test_images_show_the_maze_and_the_marble_where_the_camera_has_it(self):
        pixel = 0.002
        envs = agents.VectorMazeEnv(4, seed=1, randomize={"start": "random"},
                                    observation={"delay_periods": 3})
        obs, _ = envs.reset()
        for _ in range(20):
            obs = envs.step(np.full((4, 2), 0.3))[0]
        images = envs.images(pixel)
        n, channels, height, width = images.shape
        self.assertEqual((n, channels, images.dtype), (4, agents.IMAGE_CHANNELS, np.uint8))
        self.assertTrue(set(np.unique(images)) <= {0, 255})
        walls, holes, goals, marbles = (images[:, c] > 0 for c in range(4))
        # The classic maze: 0.28 x 0.23 m with a wall all round, holes and one goal.
        self.assertAlmostEqual(width * pixel, 0.28, delta=0.02)
        self.assertAlmostEqual(height * pixel, 0.23, delta=0.02)
        for edge in (walls[:, 0, :], walls[:, -1, :], walls[:, :, 0], walls[:, :, -1]):
            self.assertTrue(edge.all())
        self.assertTrue(holes.any() and goals.any())
        self.assertFalse((walls & holes).any() or (holes & goals).any())
        for i in range(n):  # the marble: a disc of its radius at the observed x, y
            rows, cols = np.nonzero(marbles[i])
            x = (cols.mean() + 0.5) * pixel - width * pixel / 2
            y = height * pixel / 2 - (rows.mean() + 0.5) * pixel
            self.assertAlmostEqual(x, float(obs[i, 0]), delta=pixel)
            self.assertAlmostEqual(y, float(obs[i, 1]), delta=pixel)
            disc = np.pi * 0.006 ** 2
            self.assertAlmostEqual(len(rows) * pixel ** 2, disc, delta=0.3 * disc)
            self.assertFalse((marbles[i] & walls[i]).any())
        single = agents.MazeEnv().images(pixel)
        self.assertEqual(single.shape, (4, height, width))
        with self.assertRaisesRegex(ValueError, "raster pixel"):
            envs.images(0)

    def test_reset_seeds_np_random_as_gymnasium_does(self):
        env = agents.MazeEnv()
        env.reset(seed=7)
        # Gymnasium's seeding.np_random(seed): PCG64 from a SeedSequence of the seed.
        expected = np.random.Generator(np.random.PCG64(np.random.SeedSequence(7)))
        np.testing.assert_array_equal(env.np_random.integers(2**62, size=4),
                                      expected.integers(2**62, size=4))
        generator = env.np_random
        env.reset()  # no seed: the generator goes on
        self.assertIs(env.np_random, generator)
        self.assertIs(env.unwrapped, env)

    def test_render_colours_the_images_planes(self):
        self.assertIsNone(agents.MazeEnv().render())
        env = agents.MazeEnv(render_mode="rgb_array", seed=2, randomize={"start": "random"})
        env.reset()
        for _ in range(10):
            env.step(np.array([0.4, -0.2]))
        frame = env.render()
        planes = env.images(agents.RENDER_PIXEL) > 0
        self.assertEqual(frame.shape, planes.shape[1:] + (3,))
        self.assertEqual(frame.dtype, np.uint8)
        walls, holes, goals, marble = planes
        self.assertTrue(marble.any() and holes.any() and goals.any())
        colours = [frame[plane & ~marble] for plane in (walls, holes, goals)] + [frame[marble]]
        colours.append(frame[~planes.any(axis=0)])  # the board
        for pixels in colours:  # each plane in one colour, none shared with another
            self.assertEqual(len(np.unique(pixels, axis=0)), 1)
        self.assertEqual(len(np.unique([c[0] for c in colours], axis=0)), 5)
        self.assertEqual(env.metadata["render_fps"], 55.0)
        seeds = [3, 4, 5]  # each environment's own start: each picture its own
        envs = agents.VectorMazeEnv(3, render_mode="rgb_array", randomize={"start": "random"})
        envs.reset(seed=seeds)
        frames = envs.render()
        self.assertEqual(len(frames), 3)
        for seed, frame in zip(seeds, frames):
            single = agents.MazeEnv(render_mode="rgb_array", randomize={"start": "random"})
            single.reset(seed=seed)
            np.testing.assert_array_equal(frame, single.render())
        self.assertFalse(np.array_equal(frames[0], frames[1]))
        with self.assertRaisesRegex(ValueError, "render_mode: expected None or 'rgb_array', got "
                                                "'human'"):
            agents.MazeEnv(render_mode="human")

    @unittest.skipUnless(agents.gymnasium, "gymnasium is not installed")
    def test_gymnasium_checks_and_makes_them(self):
        import gymnasium
        from gymnasium.utils.env_checker import check_env
        for render_mode in (None, "rgb_array"):
            check_env(agents.MazeEnv(render_mode=render_mode))
        gymnasium.spec(agents.ENV_ID).to_json()  # (entry points that a spec can be saved with)
        env = gymnasium.make(agents.ENV_ID, maze="generated:seed=7,cells=5x5")
        self.assertIsInstance(env.unwrapped, agents.MazeEnv)
        obs, _ = env.reset(seed=1)
        np.testing.assert_array_equal(obs, agents.MazeEnv(maze="generated:seed=7,cells=5x5")
                                      .reset(seed=1)[0])
        if gymnasium.__version__.startswith("0."):
            return  # (0.29's make_vec is experimental, and passes arguments of its own)
        envs = gymnasium.make_vec(agents.ENV_ID, num_envs=4,
                                  vectorization_mode="vector_entry_point")
        self.assertIs(envs.metadata["autoreset_mode"], gymnasium.vector.AutoresetMode.SAME_STEP)
        self.assertIsInstance(envs.unwrapped, agents.VectorMazeEnv)
        self.assertEqual(envs.reset(seed=1)[0].shape, (4, agents.OBSERVATION_SIZE))

    def test_bad_arguments_are_refused_naming_them(self):
        with self.assertRaisesRegex(ValueError, "observation: 'latency'"):
            agents.VectorMazeEnv(1, observation={"latency": 2})
        with self.assertRaisesRegex(ValueError, "position_noise"):
            agents.VectorMazeEnv(1, observation={"position_noise": -1})
        with self.assertRaisesRegex(ValueError, "nope"):
            agents.VectorMazeEnv(1, maze="nope")
        with self.assertRaisesRegex(ValueError, "restitution"):
            agents.VectorMazeEnv(1, sets={"restitution": 2})
        with self.assertRaisesRegex(ValueError, "control_rate"):
            agents.VectorMazeEnv(1, control_rate=0)
        with self.assertRaisesRegex(ValueError, "friction"):
            agents.VectorMazeEnv(1, randomize={"friction": (0.2, 20)})
        with self.assertRaisesRegex(ValueError, "start"):
            agents.VectorMazeEnv(1, randomize={"start": "anywhere"})
        refused = [  # (arguments, what the message must name)
            ({"num_envs": 2.5}, r"num_envs: expected a whole number, got 2\.5"),
            ({"num_threads": "2"}, "num_threads: expected a whole number"),
            ({"control_rate": "fast"}, "control_rate: expected a number, got 'fast'"),
            # (a period of 2e8 steps would hold the caller for hours)
            ({"control_rate": 1e-6}, "control_rate: 1e-06 Hz .* more than 10000000 steps"),
            ({"max_episode_seconds": 0.005},
             "max_episode_seconds: expected at least one control period"),
            ({"max_episode_seconds": float("nan")}, "max_episode_seconds"),
            ({"goal_bonus": float("nan")}, "goal_bonus: expected a finite number, got nan"),
            ({"hole_penalty": float("inf")}, "hole_penalty: expected a finite number"),
            ({"randomize": {"friction": 0.3}}, r"randomize: friction: expected \(low, high\)"),
            ({"randomize": {"friction": (0.4, 0.2)}}, r"friction: .*low <= high, got \[0\.4, "),
            # (each period's steps are fixed with the step; a whole-number key has no range)
            ({"randomize": {"step": (0.001, 0.002)}}, "step: cannot be drawn per episode"),
            ({"randomize": {"substeps": (1, 2)}}, "substeps: cannot be drawn from a range"),
            ({"observation": {"delay_periods": 1.5}}, "observation: delay_periods: expected a "
                                                      "whole number"),
            ({"observation": {"delay_periods": 10**12}}, "delay_periods: 1000000000000 is out"),
        ]
        for arguments, message in refused:
            with self.subTest(arguments=arguments), self.assertRaisesRegex(ValueError, message):
                agents.VectorMazeEnv(**dict({"num_envs": 1}, **arguments))
        envs = agents.VectorMazeEnv(2)
        envs.reset()
        with self.assertRaisesRegex(ValueError, r"actions: expected shape \(2, 2\), got \(3, 2\)"):
            envs.step(np.zeros((3, 2)))
        with self.assertRaisesRegex(ValueError, "actions: expected numbers, got 'x'"):
            envs.step("x")
        with self.assertRaisesRegex(IndexError, "environment 2: expected 0 to 1"):
            envs.simulated_time(2)
        with self.assertRaisesRegex(IndexError, "environment -1: expected 0 to 1"):
            envs.params(-1)
        with self.assertRaisesRegex(ValueError, r"action: expected 2 numbers .*got array\(\[0"):
            agents.MazeEnv().step(np.zeros(3))

    def test_a_nan_action_is_refused_and_changes_nothing(self):
        refused, twin = (agents.VectorMazeEnv(3, seed=4) for _ in range(2))
        refused.reset(), twin.reset()
        actions = np.array([[0.3, -0.2], [-0.5, 0.1], [0.2, 0.6]])
        for envs in (refused, twin):
            envs.step(actions)
        with self.assertRaisesRegex(ValueError, r"actions\[2\]\[1\]: expected a number .*nan"):
            refused.step(np.where([[0, 0], [0, 0], [0, 1]], np.nan, actions))
        with self.assertRaisesRegex(ValueError, r"action: .*got array\(\[nan"):
            agents.MazeEnv().step(np.array([np.nan, 0]))
        # Every environment as if the refused call had not been made, bit for bit.
        for a, b in zip(refused.step(actions)[:4], twin.step(actions)[:4]):
            np.testing.assert_array_equal(a, b)
        self.assertEqual(refused.simulated_time(0), twin.simulated_time(0))

    def test_an_action_beyond_the_limits_is_clipped_to_them(self):
        beyond, limits = (agents.VectorMazeEnv(2, seed=5) for _ in range(2))
        beyond.reset(), limits.reset()
        for _ in range(20):
            obs = beyond.step(np.array([[np.inf, -np.inf], [7.0, -1.5]]))[0]
            np.testing.assert_array_equal(obs, limits.step(np.array([[1, -1], [1, -1]]))[0])
        tilt_limit = float(beyond.params(0)["tilt_limit"])
        # (the target roll and pitch, the observation's 7th and 8th values)
        np.testing.assert_allclose(obs[:, 6:8], [[tilt_limit, -tilt_limit]] * 2, rtol=1e-6)

    def test_an_endless_episode_is_never_truncated(self):
        envs = agents.VectorMazeEnv(1, max_episode_seconds=float("inf"))
        envs.reset()
        for _ in range(60 * 55 + 10):  # past the default limit's 3,300 periods, at rest
            _, _, terminated, truncated, _ = envs.step(np.zeros((1, 2)))
            self.assertFalse(terminated[0] or truncated[0])
        self.assertGreater(envs.simulated_time(0), 60.1)


if __name__ == "__main__":
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    import xml_results
    xml_results.main()
