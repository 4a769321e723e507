import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as net from 'node:net';
import * as path from 'node:path';
import {
  missingRunSetting,
  reachable,
  runEndMessage,
  scenarioRunnerCommandLine,
  startProblem,
  unreachableMessage,
} from '../../client/src/carla/run';
import { temporaryFolder } from '../support/temporaryDirectory';

const settings = { host: 'carla.local', port: 2000, scenarioRunner: '/opt/scenario_runner', python: '/usr/bin/python3' };

/** A port on 127.0.0.1 that nothing listens on: one the system gave a server, closed again. */
async function closedPort(): Promise<number> {
  const server = net.createServer();
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address() as net.AddressInfo;
  await new Promise<void>((resolve) => server.close(() => resolve()));
  return port;
}

describe('client: Run in CARLA without a CARLA server', () => {
  it('builds scenario_runner.py --openscenario EXPORT --host H --port P, run in ScenarioRunner’s folder with the configured Python', () => {
    assert.deepEqual(scenarioRunnerCommandLine(settings, '/work/out/cut-in.carla.xosc'), {
      program: '/usr/bin/python3',
      args: [
        path.join('/opt/scenario_runner', 'scenario_runner.py'),
        '--openscenario',
        '/work/out/cut-in.carla.xosc',
        '--host',
        'carla.local',
        '--port',
        '2000',
      ],
      cwd: '/opt/scenario_runner',
    });
    assert.equal(scenarioRunnerCommandLine({ ...settings, python: ' ' }, 'x.xosc').program, 'python3');
  });

  it('refuses to start without a host, naming the setting, and says nothing was run', () => {
    const message = missingRunSetting({ ...settings, host: '  ' });
    assert.match(message ?? '', /set modular2simple\.carla\.host \(and modular2simple\.carla\.port, 2000 by default\)/);
    assert.match(message ?? '', /nothing was run/);
    assert.match(missingRunSetting({ ...settings, port: 70000 }) ?? '', /modular2simple\.carla\.port is 70000, not a port/);
    assert.match(missingRunSetting({ ...settings, scenarioRunner: '' }) ?? '', /set modular2simple\.carla\.scenarioRunnerPath/);
    assert.equal(missingRunSetting(settings), undefined);
  });

  it('reports a connection refused as not run, and a listening server as reachable', async () => {
    const port = await closedPort();
    const refused = await reachable('127.0.0.1', port, 10_000);
    assert.deepEqual(refused, { ok: false, reason: 'ECONNREFUSED' });
    if (!refused.ok)
      assert.match(
        unreachableMessage({ ...settings, host: '127.0.0.1', port }, refused.reason),
        new RegExp(`no CARLA server at 127\\.0\\.0\\.1:${port} \\(ECONNREFUSED\\).*nothing was run`),
      );
    const server = net.createServer((socket) => socket.end());
    await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
    try {
      assert.deepEqual(await reachable('127.0.0.1', (server.address() as net.AddressInfo).port, 10_000), { ok: true });
    } finally {
      await new Promise<void>((resolve) => server.close(() => resolve()));
    }
  });

  it('calls a run done only when ScenarioRunner exits with 0', () => {
    assert.equal(runEndMessage('cut-in', 0).ran, true);
    for (const code of [1, 255, undefined]) {
      const end = runEndMessage('cut-in', code);
      assert.equal(end.ran, false);
      assert.match(end.message, /did not run to its end/);
    }
  });

  it('refuses to start a Python that is not there, or without scenario_runner.py, naming the setting: a task whose program cannot start never ends in VS Code', () => {
    const folder = temporaryFolder();
    const scenarioRunner = path.join(folder, 'scenario_runner');
    fs.mkdirSync(scenarioRunner);
    const bin = path.join(folder, 'bin');
    fs.mkdirSync(bin);
    const python = path.join(bin, 'python3');
    fs.writeFileSync(python, '#!/bin/sh\n', { mode: 0o755 });
    const at = { ...settings, scenarioRunner, python };
    assert.match(startProblem(at, bin) ?? '', /no scenario_runner\.py in .*scenarioRunnerPath.*Nothing was run/);
    fs.writeFileSync(path.join(scenarioRunner, 'scenario_runner.py'), '');
    assert.equal(startProblem(at, bin), undefined);
    assert.equal(startProblem({ ...at, python: 'python3' }, bin), undefined, 'a name found on PATH');
    assert.match(
      startProblem({ ...at, python: 'python3' }, scenarioRunner) ?? '',
      /the Python python3 \(modular2simple\.carla\.python\) is not on PATH.*Nothing was run/,
    );
    const missing = path.join(folder, 'no-such-python');
    assert.match(startProblem({ ...at, python: missing }, bin) ?? '', /is not an executable file.*Nothing was run/);
    fs.writeFileSync(missing, '', { mode: 0o644 });
    assert.match(startProblem({ ...at, python: missing }, bin) ?? '', /is not an executable file/, 'a file that cannot be executed');
  });

  it("takes a relative Python as one in ScenarioRunner's folder, started by its absolute path from any working directory", () => {
    const folder = temporaryFolder();
    try {
      const scenarioRunner = path.join(folder, 'scenario_runner');
      fs.mkdirSync(path.join(scenarioRunner, 'venv', 'bin'), { recursive: true });
      fs.writeFileSync(path.join(scenarioRunner, 'scenario_runner.py'), '');
      const record = path.join(folder, 'started.txt');
      // The venv's Python records where it was started and with what, as scenario_runner.py would be.
      fs.writeFileSync(path.join(scenarioRunner, 'venv', 'bin', 'python'), `#!/bin/sh\necho "$0 $(pwd) $*" > '${record}'\n`, {
        mode: 0o755,
      });
      const at = { ...settings, scenarioRunner, python: 'venv/bin/python' };
      assert.equal(startProblem(at, ''), undefined);
      const line = scenarioRunnerCommandLine(at, path.join(folder, 'cut-in.carla.xosc'));
      assert.equal(line.program, path.join(scenarioRunner, 'venv', 'bin', 'python'));
      // Started as a task starts it, and from elsewhere: the same file runs (nothing depends on how a relative program is looked up).
      for (const cwd of [line.cwd, folder]) {
        fs.rmSync(record, { force: true });
        assert.equal(spawnSync(line.program, line.args, { cwd }).status, 0);
        assert.match(fs.readFileSync(record, 'utf8'), new RegExp(`^${line.program} ${cwd} .*scenario_runner\\.py --openscenario`));
      }
      // Not there in ScenarioRunner's folder: said with the path looked at, nothing run.
      assert.match(
        startProblem({ ...at, python: 'env/bin/python' }, '') ?? '',
        new RegExp(`the Python ${path.join(scenarioRunner, 'env', 'bin', 'python')} .*is not an executable file.*Nothing was run`),
      );
    } finally {
      fs.rmSync(folder, { recursive: true, force: true });
    }
  });
});
