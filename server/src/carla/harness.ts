import { spawn } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';

/** The harness shipped with the extension (server/python/): ScenarioRunner's loader against a stand-in for CARLA. */
export const HARNESS_FILE = 'scenario_runner_check.py';

/** The harness beside the bundle (dist/server.js, dist/cli.js) or, run from source, in server/python/. */
export function harnessScript(from: string = __dirname): string {
  const candidates = [path.resolve(from, '..', 'server', 'python', HARNESS_FILE), path.resolve(from, '..', '..', 'python', HARNESS_FILE)];
  const found = candidates.find((candidate) => fs.existsSync(candidate));
  if (!found) throw new Error(`the ScenarioRunner harness ${HARNESS_FILE} is not installed (looked in ${candidates.join(', ')})`);
  return found;
}

/** What the harness printed: ScenarioRunner's verdict on one file, or why it could not give one. */
export interface HarnessVerdict {
  status: 'built' | 'refused' | 'not-scenario-runner' | 'requirements' | 'error';
  stage?: 'schema' | 'version' | 'configuration' | 'build' | null;
  reason?: string | null;
  /** The innermost ScenarioRunner frame: `srunner/tools/openscenario_parser.py:123 function`. */
  where?: string | null;
  source_line?: string | null;
  /** The element it failed on: its place in the file's document order. */
  element?: { index: number | null; tag: string; name: string | null } | null;
  warnings?: string[];
  tree_nodes?: number;
  town?: string | null;
  egos?: string[];
  module?: string | null;
  traceback?: string;
}

export type HarnessRun =
  | { kind: 'verdict'; verdict: HarnessVerdict; output: string; command: string[] }
  /** The Python could not be started (not found, not executable). */
  | { kind: 'no-python'; message: string; command: string[] }
  /** Stopped at the time limit: its process group killed. */
  | { kind: 'timeout'; output: string; command: string[]; pid: number | undefined }
  /** It ended without a verdict (a crash of the interpreter, a Python 2, a program that is no Python). */
  | { kind: 'no-verdict'; code: number | null; signal: string | null; output: string; command: string[] }
  | { kind: 'cancelled'; command: string[] };

export interface HarnessOptions {
  python: string;
  scenarioRunner: string;
  scenario: string;
  /** The CARLA maps a town may name (core/profiles/scenarioRunner.ts CARLA_TOWNS). */
  towns: readonly string[];
  timeLimitMs: number;
  cancel?: AbortSignal;
  script?: string;
}

const MAX_OUTPUT = 200_000;

/** Runs the harness once, in a process group of its own that is killed at the time limit. Never throws. */
export function runHarness(options: HarnessOptions): Promise<HarnessRun> {
  const command = [
    options.python,
    options.script ?? harnessScript(),
    '--scenario-runner',
    options.scenarioRunner,
    '--towns',
    options.towns.join(','),
    options.scenario,
  ];
  return new Promise((resolve) => {
    let stdout = '';
    let stderr = '';
    let settled = false;
    let timedOut = false;
    let cancelled = false;
    // Its own process group: a Python started through a wrapper script (pyenv, a venv's shim) goes with it.
    const child = spawn(command[0], command.slice(1), {
      stdio: ['ignore', 'pipe', 'pipe'],
      detached: true,
      env: { ...process.env, PYTHONDONTWRITEBYTECODE: '1' },
    });
    const killGroup = (): void => {
      try {
        if (child.pid !== undefined) process.kill(-child.pid, 'SIGKILL');
      } catch {
        child.kill('SIGKILL');
      }
    };
    const timer = setTimeout(() => {
      timedOut = true;
      killGroup();
    }, options.timeLimitMs);
    const onCancel = (): void => {
      cancelled = true;
      killGroup();
    };
    options.cancel?.addEventListener('abort', onCancel);
    const finish = (run: HarnessRun): void => {
      if (settled) return;
      settled = true;
      clearTimeout(timer);
      options.cancel?.removeEventListener('abort', onCancel);
      resolve(run);
    };
    child.stdout.on('data', (chunk: Buffer) => (stdout = (stdout + chunk.toString('utf8')).slice(-MAX_OUTPUT)));
    child.stderr.on('data', (chunk: Buffer) => (stderr = (stderr + chunk.toString('utf8')).slice(-MAX_OUTPUT)));
    child.on('error', (error) => finish({ kind: 'no-python', message: `cannot start ${options.python}: ${error.message}`, command }));
    child.on('close', (code, signal) => {
      const output = [stdout, stderr].filter((text) => text.trim()).join('\n');
      if (cancelled) return finish({ kind: 'cancelled', command });
      if (timedOut) return finish({ kind: 'timeout', output, command, pid: child.pid });
      const verdict = lastJsonLine(stdout);
      if (verdict) return finish({ kind: 'verdict', verdict, output: stderr, command });
      finish({ kind: 'no-verdict', code, signal, output, command });
    });
  });
}

function lastJsonLine(text: string): HarnessVerdict | undefined {
  const lines = text.trim().split('\n');
  for (let i = lines.length - 1; i >= 0; i--) {
    try {
      const parsed = JSON.parse(lines[i]) as unknown;
      if (parsed && typeof parsed === 'object' && typeof (parsed as { status?: unknown }).status === 'string')
        return parsed as HarnessVerdict;
    } catch {
      // not the verdict line
    }
  }
  return undefined;
}
