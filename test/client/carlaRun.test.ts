import * as assert from 'node:assert/strict';
import * as net from 'node:net';
import * as path from 'node:path';
import { missingRunSetting, reachable, runEndMessage, scenarioRunnerCommandLine, unreachableMessage } from '../../client/src/carla/run';

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
});
