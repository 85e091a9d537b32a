#!/usr/bin/env python3
"""Learns generated 5 x 5 mazes with PPO, from marble_maze.agents alone.

An actor-critic MLP, a Gaussian policy clipped to the actions' [-1, 1], GAE and the clipped
objective, in torch on one CPU thread (numpy, torch and matplotlib from Debian; no gymnasium).
It trains on one set of generated mazes from random starts and is judged on mazes it never saw,
from starts of their own: it has to learn to follow the route's next waypoint (the observation's
dx, dy), not any one maze.

    source "$(make -s ws)/devel/setup.bash"
    /usr/bin/python3 examples/train.py [--minutes 10] [--seed 0] [--out doc/learning_curve.png]

Trains until --minutes of wall time are nearly spent (or for --iterations), keeping time for the
final test, then prints "success S on N held-back episodes (M maze seeds), return X vs random Y,
..." and exits 0 when S reaches 0.8. --quick trains a few iterations (seconds) and exits 0 when
its return beats a random policy's. Given --seed, iteration k is the same on every run; only
where a time budget stops training depends on the machine's speed.
"""
import argparse
import copy
import os
import sys
import time

import numpy as np
import torch
from torch import nn

import marble_maze.agents as agents

CELLS = "5x5"
HOLES = 0.3  # the generator's default: that share of the dead ends off the path are holes
EPISODE_SECONDS = 20.0  # a steering controller crosses a 5 x 5 maze in about 5 s
# Disjoint maze seeds: trained on (from TRAIN_MAZES + 1000 * --seed), watched during training
# for the curve, and the final test's.
TRAIN_MAZES = 1000
VALIDATION_MAZES = 500
TEST_MAZES = 0
# Episode seeds (the random starts) of the validation and the test, unlike the training's.
VALIDATION_EPISODES = 77
TEST_EPISODES = 99
TARGET = 0.8
QUICK_ITERATIONS = 12  # 4 already beat a random policy's return by 3 (seeds 0 to 2)

# Each observation value over its typical size (board frame, SI): x, y (m), vx, vy (m/s), roll,
# pitch, target roll, pitch (rad; the tilt limit is 0.1745), the waypoint's dx, dy (m, within a
# cell): inputs of about one keep the tanh units out of saturation from the start.
SCALE = np.array([0.05, 0.05, 0.1, 0.1, 0.1, 0.1, 0.1745, 0.1745, 0.015, 0.015], np.float32)


def maze_name(seed, holes=HOLES):
    return "generated:seed=%d,cells=%s,holes=%g" % (seed, CELLS, holes)


def reached_goal(reward, terminated):
    """Whether an ending step reached the goal. The goal pays +goal_bonus (1) and one period's
    progress (under 0.04 measured); a hole or the board's edge pays -hole_penalty (1) and no
    progress, as no route crosses either: so a terminated step's reward is positive exactly at
    the goal."""
    return terminated & (reward > 0)


class Mazes:
    """Several generated mazes, `per_maze` environments each, stepped as one batch."""

    def __init__(self, seeds, per_maze, seed, holes=HOLES):
        self.envs = [agents.VectorMazeEnv(per_maze, maze=maze_name(s, holes), seed=seed,
                                          max_episode_seconds=EPISODE_SECONDS,
                                          randomize={"start": "random"}) for s in seeds]
        self.per_maze = per_maze
        self.num_envs = per_maze * len(self.envs)

    def reset(self):
        return np.concatenate([e.reset()[0] for e in self.envs])

    def step(self, actions):
        """obs, reward, terminated, truncated, and the ended episodes' last observations (the
        new episode's first elsewhere)."""
        out = [e.step(a) for e, a in zip(self.envs, np.split(actions, len(self.envs)))]
        obs = np.concatenate([o[0] for o in out])
        final = obs.copy()
        for k, (_, _, _, _, info) in enumerate(out):
            for i in np.nonzero(info.get("_final_observation", []))[0]:
                final[k * self.per_maze + i] = info["final_observation"][i]
        return (obs, np.concatenate([o[1] for o in out]), np.concatenate([o[2] for o in out]),
                np.concatenate([o[3] for o in out]), final)


class ActorCritic(nn.Module):
    """Two 64-64 tanh MLPs, the policy's mean and the value, and a state-independent log std."""

    def __init__(self, hidden=64):
        super().__init__()

        def mlp(out, gain):
            layers = [nn.Linear(len(SCALE), hidden), nn.Tanh(), nn.Linear(hidden, hidden),
                      nn.Tanh(), nn.Linear(hidden, out)]
            for layer, g in zip(layers[::2], (np.sqrt(2), np.sqrt(2), gain)):
                nn.init.orthogonal_(layer.weight, g)
                nn.init.zeros_(layer.bias)
            return nn.Sequential(*layers)

        # A small last layer: the first policy holds the board about level and explores about
        # that, rather than starting from some arbitrary tilt everywhere.
        self.actor = mlp(2, 0.01)
        self.critic = mlp(1, 1.0)
        self.log_std = nn.Parameter(torch.full((2,), -0.5))
        self.register_buffer("scale", torch.from_numpy(SCALE))

    def forward(self, obs):
        x = obs / self.scale
        return self.actor(x), self.log_std.expand(len(obs), 2), self.critic(x).squeeze(-1)

    def act(self, obs):
        """The mean action, clipped: the policy as it is judged."""
        with torch.no_grad():
            mean = self.actor(torch.as_tensor(obs) / self.scale)
        return mean.clamp(-1, 1).numpy().astype(np.float64)


def log_prob(mean, log_std, action):
    """The Gaussian's, of the action before clipping: clipping is the environment's business
    (as the env clips anyway), so the policy's density stays a plain Gaussian."""
    return (-0.5 * ((action - mean) / log_std.exp()) ** 2 - log_std
            - 0.5 * np.log(2 * np.pi)).sum(-1)


def random_actions(seed):
    rng = np.random.default_rng(seed)
    return lambda obs: rng.uniform(-1.0, 1.0, (len(obs), 2))


def evaluate(act, seeds, per_maze, episode_seed, holes=HOLES):
    """The first episode of each environment under `act`: returns, goals and holes, per
    episode."""
    mazes = Mazes(seeds, per_maze, episode_seed, holes)
    obs = mazes.reset()
    n = mazes.num_envs
    ret, done = np.zeros(n), np.zeros(n, bool)
    goal, hole = np.zeros(n, bool), np.zeros(n, bool)
    while not done.all():
        obs, reward, terminated, truncated, _ = mazes.step(act(obs))
        ret += np.where(done, 0.0, reward)
        ended = (terminated | truncated) & ~done
        goal |= ended & reached_goal(reward, terminated)
        hole |= ended & terminated & ~reached_goal(reward, terminated)
        done |= ended
    return ret, goal, hole


def train(minutes=10.0, seed=0, quick=False, iterations=None, holes=HOLES, log=print):
    """PPO until the budget or the iterations run out, then the test on held-back mazes.
    Returns a dict: the curve, the model, and per test episode the return, goal and hole of
    the policy and of a random one."""
    start = time.time()
    torch.manual_seed(seed)
    torch.set_num_threads(1)  # (one core for the learner, the other for whatever else runs)
    if quick:
        train_mazes, per_maze = 16, 4
        validation = (range(VALIDATION_MAZES, VALIDATION_MAZES + 5), 4)
        test = (range(TEST_MAZES, TEST_MAZES + 10), 5)
        budget, evaluate_every = min(minutes * 60, 30.0), 3
        iterations = QUICK_ITERATIONS if iterations is None else iterations
    else:
        train_mazes, per_maze = 32, 4
        validation = (range(VALIDATION_MAZES, VALIDATION_MAZES + 10), 5)
        test = (range(TEST_MAZES, TEST_MAZES + 20), 10)
        budget, evaluate_every = minutes * 60, 10
    # 128 periods (2.3 s of play) a rollout, the value bootstrapping the rest. gamma 0.995 looks
    # about 200 periods (3.6 s) ahead, near a route's 250: with 0.99 the goal's bonus and a
    # hole's cost weighed less, and ten minutes' training drifted to a faster policy that met
    # more holes (5% of the test against none after one minute).
    steps, epochs, minibatches, gamma, lam, clip = 128, 4, 4, 0.995, 0.95, 0.2
    first = TRAIN_MAZES + 1000 * seed
    mazes = Mazes(range(first, first + train_mazes), per_maze, seed, holes)
    model = ActorCritic()
    optimizer = torch.optim.Adam(model.parameters(), lr=3e-4, eps=1e-5)
    n, size = mazes.num_envs, len(SCALE)
    obs_buf, act_buf = torch.zeros(steps, n, size), torch.zeros(steps, n, 2)
    logp_buf, rew_buf, done_buf, val_buf = (torch.zeros(steps, n) for _ in range(4))

    # A random policy on the test's own episodes: the line to beat. Its episodes run longest
    # (most run out of time), so its time bounds the final test's.
    t0 = time.time()
    rand_ret, rand_goal, rand_hole = evaluate(random_actions(seed), *test, TEST_EPISODES, holes)
    test_seconds = time.time() - t0
    log("random policy: return %.3f, success %.2f, holes %.2f on %d held-back episodes"
        % (rand_ret.mean(), rand_goal.mean(), rand_hole.mean(), len(rand_ret)))

    curve = {"steps": [], "minutes": [], "return": [], "eval_steps": [], "eval_minutes": [],
             "eval_success": [], "eval_return": []}

    best = {"score": (-1.0, -np.inf)}

    def validate(total_steps):
        ret, goal, _ = evaluate(model.act, *validation, VALIDATION_EPISODES, holes)
        # The policy tested at the end is the validation's best (success, then return), the
        # latest of equals: the validation mazes are none of the test's, so the choice tells
        # the test nothing.
        if (goal.mean(), ret.mean()) >= best["score"]:
            best.update(score=(goal.mean(), ret.mean()), iteration=iteration,
                        state=copy.deepcopy(model.state_dict()))
        curve["eval_steps"].append(total_steps)
        curve["eval_minutes"].append((time.time() - start) / 60)
        curve["eval_success"].append(float(goal.mean()))
        curve["eval_return"].append(float(ret.mean()))
        log("%4d iterations, %8d steps, %4.1f min: training return %6.3f; unseen mazes: "
            "success %.2f, return %.3f; std %.3f" % (
                iteration, total_steps, curve["eval_minutes"][-1],
                curve["return"][-1] if curve["return"] else float("nan"), goal.mean(),
                ret.mean(), model.log_std.exp().mean().item()))

    obs = torch.as_tensor(mazes.reset())
    ep_ret, total_steps, iteration, longest = np.zeros(n), 0, 0, 0.0
    validate(0)
    while iterations is None or iteration < iterations:
        # Another iteration (as long as the longest yet) and the test must fit, with a margin
        # for the plot.
        if time.time() - start + longest + test_seconds + 3.0 > budget:
            break
        began = time.time()
        iteration += 1
        finished = []
        for t in range(steps):
            with torch.no_grad():
                mean, log_std, value = model(obs)
                action = mean + log_std.exp() * torch.randn_like(mean)
                logp_buf[t] = log_prob(mean, log_std, action)
            next_obs, reward, terminated, truncated, final = mazes.step(
                action.clamp(-1, 1).numpy().astype(np.float64))
            ep_ret += reward
            ended = terminated | truncated
            for i in np.nonzero(ended)[0]:
                finished.append(ep_ret[i])
                ep_ret[i] = 0.0
            reward = torch.as_tensor(reward, dtype=torch.float32)
            if truncated.any():  # out of time is no failure: the value says what would follow
                with torch.no_grad():
                    reward[torch.as_tensor(truncated)] += gamma * model(
                        torch.as_tensor(final[truncated]))[2]
            obs_buf[t], act_buf[t], val_buf[t] = obs, action, value
            rew_buf[t], done_buf[t] = reward, torch.as_tensor(ended, dtype=torch.float32)
            obs = torch.as_tensor(next_obs)
        total_steps += steps * n

        with torch.no_grad():
            next_value = model(obs)[2]
        advantage, last = torch.zeros(steps, n), torch.zeros(n)
        for t in reversed(range(steps)):
            live = 1.0 - done_buf[t]
            following = next_value if t == steps - 1 else val_buf[t + 1]
            delta = rew_buf[t] + gamma * following * live - val_buf[t]
            last = advantage[t] = delta + gamma * lam * live * last
        b_obs, b_act = obs_buf.reshape(-1, size), act_buf.reshape(-1, 2)
        b_logp, b_adv = logp_buf.reshape(-1), advantage.reshape(-1)
        b_ret = b_adv + val_buf.reshape(-1)
        batch = len(b_obs) // minibatches
        for _ in range(epochs):
            order = torch.randperm(len(b_obs))
            for k in range(minibatches):
                idx = order[k * batch:(k + 1) * batch]
                mean, log_std, value = model(b_obs[idx])
                ratio = (log_prob(mean, log_std, b_act[idx]) - b_logp[idx]).exp()
                adv = (b_adv[idx] - b_adv[idx].mean()) / (b_adv[idx].std() + 1e-8)
                policy_loss = -torch.min(ratio * adv, ratio.clamp(1 - clip, 1 + clip) * adv)
                value_loss = 0.5 * (value - b_ret[idx]) ** 2
                loss = policy_loss.mean() + 0.5 * value_loss.mean()
                optimizer.zero_grad()
                loss.backward()
                nn.utils.clip_grad_norm_(model.parameters(), 0.5)
                optimizer.step()

        if finished:
            curve["steps"].append(total_steps)
            curve["minutes"].append((time.time() - start) / 60)
            curve["return"].append(float(np.mean(finished)))
        if iteration % evaluate_every == 0:
            validate(total_steps)
        longest = max(longest, time.time() - began)

    if iteration % evaluate_every != 0:
        validate(total_steps)
    model.load_state_dict(best["state"])
    ret, goal, hole = evaluate(model.act, *test, TEST_EPISODES, holes)
    return {"curve": curve, "model": model, "return": ret, "goal": goal, "hole": hole,
            "random_return": rand_ret, "random_goal": rand_goal, "steps": total_steps,
            "iterations": iteration, "chosen": best["iteration"], "seconds": time.time() - start,
            "train_mazes": train_mazes, "test_mazes": len(test[0]), "holes": holes}


def plot(result, path):
    """The training episodes' and the validation's mean return, and the validation's success,
    against environment steps, wall minutes along the top."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c = result["curve"]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    top.plot(c["steps"], c["return"], linewidth=0.8,
             label="training episodes (sampled actions)")
    top.plot(c["eval_steps"], c["eval_return"], ".-", label="unseen mazes (mean action)")
    top.axhline(result["random_return"].mean(), color="grey", linestyle="--",
                label="random policy")
    top.set_ylabel("mean episode return")
    top.legend(loc="center right")
    bottom.plot(c["eval_steps"], c["eval_success"], ".-", color="C1",
                label="validation mazes (never trained on)")
    bottom.axhline(result["random_goal"].mean(), color="grey", linestyle="--",
                   label="random policy")
    bottom.axhline(TARGET, color="grey", linestyle=":", label="target")
    bottom.set_ylim(0, 1.02)
    bottom.set_ylabel("success rate")
    bottom.set_xlabel("environment steps (control periods of 1/55 s)")
    bottom.legend(loc="center right")
    steps = np.array(c["eval_steps"], float)
    minutes = np.array(c["eval_minutes"])
    if len(steps) > 1:
        top.secondary_xaxis("top", functions=(lambda s: np.interp(s, steps, minutes),
                                              lambda m: np.interp(m, minutes, steps))
                            ).set_xlabel("wall minutes")
    fig.suptitle("PPO on generated %s mazes (holes=%g), %d of them for training\nthe test: "
                 "success %.2f on %d episodes of %d other mazes" % (
                     CELLS, result["holes"], result["train_mazes"], result["goal"].mean(),
                     len(result["goal"]), result["test_mazes"]), fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def summary(result):
    return ("success %.2f on %d held-back episodes (%d maze seeds), return %.3f vs random %.3f, "
            "%d control steps in %.0f s" % (
                result["goal"].mean(), len(result["goal"]), result["test_mazes"],
                result["return"].mean(), result["random_return"].mean(), result["steps"],
                result["seconds"]))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--minutes", type=float, default=10.0,
                        help="wall-time budget, the final test included (default 10)")
    parser.add_argument("--seed", type=int, default=0, help="a whole number from 0 (default 0)")
    parser.add_argument("--out", default="doc/learning_curve.png",
                        help="where the learning curve goes ('' for nowhere)")
    parser.add_argument("--quick", action="store_true",
                        help="%d iterations (some seconds): the return must beat a random "
                        "policy's" % QUICK_ITERATIONS)
    parser.add_argument("--iterations", type=int,
                        help="stop after this many iterations (the budget still applies)")
    parser.add_argument("--holes", type=float, default=HOLES,
                        help="the mazes' share of holed dead ends (default %g)" % HOLES)
    args = parser.parse_args(argv)
    if args.seed < 0:
        parser.error("--seed: expected a whole number from 0")
    result = train(args.minutes, args.seed, args.quick, args.iterations, args.holes)
    if args.out:
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        plot(result, args.out)
    print("%d iterations on %d training mazes, the policy of iteration %d tested; held-back "
          "episodes in a hole %.2f, random policy's success %.2f" % (
              result["iterations"], result["train_mazes"], result["chosen"],
              result["hole"].mean(), result["random_goal"].mean()))
    print(summary(result))
    if args.quick:
        return 0 if result["return"].mean() > result["random_return"].mean() else 1
    return 0 if result["goal"].mean() >= TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
