# The two commands of the README, plus their set-up.
#   make results   the default comparison, headless: images, CSV and a report in results/default
#   make test      the whole test suite (GPU tests run on lavapipe when there is no GPU)

CARGO ?= cargo
# Vulkan loaders complain without a private runtime folder; any mode-700 folder will do.
export XDG_RUNTIME_DIR ?= /tmp/grassbench-runtime-$(shell id -u)

.PHONY: setup results test bench
setup:
	@bash .ci/install-deps
	@mkdir -p -m 700 $(XDG_RUNTIME_DIR)

results: setup
	$(CARGO) run --release -p grassbench-cli -- run --technique all --scene default \
		--frames 20 --warmup 3 --out results/default --force

test: setup
	$(CARGO) test --release --workspace
	# Every benchmark compiles (they are not built by `cargo test`).
	$(CARGO) build --release --workspace --benches
	# Smoke-run the criterion benchmarks on a tiny workload (each once).
	GRASSBENCH_BENCH_SMALL=1 $(CARGO) test --release -p grassbench-cli --bench techniques

bench: setup
	$(CARGO) bench -p grassbench-cli --bench techniques
