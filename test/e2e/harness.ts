import { spawn, spawnSync, type ChildProcess } from 'node:child_process';
import * as fs from 'node:fs';
import * as http from 'node:http';
import * as net from 'node:net';
import * as os from 'node:os';
import * as path from 'node:path';
import type { Browser, Page } from 'playwright-core';
import { repoRoot } from '../support/paths';
import { STALL_MS } from './limits';

/**
 * Runs the packaged extension inside a real VS Code: code-server 4.100.3 (installed by
 * scripts/e2e-setup.sh into .cache/code-server) on 127.0.0.1, driven by Debian's Chromium through
 * playwright-core. Nothing is downloaded here.
 */

export const CODE_SERVER =
  process.env.M2S_CODE_SERVER ?? path.join(repoRoot, '.cache', 'code-server', 'node_modules', '.bin', 'code-server');
export const CHROMIUM = process.env.M2S_CHROMIUM ?? '/usr/bin/chromium';
export const ARTIFACTS = path.join(repoRoot, 'test-results', 'e2e');
const SETUP = 'scripts/e2e-setup.sh';

/** Why the real-VS-Code tests cannot run here, or undefined when everything is installed. */
export function missingTools(): string | undefined {
  const missing: string[] = [];
  if (!fs.existsSync(CODE_SERVER)) missing.push(`code-server (${CODE_SERVER})`);
  if (!fs.existsSync(CHROMIUM)) missing.push(`chromium (${CHROMIUM})`);
  try {
    require.resolve('playwright-core');
  } catch {
    missing.push('playwright-core (npm ci)');
  }
  return missing.length > 0 ? `missing ${missing.join(', ')}; run ${SETUP}` : undefined;
}

export function requireE2e(): boolean {
  return process.env.M2S_REQUIRE_E2E === '1';
}

function run(command: string, args: string[], options: { cwd?: string; env?: NodeJS.ProcessEnv } = {}): string {
  const result = spawnSync(command, args, {
    cwd: options.cwd ?? repoRoot,
    env: options.env ?? process.env,
    encoding: 'utf8',
    maxBuffer: 64 * 1024 * 1024,
    timeout: STALL_MS,
    killSignal: 'SIGKILL',
  });
  if ((result.error as NodeJS.ErrnoException | undefined)?.code === 'ETIMEDOUT')
    throw new Error(`${command} ${args.join(' ')} did not finish within ${STALL_MS / 1000} s:\n${result.stdout}\n${result.stderr}`);
  if (result.status !== 0) {
    throw new Error(`${command} ${args.join(' ')} failed (${result.status ?? result.signal}):\n${result.stdout}\n${result.stderr}`);
  }
  return result.stdout;
}

/** Builds the bundles and the .vsix exactly as `npm run package` does, into `directory`. */
export function packageExtension(directory: string): string {
  const vsix = path.join(directory, 'modular2simple.vsix');
  run(process.execPath, [path.join(repoRoot, 'scripts', 'package.mjs'), '--out', vsix]);
  return vsix;
}

/** Bundles the tests that run inside the extension host into a throwaway extension folder. */
export async function buildInsideSuite(directory: string): Promise<{ extensionPath: string; testsPath: string }> {
  const esbuild = await import('esbuild');
  // Placed under the project so that `require('mocha')` finds the project's node_modules.
  const extensionPath = path.join(repoRoot, 'out', `e2e-runner-${process.pid}`);
  fs.rmSync(extensionPath, { recursive: true, force: true });
  fs.mkdirSync(extensionPath, { recursive: true });
  fs.writeFileSync(
    path.join(extensionPath, 'package.json'),
    JSON.stringify({ name: 'modular2simple-e2e-runner', publisher: 'modular2simple', version: '0.0.0', engines: { vscode: '^1.91.0' } }),
  );
  const testsPath = path.join(extensionPath, 'suite.js');
  await esbuild.build({
    entryPoints: [path.join(repoRoot, 'test', 'e2e', 'inside', 'index.ts')],
    outfile: testsPath,
    bundle: true,
    platform: 'node',
    target: 'node20',
    format: 'cjs',
    external: ['vscode', 'mocha'],
    logLevel: 'warning',
  });
  void directory;
  return { extensionPath, testsPath };
}

export function removeInsideSuite(extensionPath: string): void {
  fs.rmSync(extensionPath, { recursive: true, force: true });
}

async function freePort(): Promise<number> {
  return new Promise((resolve, reject) => {
    const server = net.createServer();
    server.once('error', reject);
    server.listen(0, '127.0.0.1', () => {
      const address = server.address() as net.AddressInfo;
      server.close(() => resolve(address.port));
    });
  });
}

/** A private profile: HOME, XDG folders, user data and extensions all inside one temporary folder. */
export interface Profile {
  root: string;
  home: string;
  userData: string;
  extensions: string;
  env: NodeJS.ProcessEnv;
}

export function createProfile(): Profile {
  const root = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-e2e-'));
  const home = path.join(root, 'home');
  const userData = path.join(root, 'user-data');
  const extensions = path.join(root, 'extensions');
  for (const folder of [home, userData, extensions, path.join(userData, 'User')]) fs.mkdirSync(folder, { recursive: true });
  fs.writeFileSync(
    path.join(userData, 'User', 'settings.json'),
    JSON.stringify({
      'workbench.startupEditor': 'none',
      'workbench.tips.enabled': false,
      'security.workspace.trust.enabled': false,
      'telemetry.telemetryLevel': 'off',
      'extensions.autoCheckUpdates': false,
      'extensions.autoUpdate': false,
      'update.mode': 'none',
      'files.autoSave': 'off',
      'editor.minimap.enabled': false,
      'window.restoreWindows': 'none',
      'git.openRepositoryInParentFolders': 'never',
    }),
  );
  const env: NodeJS.ProcessEnv = {
    ...process.env,
    HOME: home,
    XDG_CONFIG_HOME: path.join(home, '.config'),
    XDG_DATA_HOME: path.join(home, '.local', 'share'),
    XDG_CACHE_HOME: path.join(home, '.cache'),
    XDG_RUNTIME_DIR: path.join(root, 'runtime'),
    TMPDIR: path.join(root, 'tmp'),
    // Headers from the system: without it node-gyp would try to download them under the new HOME.
    npm_config_nodedir: '/usr',
    // No extension gallery: the tests touch nothing beyond 127.0.0.1.
    EXTENSIONS_GALLERY: '{}',
  };
  for (const key of ['XDG_CONFIG_HOME', 'XDG_DATA_HOME', 'XDG_CACHE_HOME', 'XDG_RUNTIME_DIR', 'TMPDIR'] as const)
    fs.mkdirSync(env[key] as string, { recursive: true, mode: 0o700 });
  return { root, home, userData, extensions, env };
}

export function installExtension(profile: Profile, vsix: string): void {
  run(CODE_SERVER, ['--extensions-dir', profile.extensions, '--user-data-dir', profile.userData, '--install-extension', vsix, '--force'], {
    env: profile.env,
  });
}

export interface CodeServer {
  port: number;
  url: string;
  process: ChildProcess;
  log: string[];
  stop(): Promise<void>;
}

/** Starts code-server on loopback in its own process group, so that stopping it ends its extension hosts and language servers too. */
export async function startCodeServer(profile: Profile, extraEnv: NodeJS.ProcessEnv = {}): Promise<CodeServer> {
  const port = await freePort();
  const config = path.join(profile.root, 'code-server.yaml');
  fs.writeFileSync(config, `bind-addr: 127.0.0.1:${port}\nauth: none\n`);
  const child = spawn(
    CODE_SERVER,
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
      profile.userData,
      '--extensions-dir',
      profile.extensions,
      '--config',
      config,
    ],
    { env: { ...profile.env, ...extraEnv }, detached: true, stdio: ['ignore', 'pipe', 'pipe'] },
  );
  const log: string[] = [];
  child.stdout?.on('data', (chunk: Buffer) => log.push(chunk.toString()));
  child.stderr?.on('data', (chunk: Buffer) => log.push(chunk.toString()));
  const url = `http://127.0.0.1:${port}`;
  const stop = async (): Promise<void> => {
    if (child.exitCode !== null || child.pid === undefined) return;
    const exited = new Promise<void>((resolve) => child.once('exit', () => resolve()));
    try {
      process.kill(-child.pid, 'SIGTERM');
    } catch {
      return;
    }
    const timer = setTimeout(() => {
      try {
        process.kill(-(child.pid as number), 'SIGKILL');
      } catch {
        // already gone
      }
    }, 3000);
    await exited;
    clearTimeout(timer);
    // Extension hosts and language servers may outlive the main process for a moment; end the group.
    try {
      process.kill(-child.pid, 'SIGKILL');
    } catch {
      // the group is empty
    }
  };
  const deadline = Date.now() + STALL_MS;
  while (Date.now() < deadline) {
    if (child.exitCode !== null) throw new Error(`code-server exited (${child.exitCode}):\n${log.join('')}`);
    if (await healthy(`${url}/healthz`)) return { port, url, process: child, log, stop };
    await new Promise((resolve) => setTimeout(resolve, 200));
  }
  await stop();
  throw new Error(`code-server did not answer on ${url} within ${STALL_MS / 1000} s:\n${log.join('')}`);
}

function healthy(url: string): Promise<boolean> {
  return new Promise((resolve) => {
    const request = http.get(url, (response) => {
      response.resume();
      resolve(response.statusCode === 200);
    });
    request.on('error', () => resolve(false));
    request.setTimeout(1000, () => {
      request.destroy();
      resolve(false);
    });
  });
}

export async function launchBrowser(profile: Profile): Promise<Browser> {
  const { chromium } = await import('playwright-core');
  return chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    env: profile.env,
    args: [
      '--no-sandbox',
      '--disable-gpu',
      '--disable-quic',
      '--no-first-run',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync',
    ],
  });
}

/** The result of one test run inside the extension host, as reported by its reporter. */
export interface InsideResult {
  title: string;
  state: 'passed' | 'failed' | 'pending';
  durationMs: number;
  error?: string;
}

/**
 * A loopback endpoint for the tests inside VS Code: they post their results, and ask for a
 * screenshot of what the page shows at that moment.
 */
export class HarnessEndpoint {
  readonly results: InsideResult[] = [];
  /** Resolves with the number of failures when the suite inside VS Code says it has finished. */
  readonly finished: Promise<number>;
  private resolveFinished: (failures: number) => void = () => undefined;
  /** Further routes, answered with what their handler returns (as JSON). */
  readonly routes = new Map<string, (body: unknown) => Promise<unknown>>();
  /** Every request with its time and duration, kept as an artifact for diagnosing a hung test. */
  readonly log: string[] = [];
  page: Page | undefined;
  private server: http.Server | undefined;
  url = '';

  /** `onRequest` hears of every request, as the progress of the tests inside VS Code. */
  constructor(private readonly onRequest: (route: string) => void = () => undefined) {
    this.finished = new Promise((resolve) => (this.resolveFinished = resolve));
  }

  async start(): Promise<void> {
    this.server = http.createServer((request, response) => void this.handle(request, response));
    await new Promise<void>((resolve) => this.server?.listen(0, '127.0.0.1', resolve));
    this.url = `http://127.0.0.1:${(this.server.address() as net.AddressInfo).port}`;
  }

  private async handle(request: http.IncomingMessage, response: http.ServerResponse): Promise<void> {
    const chunks: Buffer[] = [];
    for await (const chunk of request) chunks.push(chunk as Buffer);
    const body = Buffer.concat(chunks).toString('utf8');
    const started = Date.now();
    this.onRequest(request.url ?? '');
    response.on('finish', () =>
      this.log.push(
        `${new Date(started).toISOString()} ${request.url} ${body.slice(0, 200)} -> ${response.statusCode} in ${Date.now() - started} ms`,
      ),
    );
    try {
      if (request.url === '/result') {
        this.results.push(JSON.parse(body) as InsideResult);
      } else if (request.url === '/finished') {
        this.resolveFinished((JSON.parse(body) as { failures: number }).failures);
      } else if (request.url === '/screenshot') {
        const { name } = JSON.parse(body) as { name: string };
        const file = path.join(ARTIFACTS, `${name.replace(/[^\w.-]+/g, '-').slice(0, 100)}.png`);
        fs.mkdirSync(ARTIFACTS, { recursive: true });
        await this.page?.screenshot({ path: file });
        response.end(JSON.stringify({ file }));
        return;
      } else {
        const route = this.routes.get(request.url ?? '');
        if (!route) throw new Error(`no route ${request.url}`);
        response.end(JSON.stringify(await route(JSON.parse(body || '{}'))));
        return;
      }
      response.end('{}');
    } catch (error) {
      response.statusCode = 500;
      response.end(JSON.stringify({ error: (error as Error).message }));
    }
  }

  async stop(): Promise<void> {
    const closed = new Promise<void>((resolve) => (this.server ? this.server.close(() => resolve()) : resolve()));
    // A request left open by an extension host that was killed would keep close() waiting for ever.
    this.server?.closeAllConnections();
    await closed;
  }
}

/**
 * The run's progress: each step resets the stall limit (and the mocha limit of the hook that waits, which
 * `onProgress` resets); `stalled` resolves once nothing progressed for STALL_MS, naming the last step.
 */
export class Progress {
  private lastStep = 'start';
  private lastAt = Date.now();
  private timer: NodeJS.Timeout | undefined;

  constructor(private readonly onProgress: () => void) {}

  step(what: string): void {
    this.lastStep = what;
    this.lastAt = Date.now();
    this.onProgress();
  }

  stalled(): Promise<string> {
    return new Promise((resolve) => {
      const check = (): void => {
        const idle = Date.now() - this.lastAt;
        if (idle >= STALL_MS) resolve(`no progress for ${Math.round(idle / 1000)} s after ${this.lastStep}`);
        else this.timer = setTimeout(check, Math.min(1000, STALL_MS - idle));
      };
      check();
    });
  }

  stop(): void {
    clearTimeout(this.timer);
  }
}

/** Copies a folder, as the tests change the workspace they open. */
export function copyFolder(from: string, to: string): void {
  fs.cpSync(from, to, { recursive: true });
}
