#!/usr/bin/python3
"""What holds a step's time, worked out by a model of the processor from what the step runs.

These machines give no hardware counters, and a timed run says how long, not why. So: valgrind's
lackey lists every instruction a traced run executes, in order, with the bytes each reads and
writes; Capstone names the registers each reads and writes; and a model issues them in program
order into an out-of-order core and retires them in order:

- `width` instructions a cycle are taken in and retired;
- at most `window` of them are in flight (the reorder buffer);
- at most `fp_ports` floating-point operations start in a cycle (adds, multiplies, quotients,
  square roots, minima, maxima and comparisons all run on the same two ports);
- each result is ready `latency` cycles after its operands (LATENCY below, for the processors
  of these machines); a load is ready `load_latency` after its address, or after the store that
  wrote its bytes, and `mixed_store_penalty` later when several stores wrote them (the processor
  cannot forward those);
- branches, calls and returns are predicted: nothing waits on them.

It reports, in cycles a step: the chain of dependent values alone (no limit on width or window),
the width alone, the window alone, and both: the model. Run by scripts/cycle_model.sh
(make model); its own tests are test/tools/test_cycle_model.py.

    cycle_model.py DRIVER_OUTPUT TRACE [--free REGEX] [--chain] [--machine JSON]

DRIVER_OUTPUT is what marble_maze_cycle_driver printed (where its objects and marks are loaded),
TRACE lackey's log of the same run. --free takes the work of the functions whose names match out
of the model (no slot, no window entry, no time): what a stage costs. --chain lists the functions
the chain runs through. --machine sets rules other than the defaults (those of the Intel cores
these machines mostly had: width 5, window 352, 2 floating-point ports, loads 5 cycles, 12 more
for several stores' bytes), another processor's: {"window": 224} is an AMD Zen 2's reorder
buffer.
"""
import argparse
import bisect
import collections
import inspect
import json
import re
import subprocess
import sys

# Cycles from operands to result; anything not named takes one. A move between registers is
# renamed away (none); a load's own cost is load_latency.
LATENCY = {"divsd": 14, "divpd": 14, "sqrtsd": 16, "sqrtpd": 16, "div": 20, "idiv": 20,
           "ucomisd": 3, "comisd": 3, "imul": 3}
for _m in ("addsd subsd mulsd addpd subpd mulpd minsd maxsd minpd maxpd cmpsd cmppd cmpltsd "
           "cmplesd cmpnlesd cmpnltsd cmpltpd cmplepd haddpd hsubpd roundsd cvtsi2sd cvttsd2si "
           "cvtsd2si cvtdq2pd cvttpd2dq cvtpd2dq cvtsd2ss cvtss2sd addss subss mulss").split():
    LATENCY[_m] = 4
MOVES = set("mov movapd movaps movq movsd movupd movups movdqa movdqu movss movd".split())
# Instructions whose work is the load itself (their result is the loaded value).
LOAD_ONLY = MOVES | set("movzx movsx movsxd movhpd movlpd movhps movlps pop ret".split())
FP_PORTS = ("add", "sub", "mul", "div", "min", "max", "cmp", "sqrt", "ucomi", "comi")


class Op:
    """One executed instruction, as the model sees it."""
    __slots__ = ("latency", "reads", "writes", "loads", "stores", "fp", "branch", "load_only",
                 "free", "function")

    def __init__(self, mnemonic="nop", reads=(), writes=(), loads=(), stores=(), free=False,
                 function="?"):
        self.latency = 0 if mnemonic in MOVES else LATENCY.get(mnemonic, 1)
        self.reads, self.writes = frozenset(reads), frozenset(writes)
        self.loads, self.stores = tuple(loads), tuple(stores)  # (address, bytes)
        self.fp = mnemonic.endswith(("sd", "pd")) and mnemonic.startswith(FP_PORTS)
        self.branch = mnemonic.startswith("j") or mnemonic in ("call", "ret")
        self.load_only = mnemonic in LOAD_ONLY
        self.free, self.function = free, function


def run(ops, width=5.0, window=352, fp_ports=2, load_latency=5, mixed_store_penalty=12):
    """Cycles the ops take on the machine, and for each op the op its start waited on (-1: none)
    and the cycle its result was ready. width=None: no limit; window=0: none; fp_ports=0: none."""
    per_op = 0.0 if width is None else 1.0 / width
    reg_ready, reg_source = collections.defaultdict(float), {}
    byte_store = {}  # address -> (index of the store, cycle its data is ready)
    in_flight = collections.deque()  # retire cycles of the ops in the window, oldest first
    fp_started = collections.Counter()  # per whole cycle
    waited_on, ready_at = [-1] * len(ops), [0.0] * len(ops)
    taken = retired = 0.0
    for i, op in enumerate(ops):
        cost = 0.0 if op.free else per_op
        taken = max(taken + cost, in_flight[0] if window and len(in_flight) == window else 0.0)
        operands, source = 0.0, -1
        if not op.branch:
            for r in op.reads:
                if reg_ready[r] > operands:
                    operands, source = reg_ready[r], reg_source.get(r, -1)
        start = max(taken, operands)
        load_wait = 0 if op.free else load_latency
        for address, size in () if op.branch else op.loads:
            stores = {byte_store[b] for b in range(address, address + size) if b in byte_store}
            loaded, loaded_from = max(operands, taken) + load_wait, source
            if len(stores) == 1:
                store, data = next(iter(stores))
                if data + load_wait > loaded:
                    loaded, loaded_from = data + load_wait, store
            elif stores:
                recent = [s for s in stores if i - s[0] < (window or len(ops))]
                if recent:
                    late = max(data for _, data in recent) + mixed_store_penalty
                    if late > loaded:
                        loaded, loaded_from = late, max(index for index, _ in recent)
                else:
                    loaded = max(loaded, max(data for _, data in stores) + load_wait)
            if loaded > start:
                start, source = loaded, loaded_from
        latency = 0 if op.free or (op.loads and op.load_only) else op.latency
        if op.fp and fp_ports and not op.free:
            cycle = int(start)
            while fp_started[cycle] >= fp_ports:
                cycle += 1
            fp_started[cycle] += 1
            start += cycle - int(start)
        done = start + latency
        waited_on[i], ready_at[i] = source, done
        for r in op.writes:
            # (The stack pointer is renamed by its own engine: no op waits for another's push,
            # and it is no link of a chain.)
            stack = r == "rsp"
            reg_ready[r] = taken if stack else done
            reg_source[r] = -1 if stack else i
        for address, size in op.stores:
            for b in range(address, address + size):
                byte_store[b] = (i, done)
        retired = max(retired + cost, done)
        if window and not op.free:
            in_flight.append(retired)
            if len(in_flight) > window:
                in_flight.popleft()
    return retired, waited_on, ready_at


def chain_by_function(ops, waited_on, ready_at):
    """Cycles of the longest chain spent in each function, costliest first."""
    i = max(range(len(ops)), key=ready_at.__getitem__) if ops else -1
    spent = collections.Counter()
    while i >= 0:
        before = waited_on[i]
        spent[ops[i].function] += ready_at[i] - (ready_at[before] if before >= 0 else 0.0)
        i = before
    return spent.most_common()


def figures(samples, steps, machine=None):
    """The model's four figures, cycles a step (chain, width alone, window alone, and both: the
    model), over samples of ops that are each run from an idle machine (they are not contiguous:
    what one's last step stored is not what the next one's first step loads), and the cycles of
    their chains by function, costliest first."""
    machine = dict(machine or {})
    width, window = machine.pop("width", 5.0), machine.pop("window", 352)
    ports = machine.pop("fp_ports", 2)
    cycles = collections.Counter()
    by_function = collections.Counter()
    for ops in samples:
        def limited(w, n):  # (the ports limit how many start in a cycle: a width, lifted with it)
            return run(ops, width=w, window=n, fp_ports=ports if w else 0, **machine)

        chain, waited_on, ready_at = limited(None, 0)
        cycles["chain"] += chain
        cycles["width"] += limited(width, 0)[0]
        cycles["window"] += limited(None, window)[0]
        cycles["model"] += limited(width, window)[0]
        by_function.update(dict(chain_by_function(ops, waited_on, ready_at)))
    return {k: cycles[k] / steps for k in ("chain", "width", "window", "model")}, \
        by_function.most_common()


class Objects:
    """The traced program's objects as loaded: each traced address's instruction and function."""

    def __init__(self, loaded):
        import capstone  # (only here: the model itself, and its tests, need no Capstone)
        self._capstone = capstone
        self._decoder = capstone.Cs(capstone.CS_ARCH_X86, capstone.CS_MODE_64)
        self._decoder.detail = True
        self._objects = []
        for base, path in loaded:
            header = subprocess.run(["readelf", "-hSW", path], capture_output=True, text=True,
                                    check=True).stdout
            # A position-independent object's addresses are offsets from where it is loaded.
            bias = 0 if re.search(r"Type:\s+EXEC", header) else base
            text = re.search(r"\.text\s+PROGBITS\s+([0-9a-f]+)\s+([0-9a-f]+)\s+([0-9a-f]+)", header)
            start, offset, size = (int(x, 16) for x in text.groups())
            with open(path, "rb") as f:
                f.seek(offset)
                code = f.read(size)
            names = {}
            symbols = subprocess.run(["nm", "-C", "--defined-only", path], capture_output=True,
                                     text=True, check=True).stdout
            for line in symbols.splitlines():
                parts = line.split(" ", 2)
                if len(parts) == 3 and parts[1] in "tTwW":
                    names.setdefault(int(parts[0], 16) + bias, parts[2])
            self._objects.append((start + bias, code, sorted(names), names))
        self._registers = self._register_names()
        self._decoded = {}

    @staticmethod
    def _register_names():
        """Each register's name to the whole register it is part of."""
        whole = {"eflags": "flags", "rflags": "flags"}
        for r in ("ax", "bx", "cx", "dx"):
            for name in ("r" + r, "e" + r, r, r[0] + "l", r[0] + "h"):
                whole[name] = "r" + r
        for r in ("si", "di", "bp", "sp"):
            for name in ("r" + r, "e" + r, r, r + "l"):
                whole[name] = "r" + r
        for i in range(8, 16):
            for name in ("r%d" % i, "r%dd" % i, "r%dw" % i, "r%db" % i):
                whole[name] = "r%d" % i
        for i in range(32):
            for prefix in "xyz":
                whole["%smm%d" % (prefix, i)] = "xmm%d" % i
        return whole

    def decode(self, address):
        """(mnemonic, reads, writes, function) of the instruction at a loaded address."""
        known = self._decoded.get(address)
        if known:
            return known
        found = ("?", (), (), "(outside the traced objects)")  # libm, libc: no dependencies
        for start, code, starts, names in self._objects:
            if start <= address < start + len(code):
                ins = next(self._decoder.disasm(code[address - start:address - start + 16], address))
                reads, writes = ins.regs_access()
                name = lambda r: self._registers.get(ins.reg_name(r), ins.reg_name(r))  # noqa
                reads = {name(r) for r in reads} - {"rip"}
                writes = {name(r) for r in writes} - {"rip"}
                x86 = self._capstone.x86
                operands = ins.operands
                # xor r, r and the like: a new value that waits on nothing
                if (ins.mnemonic in ("xor", "pxor", "xorpd", "xorps", "sub") and
                        len(operands) == 2 and all(o.type == x86.X86_OP_REG for o in operands) and
                        operands[0].reg == operands[1].reg):
                    reads = set()
                k = bisect.bisect_right(starts, address) - 1
                found = (ins.mnemonic, reads, writes, names[starts[k]] if k >= 0 else "?")
                break
        self._decoded[address] = found
        return found


def read_driver_output(path):
    """The loaded objects [(base, path)] and the two marks' addresses the driver printed."""
    loaded, marks = [], {}
    for line in open(path):
        words = line.split(None, 2)
        if words and words[0] == "object":
            loaded.append((int(words[1], 16), words[2].strip()))
        elif words and words[0] in ("mark", "end"):
            marks[words[0]] = int(words[1], 16)
    if not loaded or len(marks) != 2:
        sys.exit("%s: no 'object', 'mark' or 'end' line: not marble_maze_cycle_driver's output"
                 % path)
    return loaded, marks["mark"], marks["end"]


def read_trace(path, mark, end, objects, free=None):
    """The ops of each traced window (from a call of the mark to a call of the end), and the steps
    they hold (one a call of the mark)."""
    windows, steps, inside, current = [], 0, False, None
    mark_line = "I  %08x," % mark  # (as lackey writes it: the lines between windows are skipped)
    pattern = re.compile(free) if free else None
    with open(path) as f:
        for line in f:
            if not inside:
                if not line.startswith(mark_line):
                    continue
                inside = True
                windows.append([])
            if line.startswith("I"):
                address = int(line[3:line.index(",")], 16)
                if address == end:
                    inside = False
                    continue
                steps += address == mark
                mnemonic, reads, writes, function = objects.decode(address)
                current = Op(mnemonic, reads, writes, free=bool(
                    pattern and pattern.search(function)), function=function)
                current.loads, current.stores = [], []
                windows[-1].append(current)
            elif line[:1] == " " and line[1:2] in "LSM":
                address, size = line[3:].split(",")
                access = (int(address, 16), int(size))
                if line[1] in "LM":
                    current.loads.append(access)
                if line[1] in "SM":
                    current.stores.append(access)
    if steps == 0:
        sys.exit("%s: the mark was never called: no step was traced" % path)
    return windows, steps


# The rules a machine may set: run()'s keywords, taken from it so that the two cannot differ.
MACHINE_RULES = tuple(inspect.signature(run).parameters)[1:]


def machine_from_json(text):
    """The machine's rules that JSON text sets over the defaults (run()'s keywords), e.g. a
    smaller window {"window": 224}; a rule the model has not, or a value not a positive number
    (a window of 0: none), is refused naming it."""
    try:
        machine = json.loads(text)
    except ValueError as e:
        raise ValueError("--machine: not JSON (%s): %r" % (e, text))
    if not isinstance(machine, dict):
        raise ValueError("--machine: not a JSON object of rules: %r" % text)
    for key, value in machine.items():
        if key not in MACHINE_RULES:
            raise ValueError("--machine: no rule %r (the rules: %s)" % (key, ", ".join(MACHINE_RULES)))
        if isinstance(value, bool) or not isinstance(value, (int, float)) or value < 0 or \
                (value == 0 and key not in ("window", "fp_ports")):
            raise ValueError("--machine: %s must be a positive number, not %r" % (key, value))
    return machine


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("driver_output")
    parser.add_argument("trace")
    parser.add_argument("--free", help="regex of functions whose work is taken out of the model")
    parser.add_argument("--chain", action="store_true", help="the functions the chain runs through")
    parser.add_argument("--machine", default="{}",
                        help='JSON of rules over the defaults, e.g. {"window": 224} (%s)' %
                        ", ".join(MACHINE_RULES))
    args = parser.parse_args()
    try:
        machine = machine_from_json(args.machine)
    except ValueError as e:
        parser.error(str(e))
    loaded, mark, end = read_driver_output(args.driver_output)
    windows, steps = read_trace(args.trace, mark, end, Objects(loaded), args.free)
    f, chain = figures(windows, steps, machine)
    instructions = sum(len(ops) for ops in windows)
    print("%8.0f %8.0f %8.0f %8.0f %8.0f" % (instructions / steps, f["chain"], f["width"],
                                             f["window"], f["model"]))
    if args.chain:
        for function, cycles in chain[:12]:
            print("    %7.1f  %s" % (cycles / steps, function[:100]))


if __name__ == "__main__":
    main()
