#!/usr/bin/env python3
"""examples/train.py's quick run: a few PPO iterations on generated mazes, then a policy that
earns clearly more than a random one on mazes and starts it never trained on, and a learning
curve drawn (about 10 s on one core)."""
import os
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "examples"))

import train  # noqa: E402 (examples/ is no package: found through the path set just above)

# The trained policy's mean return over the random policy's on the same held-back episodes.
# Measured with 12 iterations, seeds 0 to 3: 4.05 vs 0.51, 4.05 vs 0.72, 4.01 vs 0.71, 3.75 vs
# 0.54, a lead of 3.2 to 3.5 (a return is 10 a metre of the route and 1 at the goal). 2, 20 cm
# of route an episode more than random play, leaves room for another machine's floating point.
MARGIN = 2.0


class TrainingTest(unittest.TestCase):
    def test_the_quick_run_beats_a_random_policy_on_unseen_mazes(self):
        result = train.train(seed=0, quick=True, log=lambda *args: None)
        print(train.summary(result))
        self.assertEqual(len(result["return"]), 50)  # 10 held-back mazes, 5 starts each
        self.assertGreater(result["return"].mean(), result["random_return"].mean() + MARGIN)
        self.assertGreater(result["goal"].mean(), result["random_goal"].mean())
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "curve.png")
            train.plot(result, path)
            with open(path, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_the_same_seed_trains_the_same_policy(self):
        a = train.train(seed=1, quick=True, iterations=2, log=lambda *args: None)
        b = train.train(seed=1, quick=True, iterations=2, log=lambda *args: None)
        for (name, x), (_, y) in zip(a["model"].state_dict().items(),
                                     b["model"].state_dict().items()):
            self.assertTrue(bool((x == y).all()), name)
        self.assertEqual(list(a["return"]), list(b["return"]))


if __name__ == "__main__":
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    import xml_results
    xml_results.main()
