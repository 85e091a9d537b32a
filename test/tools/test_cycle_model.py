"""Unit tests of scripts/cycle_model.py, the model of the processor make model runs: on steps
made up here, whose cycles follow from the machine's rules in closed form (a chain of dependent
adds takes their latencies summed; independent ones, the width or the floating-point ports; a
load waits for the store that wrote its bytes; a full window holds back what follows).

Plain unittest, no ROS and no Capstone: python3 test/tools/test_cycle_model.py. With
--gtest_output=xml:FILE it writes JUnit XML for catkin.
"""
import importlib.util
import os
import subprocess
import sys
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                      "cycle_model.py")


def load_model():
    spec = importlib.util.spec_from_file_location("cycle_model", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    dont_write_bytecode, sys.dont_write_bytecode = sys.dont_write_bytecode, True
    try:
        spec.loader.exec_module(module)
    finally:
        sys.dont_write_bytecode = dont_write_bytecode
    return module


model = load_model()
BUDGETS = os.path.join(os.path.dirname(SCRIPT), "..", "bench", "instruction_budgets.txt")
Op = model.Op


def cycles(ops, **machine):
    return model.run(ops, **machine)[0]


class ChainTest(unittest.TestCase):
    def test_dependent_adds_take_their_latencies_summed(self):
        ops = [Op("addsd", reads={"xmm0"}, writes={"xmm0"}) for _ in range(100)]
        self.assertEqual(cycles(ops, width=None, window=0), 400)
        # The width and the window add nothing to a chain this narrow (5 a cycle keeps ahead).
        self.assertAlmostEqual(cycles(ops), 400, delta=1)

    def test_a_square_root_and_a_quotient_on_the_chain(self):
        ops = [Op("sqrtsd", reads={"xmm0"}, writes={"xmm0"}),
               Op("divsd", reads={"xmm0", "xmm1"}, writes={"xmm0"}),
               Op("mulsd", reads={"xmm0"}, writes={"xmm0"})]
        self.assertEqual(cycles(ops, width=None, window=0), 16 + 14 + 4)

    def test_a_move_between_registers_costs_nothing_on_the_chain(self):
        ops = [Op("addsd", reads={"xmm0"}, writes={"xmm0"}),
               Op("movapd", reads={"xmm0"}, writes={"xmm1"}),
               Op("addsd", reads={"xmm1"}, writes={"xmm1"})]
        self.assertEqual(cycles(ops, width=None, window=0), 8)

    def test_nothing_waits_on_a_branch(self):
        ops = [Op("sqrtsd", reads={"xmm0"}, writes={"xmm0"}),
               Op("ucomisd", reads={"xmm0"}, writes={"flags"}),
               Op("ja", reads={"flags"}),
               Op("sqrtsd", reads={"xmm2"}, writes={"xmm2"})]
        self.assertEqual(cycles(ops, width=None, window=0), 16 + 3)


class WidthTest(unittest.TestCase):
    def test_independent_integer_ops_go_width_a_cycle(self):
        ops = [Op("add", reads={"r%d" % (8 + i % 8)}, writes={"r%d" % (8 + i % 8)})
               for i in range(1000)]
        # 8 chains of 125 one-cycle adds: the width, 5 a cycle, holds them to 1000 / 5.
        self.assertAlmostEqual(cycles(ops, width=5, window=0), 200, delta=2)

    def test_floating_point_ops_go_two_a_cycle(self):
        ops = [Op("mulsd", reads={"xmm%d" % (i % 16)}, writes={"xmm%d" % (i % 16)})
               for i in range(1000)]
        # 16 chains of 4-cycle products could start 4 a cycle; the two ports allow 2.
        self.assertAlmostEqual(cycles(ops, width=5, window=0), 500, delta=5)
        self.assertAlmostEqual(cycles(ops, width=5, window=0, fp_ports=0), 250, delta=5)


class MemoryTest(unittest.TestCase):
    def test_a_load_waits_for_the_store_that_wrote_its_bytes(self):
        ops = [Op("mulsd", reads={"xmm0"}, writes={"xmm0"}),
               Op("movsd", reads={"xmm0", "rsp"}, stores=[(1000, 8)]),
               Op("movsd", reads={"rsp"}, writes={"xmm1"}, loads=[(1000, 8)]),
               Op("addsd", reads={"xmm1"}, writes={"xmm1"})]
        # The product (4), the store's data then, the load 5 later, the sum 4 more.
        self.assertEqual(cycles(ops, width=None, window=0), 4 + 5 + 4)

    def test_a_load_of_two_stores_waits_for_the_later_and_the_penalty(self):
        ops = [Op("mulsd", reads={"xmm0"}, writes={"xmm0"}),
               Op("movss", reads={"xmm0"}, stores=[(1000, 4)]),
               Op("movss", reads={"xmm2"}, stores=[(1004, 4)]),
               Op("movsd", writes={"xmm1"}, loads=[(1000, 8)])]
        self.assertEqual(cycles(ops, width=None, window=0), 4 + 12)
        # Without the penalty the load takes its own latency, the stores' data being ready first.
        self.assertEqual(cycles(ops, width=None, window=0, mixed_store_penalty=0), 5)

    def test_a_load_of_memory_no_op_wrote_takes_the_load_latency(self):
        ops = [Op("addsd", reads={"xmm1"}, writes={"xmm1"}, loads=[(64, 8)])]
        self.assertEqual(cycles(ops, width=None, window=0), 5 + 4)


class WindowTest(unittest.TestCase):
    def test_a_full_window_holds_back_what_follows(self):
        # Eight independent 20-cycle divisions: all at once, 20 cycles; four in flight at a time,
        # two rounds of them.
        ops = [Op("div", reads={"r%d" % (8 + i)}, writes={"r%d" % (8 + i)}) for i in range(8)]
        self.assertEqual(cycles(ops, width=None, window=0), 20)
        self.assertEqual(cycles(ops, width=None, window=8), 20)
        self.assertEqual(cycles(ops, width=None, window=4), 40)

    def test_links_of_a_chain_far_apart_wait_on_the_window(self):
        # Ten links of 8 dependent square roots (128 cycles each), 400 independent adds after
        # each. The chain alone: 1280 cycles. The width alone adds the last adds' retiring, 80.
        # With the window of 352 too, the adds behind a link in flight fill it, and the 48 the
        # window could not take go in only when the link retires, 5 a cycle, before the next
        # link can start: 9.6 cycles more a link.
        ops = []
        for _ in range(10):
            ops += [Op("sqrtsd", reads={"xmm0"}, writes={"xmm0"}) for _ in range(8)]
            ops += [Op("add", reads={"r8"}, writes={"r9"}) for _ in range(400)]
        self.assertEqual(cycles(ops, width=None, window=0), 1280)
        self.assertAlmostEqual(cycles(ops, width=5, window=0), 1280 + 400 / 5, delta=3)
        self.assertAlmostEqual(cycles(ops, width=None, window=352), 1280, delta=3)
        self.assertAlmostEqual(cycles(ops, width=5, window=352),
                               9 * (128 + (400 - 352) / 5) + 128 + 400 / 5, delta=3)


class FiguresTest(unittest.TestCase):
    def test_free_functions_take_no_slot_and_no_time(self):
        ops = [Op("addsd", reads={"xmm0"}, writes={"xmm0"}, function="kept") for _ in range(10)]
        ops += [Op("sqrtsd", reads={"xmm0"}, writes={"xmm0"}, free=True, function="taken out")
                for _ in range(10)]
        f, _ = model.figures([ops], steps=2)
        self.assertEqual(f["chain"], 40 / 2)
        self.assertAlmostEqual(f["model"], 40 / 2, delta=1)

    def test_samples_are_each_run_from_an_idle_machine_and_summed(self):
        # Two samples of the same 4 dependent adds, which store their sum and load it back (as a
        # step's state does): the second's load is of its own store, not the first sample's.
        def sample():
            return [Op("movsd", writes={"xmm0"}, loads=[(1000, 8)]),
                    *[Op("addsd", reads={"xmm0"}, writes={"xmm0"}) for _ in range(4)],
                    Op("movsd", reads={"xmm0"}, stores=[(1000, 8)])]
        f, chain = model.figures([sample(), sample()], steps=2)
        self.assertEqual(f["chain"], 5 + 16)  # each sample's load, 5, then its adds
        self.assertEqual(chain, [("?", 2 * 21.0)])

    def test_the_chain_is_told_by_function(self):
        ops = [Op("sqrtsd", reads={"xmm0"}, writes={"xmm0"}, function="solve"),
               Op("addsd", reads={"xmm0"}, writes={"xmm0"}, function="path"),
               Op("addsd", reads={"xmm5"}, writes={"xmm5"}, function="aside")]
        _, waited_on, ready_at = model.run(ops, width=None, window=0)
        self.assertEqual(model.chain_by_function(ops, waited_on, ready_at),
                         [("solve", 16.0), ("path", 4.0)])


class MachineTest(unittest.TestCase):
    def test_another_processors_rules_come_from_json(self):
        # Eight independent 20-cycle divisions, as above: a window of 4 (given as --machine
        # would give it) takes them in two rounds, the default window of 352 in one.
        ops = [Op("div", reads={"r%d" % (8 + i)}, writes={"r%d" % (8 + i)}) for i in range(8)]
        small = model.machine_from_json('{"window": 4, "width": 5}')
        self.assertEqual(small, {"window": 4, "width": 5})
        self.assertAlmostEqual(model.figures([ops], steps=1)[0]["model"], 20, delta=2)
        self.assertAlmostEqual(model.figures([ops], steps=1, machine=small)[0]["model"], 40,
                               delta=2)

    def test_a_rule_the_model_has_not_or_a_wrong_value_is_refused_naming_it(self):
        for text, named in (('{"windw": 4}', "'windw'"), ('{"window": -1}', "window"),
                            ('{"width": 0}', "width"), ('{"fp_ports": "two"}', "fp_ports"),
                            ("[224]", "not a JSON object"), ("window=224", "not JSON")):
            with self.assertRaises(ValueError, msg=text) as caught:
                model.machine_from_json(text)
            self.assertIn(named, str(caught.exception))


class TracedStepTest(unittest.TestCase):
    """The whole of make model on a few steps of free flight: the driver, lackey, Capstone."""

    def test_a_traced_step_obeys_the_models_bounds(self):
        workspace = os.environ.get("MARBLE_MAZE_WS")
        if not workspace:
            self.skipTest("MARBLE_MAZE_WS is not set (catkin's run_tests sets it)")
        script = os.path.join(os.path.dirname(SCRIPT), "cycle_model.sh")
        env = dict(os.environ, STEPS="200", SAMPLES="4", WINDOW="10")
        out = subprocess.run(["bash", script, "free_flight"], env=env, capture_output=True,
                             text=True, timeout=300)
        self.assertEqual(out.returncode, 0, out.stderr)
        line = out.stdout.splitlines()[-1].split()
        self.assertEqual(line[0], "free_flight")
        instructions, chain, width, window, both = (float(x) for x in line[1:])
        # The step's instructions as make instructions counts them (its budget is 10% above
        # them), plus the loop's few around the step: the trace was read whole.
        budget = next(float(rule.split()[2]) for rule in open(BUDGETS)
                      if rule.startswith("budget BM_FreeFlight "))
        self.assertGreater(instructions, budget / 1.1 * 0.95)
        self.assertLess(instructions, budget * 1.1)
        # Each limit alone costs no more than all of them; the width alone at least its count.
        self.assertGreater(chain, 0)
        self.assertLessEqual(chain, window + 1e-9)
        self.assertGreaterEqual(width, instructions / 5 - 1)
        self.assertLessEqual(max(width, window), both + 1e-9)


if __name__ == "__main__":
    if any(arg.startswith("--gtest_output=xml:") for arg in sys.argv):
        import rosunit
        rosunit.unitrun("marble_maze", "test_cycle_model", "__main__")
    else:
        unittest.main()
