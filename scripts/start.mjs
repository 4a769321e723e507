#!/usr/bin/env node
// `npm start`: opens the bundled examples/ in a real VS Code with this extension loaded. Installs
// what is missing first (npm ci, the bundles, and code-server when desktop VS Code is not installed);
// esmini is built after the editor is open, with its progress shown, as it takes minutes the first time.
import { spawn, spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as net from 'node:net';
import * as path from 'node:path';
import { fileURLToPath } from 'node:url';
import { buildEsmini } from './esminiBuild.mjs';
import { writeStartSettings } from './startSettings.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const workspace = path.resolve(process.argv[2] ?? path.join(root, 'examples'));
const codeServer = path.join(root, '.cache', 'code-server', 'node_modules', '.bin', 'code-server');
const profile = path.join(root, '.cache', 'code-server-profile');

/** @param {string} message */
function step(message) {
  console.log(`modular2simple: ${message}`);
}

/**
 * @param {string} command
 * @param {string[]} args
 * @param {import('node:child_process').SpawnSyncOptions} [options]
 */
function runOrExit(command, args, options = {}) {
  const result = spawnSync(command, args, { cwd: root, stdio: 'inherit', ...options });
  if (result.status !== 0) {
    console.error(`modular2simple: '${command} ${args.join(' ')}' failed; fix the error above and run npm start again`);
    process.exit(result.status ?? 1);
  }
}

/** @param {string} command */
function onPath(command) {
  return spawnSync('sh', ['-c', `command -v ${command}`], { encoding: 'utf8' }).status === 0;
}

/**
 * @param {number} preferred
 * @returns {Promise<number>}
 */
function freePort(preferred) {
  return new Promise((resolve) => {
    const server = net.createServer();
    server.once('error', () => {
      const fallback = net.createServer();
      fallback.listen(0, '127.0.0.1', () => {
        const { port } = /** @type {net.AddressInfo} */ (fallback.address());
        fallback.close(() => resolve(port));
      });
    });
    server.listen(preferred, '127.0.0.1', () => server.close(() => resolve(preferred)));
  });
}

if (!fs.existsSync(path.join(root, 'node_modules', '.package-lock.json'))) {
  step('installing dependencies (npm ci)');
  runOrExit('npm', ['ci', '--no-audit', '--no-fund']);
}
step('building the extension, the language server and the CLI');
runOrExit(process.execPath, [path.join(root, 'scripts', 'build.mjs')]);

// Run in esmini and the bird's-eye view want esmini and road files: esmini is built from ../shared/esmini when it is
// there, into .cache/esmini, where the language server and the CLI look for it (server/src/esmini/locate.ts).
const shared = path.resolve(root, '..', 'shared', 'esmini');
const esminiDest = path.join(root, '.cache', 'esmini');
const canBuildEsmini = fs.existsSync(path.join(shared, 'build.sh'));
// The build runs in a process group of its own: stopping npm start (Ctrl+C, SIGTERM) stops it too.
const esminiBuildStop = new AbortController();

/** Builds esmini (at once when built before), telling how far it is; after the editor is open, so that it is usable meanwhile. */
async function buildEsminiAfterOpening() {
  if (!canBuildEsmini) return;
  if (!fs.existsSync(path.join(esminiDest, 'bin', 'esmini')))
    step(
      'building esmini from ../shared/esmini into .cache/esmini (once; 3 to 20 minutes on 2 cores, longer when they are busy). ' +
        'The editor works meanwhile; Run in esmini finds esmini when the build is done.',
    );
  const program = await buildEsmini({
    buildScript: path.join(shared, 'build.sh'),
    dest: esminiDest,
    report: step,
    signal: esminiBuildStop.signal,
  });
  if (!program && !esminiBuildStop.signal.aborted)
    step('esmini did not build (the lines above say why): Run in esmini will say how to get it');
}

if (onPath('code') && !process.env.M2S_USE_CODE_SERVER) {
  step(`opening ${path.relative(root, workspace) || '.'} in VS Code with the extension loaded`);
  runOrExit('code', ['--new-window', `--extensionDevelopmentPath=${root}`, workspace]);
  for (const signal of ['SIGINT', 'SIGTERM'])
    process.on(signal, () => {
      esminiBuildStop.abort();
      process.exit(130);
    });
  await buildEsminiAfterOpening();
  process.exit(0);
}

if (!fs.existsSync(codeServer)) {
  step('VS Code is not installed: installing code-server 4.100.3 (VS Code in the browser) into .cache/');
  runOrExit('bash', [path.join(root, 'scripts', 'e2e-setup.sh'), '--code-server']);
}

// esmini itself needs no setting (the server finds .cache/esmini); the road files beside it do.
/** @type {Record<string, unknown>} */
const esminiSettings = {};
if (canBuildEsmini) esminiSettings['modular2simple.esmini.roadPath'] = [path.join(shared, 'xodr')];

const userData = path.join(profile, 'user-data');
writeStartSettings(path.join(userData, 'User', 'settings.json'), esminiSettings);
const port = await freePort(Number(process.env.M2S_PORT ?? 8080));
const config = path.join(profile, 'code-server.yaml');
fs.writeFileSync(config, `bind-addr: 127.0.0.1:${port}\nauth: none\n`);
const server = spawn(
  codeServer,
  [
    '--bind-addr',
    `127.0.0.1:${port}`,
    '--auth',
    'none',
    '--disable-telemetry',
    '--disable-update-check',
    '--disable-workspace-trust',
    '--disable-getting-started-override',
    '--user-data-dir',
    userData,
    '--extensions-dir',
    path.join(profile, 'extensions'),
    '--config',
    config,
  ],
  // Its own process group, so that stopping it ends its extension hosts and language servers too.
  {
    stdio: ['ignore', 'ignore', 'inherit'],
    detached: true,
    env: { ...process.env, npm_config_nodedir: process.env.npm_config_nodedir ?? '/usr' },
  },
);
// The extension is loaded from this folder, as desktop VS Code's --extensionDevelopmentPath does.
const payload = JSON.stringify([['extensionDevelopmentPath', `vscode-remote://127.0.0.1:${port}${root}`]]);
const url = `http://127.0.0.1:${port}/?folder=${encodeURIComponent(workspace)}&payload=${encodeURIComponent(payload)}`;
for (let attempt = 0; attempt < 150; attempt++) {
  const ready = await fetch(`http://127.0.0.1:${port}/healthz`).then(
    (response) => response.ok,
    () => false,
  );
  if (ready) break;
  if (server.exitCode !== null) process.exit(server.exitCode);
  await new Promise((resolve) => setTimeout(resolve, 200));
}
const opened = `VS Code (code-server) is running on 127.0.0.1 only. Open this address in a browser on this machine:\n\n  ${url}\n\nAfter a rebuild (npm run build), run "Developer: Reload Window". Stop with Ctrl+C.`;
step(opened);
const stop = () => {
  esminiBuildStop.abort();
  try {
    process.kill(-(/** @type {number} */ (server.pid)), 'SIGTERM');
  } catch {
    process.exit(0);
  }
  setTimeout(() => {
    try {
      process.kill(-(/** @type {number} */ (server.pid)), 'SIGKILL');
    } catch {
      // already gone
    }
    process.exit(0);
  }, 3000).unref();
};
process.on('SIGINT', stop);
process.on('SIGTERM', stop);
server.on('exit', (code) => process.exit(code ?? 0));
const esminiWasBuilt = fs.existsSync(path.join(esminiDest, 'bin', 'esmini'));
await buildEsminiAfterOpening();
// The address again, as the build's lines have pushed it up.
if (canBuildEsmini && !esminiWasBuilt && !esminiBuildStop.signal.aborted) step(opened);
