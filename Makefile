# The two commands of the quick start, and a few more. Each installs what it lacks and builds.
SHELL := /bin/bash
.PHONY: all deps build test demo bench speedup instructions budgets model tradeoff soak fuzz screenshot lint format clean ws

all: build

deps:
	@bash scripts/install_deps.sh

build: deps
	@bash scripts/build.sh

test: build
	@bash scripts/run_tests.sh

demo: build
	@bash scripts/demo.sh

bench: build
	@. scripts/workspace.sh && "$$WS/devel/lib/marble_maze/marble_maze_bench"

# The step now against the first commit's (or COMMIT's), both built and timed here in turns on
# make bench's free flight, open floor and mazes: a speed-up no machine moves (about 2 minutes).
speedup: deps
	@bash scripts/speedup.sh $${COMMIT:+"$$COMMIT"}

# Instructions a step (callgrind), which no machine's speed or load moves: CASES is a regex of
# make bench's cases (default: free flight, open floor, mazes), each run for STEPS steps (default
# 20,000; about 20 s in all).
instructions: build
	@bash scripts/count_instructions.sh $${CASES:+"$$CASES"}

# Every case's instructions a step against its budget in bench/instruction_budgets.txt (about
# 30 s; make test checks them too).
budgets: build
	@bash scripts/check_budgets.sh

# What holds a step's time, by a model of the processor run on a trace of the step (valgrind's
# lackey): the chain of dependent values, the width and the window, cycles a step (about 2 minutes
# a case). CASES: free_flight, open_floor, maze:CELLS; FREE: a regex of functions taken out;
# MACHINE: the model's rules for another processor, as JSON ('{"window": 224}': a Zen 2's).
model: build
	@bash scripts/cycle_model.sh $${CASES:+"$$CASES"}

# The speed-accuracy trade: doc/tradeoff.{csv,md,png} from scratch (under half a minute).
tradeoff: build
	@bash scripts/tradeoff.sh

# Long runs: 10 million steps at rest and of random tilting, and an hour of simulated time of a
# session played and called at random (make test runs a million, a million and six minutes).
soak: deps
	@bash scripts/build.sh tests
	@. scripts/workspace.sh && MARBLE_MAZE_SOAK_STEPS=10000000 MARBLE_MAZE_SOAK_SECONDS=3600 \
	  "$$WS/devel/lib/marble_maze/test_core" --gtest_filter='Soak.*'

# The fuzzers for longer: FUZZ_SECONDS each (default 300; make test runs them 30 s each).
fuzz: deps
	@bash scripts/fuzz.sh $${FUZZ_SECONDS:-300}

# The workspace's path, for: source "$$(make -s ws)/devel/setup.bash"
ws:
	@. scripts/workspace.sh && echo "$$WS"

screenshot: build
	@bash scripts/screenshot.sh doc/demo.png 8

lint: deps
	@PATH=/usr/bin:$$PATH catkin_lint --strict .

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	@. scripts/workspace.sh && rm -rf "$$WS" && echo "removed $$WS"
