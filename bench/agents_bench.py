"""Control steps a second of marble_maze.agents.VectorMazeEnv from Python (random actions, the
classic maze at `fast`, 55 Hz), with 1, 8 and 64 environments on 1 and 2 threads, against the
hand-written C++ loop on one Session (marble_maze_bench's BM_AgentControlStep/envs:0) timed in
the same run. Each case is the best of three spells of wall time. Last, two processes at once,
each VectorMazeEnv(64) on one thread: what the machine's two cores give together, the most that
two threads could gain. `make bench` runs it.

usage: agents_bench.py MARBLE_MAZE_BENCH [--seconds S]
"""
import argparse
import json
import multiprocessing
import subprocess
import sys
import tempfile
import time

import numpy as np

import marble_maze.agents as agents

CASES = [(1, 1), (8, 1), (64, 1), (64, 2)]  # (environments, threads)


def python_rate(num_envs, num_threads, seconds):
    """The best of three spells of `seconds`: control steps (environments x calls) a second."""
    envs = agents.VectorMazeEnv(num_envs, num_threads=num_threads, seed=0)
    envs.reset(seed=1)
    # (Drawn ahead, 1,024 periods of them, 19 s of play: the table's cycle is longer than most
    # episodes, so the games are as random as fresh draws, whose cost is not the module's.)
    actions = np.random.default_rng(0).uniform(-1, 1, (1024, num_envs, 2))
    best = 0.0
    for _ in range(3):
        calls, begin = 0, time.perf_counter()
        while time.perf_counter() - begin < seconds:
            envs.step(actions[calls % len(actions)])
            calls += 1
        best = max(best, calls * num_envs / (time.perf_counter() - begin))
    return best


def _one_thread_of_64(seconds):
    return python_rate(64, 1, seconds)


def two_processes_rate(seconds):
    """Control steps a second of two processes at once, each VectorMazeEnv(64) on one thread."""
    with multiprocessing.get_context("fork").Pool(2) as pool:
        return sum(pool.map(_one_thread_of_64, [seconds, seconds]))


def cpp_loop_rate(bench):
    """The hand-written C++ loop's control steps a second, as marble_maze_bench times it."""
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([bench, "--benchmark_filter=BM_AgentControlStep/envs:0/",
                        "--benchmark_repetitions=3", "--benchmark_out=" + out.name,
                        "--benchmark_out_format=json"], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        runs = json.load(out)["benchmarks"]
    seconds = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    return 1 / min(r["real_time"] * seconds[r["time_unit"]] for r in runs
                   if r.get("run_type") == "iteration")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bench", help="the marble_maze_bench executable")
    parser.add_argument("--seconds", type=float, default=1.0, help="a spell's wall time")
    args = parser.parse_args()
    loop = cpp_loop_rate(args.bench)
    print("marble_maze.agents from Python, random actions, fast, 55 Hz (best of 3 x %g s):"
          % args.seconds)
    print("%-44s %12.0f control steps/s  1.00" % ("the hand-written C++ loop (one Session):", loop))
    one_thread = {}
    for num_envs, num_threads in CASES:
        rate = python_rate(num_envs, num_threads, args.seconds)
        label = "VectorMazeEnv(%d), %d thread%s:" % (
            num_envs, num_threads, "s" if num_threads > 1 else "")
        line = "%-44s %12.0f control steps/s  %.2f" % (label, rate, rate / loop)
        if num_threads == 1:
            one_thread[num_envs] = rate
        else:
            line += " (%.2f times one thread)" % (rate / one_thread[num_envs])
        print(line)
    both = two_processes_rate(args.seconds)
    print("%-44s %12.0f control steps/s  %.2f (%.2f times one thread: the two cores' most)"
          % ("two processes at once, 1 thread each:", both, both / loop, both / one_thread[64]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
