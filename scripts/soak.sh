#!/usr/bin/env bash
# Runs every fast-check property (the test files that import fast-check) ROUNDS times, each round on a
# fresh seed, and stops at the first failure with the command that replays it. CI runs them on one seed
# (.ci/run sets M2S_PROPERTY_SEED); this is where new seeds are tried. Server properties run dist/: build first.
set -euo pipefail
cd "$(dirname "$0")/.."
rounds="${1:-10}"
mapfile -t files < <(grep -rl --include='*.test.ts' "from 'fast-check'" test | sort)
for round in $(seq 1 "$rounds"); do
  seed=$(( (RANDOM << 15 | RANDOM) - (1 << 29) ))
  echo "== round $round of $rounds: M2S_PROPERTY_SEED=$seed"
  if ! M2S_PROPERTY_SEED="$seed" npx mocha "${files[@]}"; then
    echo "== a property failed on seed $seed: M2S_PROPERTY_SEED=$seed npx mocha <the failing file> replays it" >&2
    exit 1
  fi
done
echo "== ${#files[@]} files, $rounds seeds: every property held"
