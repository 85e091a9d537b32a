# The two commands of the quick start, and a few more. Each installs what it lacks and builds.
SHELL := /bin/bash
.PHONY: all deps build test check demo bench instructions tradeoff soak fuzz screenshot lint \
	format clean ws train

all: build

deps:
	@bash scripts/install_deps.sh

build: deps
	@bash scripts/build.sh

# Every test: gtest, rostest, the core under the sanitizers, the fuzzers briefly (about 4 minutes
# on a built tree); ends with "N passed, N failed".
test: deps
	@bash scripts/run_tests.sh

# The long runs: the soak, the sanitizers over the ROS layer too, the fuzzers for FUZZ_SECONDS
# each (default 120), the whole speed-accuracy sweep, the long record and replay cases.
check: build
	@bash scripts/check.sh

demo: build
	@bash scripts/demo.sh $(ARGS)

# The step's cost (Google Benchmark), each case also as a ratio to free flight in the same run;
# then marble_maze.agents from Python against the C++ loop (bench/agents_bench.py, 25 s) and ROS
# lockstep's periods a second (scripts/bench_lockstep.sh, about a minute).
bench: build
	@. scripts/workspace.sh && "$$WS/devel/lib/marble_maze/marble_maze_bench"
	@. scripts/workspace.sh && use_workspace && \
	  /usr/bin/python3 bench/agents_bench.py "$$WS/devel/lib/marble_maze/marble_maze_bench"
	@bash scripts/bench_lockstep.sh

# Instructions a step (callgrind), which no machine's speed or load moves: CASES is a regex of
# make bench's cases (default: free flight, open floor, mazes), each run for STEPS steps.
instructions: build
	@bash scripts/count_instructions.sh $${CASES:+"$$CASES"}

# The speed-accuracy trade: doc/tradeoff.{csv,md,png} from scratch (about a minute).
tradeoff: build
	@bash scripts/tradeoff.sh

# The soak alone: 10 million steps at rest and of random tilting, and an hour of simulated time
# of a session played and called at random (make test runs a million, a million and six minutes).
soak: build
	@. scripts/workspace.sh && (cd "$$WS" && catkin_make -j2 tests >/dev/null) && \
	  MARBLE_MAZE_SOAK_STEPS=10000000 MARBLE_MAZE_SOAK_SECONDS=3600 \
	  "$$WS/devel/lib/marble_maze/test_core" --gtest_filter='Soak.*'

# The fuzzers alone, for FUZZ_SECONDS each (default 300).
fuzz: deps
	@bash scripts/fuzz.sh $${FUZZ_SECONDS:-300}

# The workspace's path, for: source "$$(make -s ws)/devel/setup.bash"
ws:
	@. scripts/workspace.sh && echo "$$WS"

# PPO on generated mazes from marble_maze.agents: doc/learning_curve.png, MINUTES of training
# (default 10), then a test on mazes it never saw.
train: build
	@. scripts/workspace.sh && use_workspace && \
	  /usr/bin/python3 examples/train.py --minutes $${MINUTES:-10}

screenshot: build
	@bash scripts/screenshot.sh doc/demo.png 8

# catkin_lint, clang-format (as a check), clang-tidy, flake8 and shellcheck.
lint: build
	@bash scripts/lint.sh

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	@. scripts/workspace.sh && rm -rf "$$WS" && echo "removed $$WS"
