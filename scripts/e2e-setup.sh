#!/usr/bin/env bash
# Installs everything the real-VS-Code tests (test/e2e) need on a fresh Debian machine, without
# touching package.json: Debian packages, the project's npm dependencies (playwright-core among
# them) and code-server into .cache/code-server. Idempotent: a second run only checks and returns.
# With --code-server, only what code-server needs (for `npm start` on a machine without VS Code).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
CODE_SERVER_VERSION="4.100.3"
CODE_SERVER_DIR="${M2S_CODE_SERVER_DIR:-$ROOT/.cache/code-server}"
MARKER="$CODE_SERVER_DIR/.installed-$CODE_SERVER_VERSION"
APT_PACKAGES=(libkrb5-dev pkg-config build-essential python3 ripgrep)
only_code_server=false
if [[ "${1:-}" == "--code-server" ]]; then only_code_server=true; else APT_PACKAGES+=(chromium); fi

log() { printf 'e2e-setup: %s\n' "$*"; }

missing=()
for package in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed' || missing+=("$package")
done
if ((${#missing[@]} > 0)); then
  log "installing Debian packages: ${missing[*]}"
  sudo=""
  if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [[ $only_code_server == false && ! -d "$ROOT/node_modules/playwright-core" ]]; then
  log "installing the project's npm dependencies (npm ci)"
  (cd "$ROOT" && npm ci --no-audit --no-fund)
fi

if [[ -f "$MARKER" && -x "$CODE_SERVER_DIR/node_modules/.bin/code-server" ]]; then
  log "code-server $CODE_SERVER_VERSION already in $CODE_SERVER_DIR"
  exit 0
fi

log "installing code-server $CODE_SERVER_VERSION into $CODE_SERVER_DIR (about a minute)"
staging="$(mktemp -d "${TMPDIR:-/tmp}/m2s-code-server.XXXXXX")"
trap 'rm -rf "$staging"' EXIT
# Trap 3: @vscode/ripgrep downloads rg from GitHub unless its cache (under the temp dir) holds it.
export TMPDIR="$staging/tmp"
mkdir -p "$TMPDIR/vscode-ripgrep-cache-1.15.11" "$staging/rg" "$staging/install"
cp /usr/bin/rg "$staging/rg/rg"
tar -czf "$TMPDIR/vscode-ripgrep-cache-1.15.11/ripgrep-v13.0.0-10-x86_64-unknown-linux-musl.tar.gz" -C "$staging/rg" rg
printf '{ "name": "m2s-code-server-cache", "private": true }\n' > "$staging/install/package.json"
# Trap 1: unsafe-perm; trap 4: node-pty's `npx node-gyp` needs yes=true, and headers from /usr.
(
  cd "$staging/install"
  npm_config_unsafe_perm=true npm_config_yes=true npm_config_nodedir=/usr \
    npm install --no-audit --no-fund --loglevel=error "code-server@$CODE_SERVER_VERSION"
)
mkdir -p "$(dirname "$CODE_SERVER_DIR")"
rm -rf "$CODE_SERVER_DIR"
mv "$staging/install" "$CODE_SERVER_DIR"
touch "$MARKER"
"$CODE_SERVER_DIR/node_modules/.bin/code-server" --version | head -1
log "done"
