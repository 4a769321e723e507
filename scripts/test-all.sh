#!/usr/bin/env bash
# Installs what the tests need (Debian packages when run as root, npm packages, the e2e harness),
# then runs every test. This is the README's test command and what .ci/run runs.
set -euo pipefail
cd "$(dirname "$0")/.."

need_packages=()
command -v nvim >/dev/null 2>&1 || need_packages+=(neovim)
# The queue tests (test/cli/batchQueue.test.ts) start their own redis-server on 127.0.0.1.
command -v redis-server >/dev/null 2>&1 || need_packages+=(redis-server)
if [ ${#need_packages[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "== installing Debian packages: ${need_packages[*]}"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need_packages[@]}" >/dev/null
  else
    echo "== not root: skipping Debian packages (${need_packages[*]}); the tests that need them will say so"
  fi
fi

if [ ! -d node_modules ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  echo "== npm ci"
  npm ci --no-audit --no-fund
fi

if [ -x scripts/e2e-setup.sh ]; then
  echo "== e2e harness (code-server, chromium)"
  bash scripts/e2e-setup.sh
fi

# The simulator tests run esmini built from ../shared/esmini into .cache/esmini (idempotent: a
# second run returns at once; parallel runs wait for each other).
if [ -f ../shared/esmini/build.sh ]; then
  echo "== esmini (.cache/esmini)"
  if ! bash ../shared/esmini/build.sh .cache/esmini >/dev/null; then
    [ -z "${M2S_REQUIRE_ESMINI:-}" ] || exit 1
    echo "== esmini did not build: the simulator tests will say so"
  fi
else
  echo "== ../shared/esmini is absent: the simulator tests will say so"
fi

# The CARLA tests check exports with ScenarioRunner's own loader, unpacked from ../shared/carla into
# .cache/carla (idempotent: a second run only checks the stamp; as root it apt-gets its Debian packages).
if [ -f ../shared/carla/check.py ]; then
  echo "== CARLA ScenarioRunner harness (.cache/carla)"
  if ! python3 ../shared/carla/check.py setup >/dev/null 2>&1; then
    [ -z "${M2S_REQUIRE_CARLA:-}" ] || { python3 ../shared/carla/check.py setup; exit 1; }
    echo "== the ScenarioRunner harness did not set up: the CARLA tests will say so"
  fi
else
  echo "== ../shared/carla is absent: the CARLA tests will say so"
fi

echo "== tests"
npm test
