"""Control steps a second of marble_maze.agents.VectorMazeEnv from Python (random actions, the
classic maze at `fast`, 55 Hz), with 1, 8 and 64 environments on 1 and 2 threads, against the
hand-written C++ loop on one Session (marble_maze_bench's BM_AgentControlStep/envs:0) timed in
the same run, both on the first core (the case of two threads on the first two). Each case is
the best of three spells of wall time.

Then what two threads gain, in turns of short spells so that every figure of a round meets the
same machine, all on the first two cores: VectorMazeEnv(64) on one thread pinned to each core,
then on two threads, then two processes at once, each VectorMazeEnv(64) on one thread (the most
two threads could give). One thread's rate is the mean over the two cores: on a virtual machine
one core can run a third slower than the other for minutes, and a thread left to the scheduler
would measure whichever it landed on. `make bench` runs it.

usage: agents_bench.py MARBLE_MAZE_BENCH [--seconds S] [--rounds N] [--spell S]
"""
import argparse
import contextlib
import json
import multiprocessing
import multiprocessing.connection
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import marble_maze.agents as agents

CASES = [(1, 1), (8, 1), (64, 1), (64, 2)]  # (environments, threads)


class Player:
    """A VectorMazeEnv under random actions, played in spells of wall time."""

    def __init__(self, num_envs, num_threads):
        self.envs = agents.VectorMazeEnv(num_envs, num_threads=num_threads, seed=0)
        self.envs.reset(seed=1)
        # (Drawn ahead, 1,024 periods of them, 19 s of play: the table's cycle is longer than
        # most episodes, so the games are as random as fresh draws, whose cost is not the
        # module's.)
        self.actions = np.random.default_rng(0).uniform(-1, 1, (1024, num_envs, 2))
        self.calls = 0

    def spell(self, seconds):
        """Control steps (environments x calls) a second over `seconds` of play."""
        calls, begin = 0, time.perf_counter()
        while time.perf_counter() - begin < seconds:
            self.envs.step(self.actions[(self.calls + calls) % len(self.actions)])
            calls += 1
        self.calls += calls
        return calls * self.envs.num_envs / (time.perf_counter() - begin)


def best_rate(num_envs, num_threads, seconds):
    """The best of three spells of `seconds`: control steps a second."""
    player = Player(num_envs, num_threads)
    return max(player.spell(seconds) for _ in range(3))


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


def _play_on_request(connection):
    """A process of its own: plays a spell of the length each request names, until None."""
    player = Player(64, 1)
    for seconds in iter(connection.recv, None):
        connection.send(player.spell(seconds))


def _answer(link, worker):
    """The worker's answer, or an error if it has died (whoever else holds its pipe's ends)."""
    if link not in multiprocessing.connection.wait([link, worker.sentinel]):
        raise RuntimeError("a worker of the two processes died (exit code %s)" % worker.exitcode)
    return link.recv()


def in_turns(cores, rounds, seconds):
    """Rounds of spells: one thread pinned to each of the two `cores`, two threads, two
    processes at once, all on those cores. Returns, over the rounds, two threads' and two
    processes' rates against one thread's (its mean over the cores), and the first core's rate
    against the second's."""
    allowed = os.sched_getaffinity(0)
    links, workers = [], []
    threads, processes, cores_apart = [], [], []
    try:
        os.sched_setaffinity(0, cores)  # (inherited by the processes and by `two`'s thread)
        # Forked while no thread of the module's runs: the earlier cases' went with their
        # Players.
        context = multiprocessing.get_context("fork")
        for _ in range(2):
            link, child = context.Pipe()
            worker = context.Process(target=_play_on_request, args=(child,), daemon=True)
            worker.start()
            child.close()
            links.append(link)
            workers.append(worker)
        one, two = Player(64, 1), Player(64, 2)
        for _ in range(rounds):
            on_core = []
            for core in cores:
                os.sched_setaffinity(0, {core})  # this thread alone: the one that steps `one`
                on_core.append(one.spell(seconds))
            os.sched_setaffinity(0, cores)
            one_thread = statistics.mean(on_core)
            threads.append(two.spell(seconds) / one_thread)
            for link in links:
                link.send(seconds)
            processes.append(sum(map(_answer, links, workers)) / one_thread)
            cores_apart.append(on_core[0] / on_core[-1])
    finally:
        os.sched_setaffinity(0, allowed)
        for link in links:
            with contextlib.suppress(OSError):
                link.send(None)
        for worker in workers:
            worker.join(timeout=10)
            if worker.is_alive():
                worker.terminate()
                worker.join()
    return threads, processes, cores_apart


def spread(values):
    """The median with the quartiles (of the values themselves: inclusive), as text."""
    low, median, high = statistics.quantiles(values, n=4, method="inclusive")
    return "%.2f (quartiles %.2f to %.2f)" % (median, low, high)


def at_least_two(text):
    """argparse's type for --rounds: quartiles need two rounds."""
    value = int(text)
    if value < 2:
        raise argparse.ArgumentTypeError("%s: expected at least 2" % text)
    return value


def positive(text):
    """argparse's type for a spell's seconds."""
    value = float(text)
    if not value > 0:
        raise argparse.ArgumentTypeError("%s: expected a positive number of seconds" % text)
    return value


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bench", help="the marble_maze_bench executable")
    parser.add_argument("--seconds", type=positive, default=1.0,
                        help="a case's spell of wall time")
    parser.add_argument("--rounds", type=at_least_two, default=40,
                        help="rounds of the spells in turns")
    parser.add_argument("--spell", type=positive, default=0.05, help="a spell in turns, seconds")
    args = parser.parse_args()
    allowed = os.sched_getaffinity(0)
    cores = sorted(allowed)[:2]
    os.sched_setaffinity(0, cores[:1])  # (inherited by the C++ loop's process)
    loop = cpp_loop_rate(args.bench)
    print("marble_maze.agents from Python, random actions, fast, 55 Hz (best of 3 x %g s; one "
          "thread on the first core):" % args.seconds)
    print("%-44s %12.0f control steps/s  1.00" % ("the hand-written C++ loop (one Session):", loop))
    for num_envs, num_threads in CASES:
        os.sched_setaffinity(0, cores[:num_threads])  # (inherited by the pool's threads)
        rate = best_rate(num_envs, num_threads, args.seconds)
        label = "VectorMazeEnv(%d), %d thread%s:" % (
            num_envs, num_threads, "s" if num_threads > 1 else "")
        print("%-44s %12.0f control steps/s  %.2f" % (label, rate, rate / loop))
    os.sched_setaffinity(0, allowed)
    if len(cores) < 2:
        print("VectorMazeEnv(64) in turns: needs two cores, this process has one")
        return 0
    threads, processes, cores_apart = in_turns(cores, args.rounds, args.spell)
    print("VectorMazeEnv(64) in turns, %d rounds of %g s spells, against one thread (the mean "
          "of a spell on each core):" % (args.rounds, args.spell))
    print("  two threads:   %s times one thread" % spread(threads))
    print("  two processes: %s times one thread: the two cores' most" % spread(processes))
    print("  the first core: %s times the second's speed" % spread(cores_apart))
    return 0


if __name__ == "__main__":
    sys.exit(main())
