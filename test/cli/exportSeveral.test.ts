import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { drivingScenario, runCli } from '../support/fixtures';
import { listFiles, temporaryWorkspace } from '../support/workspace';

const exportArgs = ['--target', 'carla', '-q'];

describe('cli: export of several inputs in one process', () => {
  it('writes each input as FOLDER/NAME.xosc (a folder input by its own name), its report as NAME.json, byte for byte as alone', () => {
    const root = temporaryWorkspace({
      'a.xosc': drivingScenario('Town05', 'Drive'),
      'b/main.xosc': drivingScenario('Town04', 'Drive'),
    });
    const together = runCli(['export', 'a.xosc', 'b', ...exportArgs, '-o', 'out/carla', '--report', 'reports'], { cwd: root });
    assert.equal(together.status, 0, together.stderr);
    assert.deepEqual(listFiles(root), [
      'a.xosc',
      'b/main.xosc',
      'out/carla/a.xosc',
      'out/carla/b.xosc',
      'reports/a.json',
      'reports/b.json',
    ]);
    for (const [input, name] of [
      ['a.xosc', 'a'],
      ['b', 'b'],
    ]) {
      const alone = runCli(['export', input, ...exportArgs, '-o', `alone-${name}.xosc`, '--report', `alone-${name}.json`], { cwd: root });
      assert.equal(alone.status, 0, alone.stderr);
      assert.equal(
        fs.readFileSync(path.join(root, 'out/carla', `${name}.xosc`), 'utf8'),
        fs.readFileSync(path.join(root, `alone-${name}.xosc`), 'utf8'),
      );
      const report = JSON.parse(fs.readFileSync(path.join(root, 'reports', `${name}.json`), 'utf8')) as {
        output: string;
        written: boolean;
      };
      assert.equal(report.output, path.join(root, 'out/carla', `${name}.xosc`));
      assert.equal(report.written, true);
    }
    const told = runCli(['export', 'a.xosc', 'b', '--target', 'carla', '-o', 'out/carla'], { cwd: root });
    assert.match(told.stderr, /modular2simple: exported 2 of 2 inputs into out\/carla\n$/);
  });

  it('goes on past a refused input and a missing one: the others are written, the exit is the worst, the summary counts', () => {
    const root = temporaryWorkspace({
      'good.xosc': drivingScenario('Town05', 'Drive'),
      'noroad.xosc': drivingScenario('missing.xodr', 'Drive'),
    });
    const run = runCli(['export', 'noroad.xosc', 'absent.xosc', 'good.xosc', ...exportArgs, '-o', 'out'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /noroad\.xosc:\d+:\d+: error: <LogicFile> names the road 'missing\.xodr'/);
    assert.match(run.stderr, /modular2simple: export refused: .*noroad\.xosc.*nothing was written/);
    assert.match(run.stderr, /modular2simple: error: absent\.xosc: no such file or folder/);
    assert.match(run.stderr, /modular2simple: exported 1 of 3 inputs into out\n$/);
    assert.deepEqual(listFiles(root), ['good.xosc', 'noroad.xosc', 'out/good.xosc']);
  });

  it('makes no folder when nothing is written', () => {
    const root = temporaryWorkspace({ 'noroad.xosc': drivingScenario('missing.xodr', 'Drive') });
    const run = runCli(['export', 'noroad.xosc', 'absent.xosc', ...exportArgs, '-o', 'out'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /modular2simple: exported 0 of 2 inputs\n$/);
    assert.deepEqual(listFiles(root), ['noroad.xosc']);
  });

  it('refuses, before reading any input: two inputs of one name, -o or --report a file, --index', () => {
    const root = temporaryWorkspace({
      'a.xosc': drivingScenario('Town05', 'Drive'),
      'b.xosc': drivingScenario('Town05', 'Drive'),
      'x/a.xosc': drivingScenario('Town05', 'Drive'),
      'taken.txt': 'a file',
    });
    const cases: [string[], RegExp][] = [
      [['a.xosc', 'x/a.xosc', '-o', 'out'], /a\.xosc and x\/a\.xosc would both be written as a\.xosc: export one of them on its own/],
      [['a.xosc', 'b.xosc', '-o', 'taken.txt'], /with several inputs, -o and --report name folders, and taken\.txt is a file/],
      [
        ['a.xosc', 'b.xosc', '-o', 'out', '--report', 'taken.txt'],
        /with several inputs, -o and --report name folders, and taken\.txt is a file/,
      ],
      [
        ['a.xosc', 'b.xosc', '-o', 'out', '--index', '0'],
        /--index chooses the concrete scenario of one distribution file: export it alone/,
      ],
    ];
    for (const [args, message] of cases) {
      const run = runCli(['export', ...args, '--target', 'carla'], { cwd: root });
      assert.equal(run.status, 2, `${args.join(' ')}: ${run.stderr}`);
      assert.match(run.stderr, message);
    }
    assert.deepEqual(listFiles(root), ['a.xosc', 'b.xosc', 'taken.txt', 'x/a.xosc']);
  });
});
