import * as fs from 'node:fs';
import * as net from 'node:net';
import * as path from 'node:path';
import { carlaPython } from '../../../common/src/paths';

/*
 * *Run in CARLA*: the command line that starts ScenarioRunner on an export, and what is checked before it
 * starts. No VS Code here, so that it is tested without an editor or a CARLA server.
 */

export interface CarlaRunSettings {
  /** modular2simple.carla.host; empty: not set. */
  host: string;
  /** modular2simple.carla.port (ScenarioRunner's default 2000). */
  port: number;
  /** modular2simple.carla.scenarioRunnerPath, resolved. */
  scenarioRunner: string;
  /** modular2simple.carla.python as written: a name on PATH, or a path (a relative one is in ScenarioRunner's folder). */
  python: string;
}

export interface CarlaCommandLine {
  program: string;
  args: string[];
  /** ScenarioRunner's folder: it imports `srunner` from there. */
  cwd: string;
}

/** Why the run cannot start with these settings (naming the setting to set), or undefined. */
export function missingRunSetting(settings: CarlaRunSettings): string | undefined {
  if (!settings.host.trim())
    return 'Run in CARLA: set modular2simple.carla.host (and modular2simple.carla.port, 2000 by default) to the CARLA server ScenarioRunner is to connect to; nothing was run.';
  if (!Number.isInteger(settings.port) || settings.port < 1 || settings.port > 65535)
    return `Run in CARLA: modular2simple.carla.port is ${settings.port}, not a port (1 to 65535); nothing was run.`;
  if (!settings.scenarioRunner.trim())
    return 'Run in CARLA: set modular2simple.carla.scenarioRunnerPath to the folder of CARLA ScenarioRunner (the one holding scenario_runner.py); nothing was run.';
  return undefined;
}

/** Whether `file` is a file this process may execute. */
function executable(file: string): boolean {
  try {
    fs.accessSync(file, fs.constants.X_OK);
    return fs.statSync(file).isFile();
  } catch {
    return false;
  }
}

/**
 * Why ScenarioRunner cannot be started with these settings: no scenario_runner.py in its folder, or a Python that is
 * neither an executable file (a path) nor found on PATH (a name). A task whose program cannot start never reports
 * an end in VS Code, so this is checked before the task is started. Undefined when both are there.
 */
export function startProblem(settings: CarlaRunSettings, searchPath = process.env.PATH ?? ''): string | undefined {
  const script = path.join(settings.scenarioRunner, 'scenario_runner.py');
  if (!fs.existsSync(script))
    return `Run in CARLA: there is no scenario_runner.py in ${settings.scenarioRunner}; set modular2simple.carla.scenarioRunnerPath to the folder of CARLA ScenarioRunner that holds it. Nothing was run.`;
  const python = carlaPython(settings.python, settings.scenarioRunner);
  const found =
    python.includes('/') || python.includes(path.sep)
      ? executable(python)
      : searchPath
          .split(path.delimiter)
          .filter((folder) => folder)
          .some((folder) => executable(path.join(folder, python)));
  if (!found)
    return `Run in CARLA: the Python ${python} (modular2simple.carla.python) ${python.includes('/') ? 'is not an executable file' : 'is not on PATH'}; set it to a Python 3 that has ScenarioRunner's requirements. Nothing was run.`;
  return undefined;
}

/** `python scenario_runner.py --openscenario EXPORT --host H --port P`, run in ScenarioRunner's folder. */
export function scenarioRunnerCommandLine(settings: CarlaRunSettings, exportFile: string): CarlaCommandLine {
  return {
    program: carlaPython(settings.python, settings.scenarioRunner),
    args: [
      path.join(settings.scenarioRunner, 'scenario_runner.py'),
      '--openscenario',
      exportFile,
      '--host',
      settings.host.trim(),
      '--port',
      String(settings.port),
    ],
    cwd: settings.scenarioRunner,
  };
}

/** Whether something accepts connections at host:port within `timeoutMs`; the reason when not. */
export function reachable(host: string, port: number, timeoutMs: number): Promise<{ ok: true } | { ok: false; reason: string }> {
  return new Promise((resolve) => {
    const socket = net.connect({ host, port });
    const done = (answer: { ok: true } | { ok: false; reason: string }): void => {
      socket.destroy();
      clearTimeout(timer);
      resolve(answer);
    };
    const timer = setTimeout(() => done({ ok: false, reason: `no answer within ${timeoutMs / 1000} s` }), timeoutMs);
    socket.once('connect', () => done({ ok: true }));
    socket.once('error', (error: NodeJS.ErrnoException) => done({ ok: false, reason: error.code ?? error.message }));
  });
}

/** The sentence when the CARLA server cannot be reached: the run did not happen. */
export function unreachableMessage(settings: CarlaRunSettings, reason: string): string {
  return `Run in CARLA: no CARLA server at ${settings.host.trim()}:${settings.port} (${reason}). Start CARLA there (CarlaUE4.sh / CarlaUnreal.sh) or correct modular2simple.carla.host and .port; nothing was run.`;
}

/** How a ScenarioRunner run ended, from its exit code (scenario_runner.py exits 0 only when the scenario ran). */
export function runEndMessage(name: string, exitCode: number | undefined): { ran: boolean; message: string } {
  if (exitCode === 0)
    return { ran: true, message: `Run in CARLA: ScenarioRunner ran ${name} to its end (exit code 0); its verdict is in the terminal.` };
  const how = exitCode === undefined ? 'ended without an exit code' : `exited with code ${exitCode}`;
  return {
    ran: false,
    message: `Run in CARLA: ScenarioRunner ${how}: ${name} did not run to its end (a connection refused or timed out, a scenario it refused); see the terminal.`,
  };
}
