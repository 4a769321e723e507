import * as assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { mainOf, scenario, simpleGroup } from '../support/fixtures';
import { canUnshareMounts, runBounded } from '../support/hostile';
import { cliPath } from '../support/paths';
import { temporaryWorkspace } from '../support/workspace';

describe('cli: inputs that are not regular files', function () {
  this.timeout(180_000);

  function withFifo(files: Record<string, string>, fifo: string): string {
    const root = temporaryWorkspace(files);
    fs.mkdirSync(path.dirname(path.join(root, fifo)), { recursive: true });
    execFileSync('mkfifo', [path.join(root, fifo)]);
    return root;
  }

  it('flatten of a FIFO named main.xosc ends with a message', () => {
    const root = withFifo({}, 'pkg/main.xosc');
    const run = runBounded(['flatten', 'pkg'], { cwd: root, timeoutMs: 45_000 });
    assert.ok(!run.timedOut, 'did not hang on the FIFO');
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /is a FIFO, not a file/);
  });

  it('check of a folder holding a FIFO ends with a message', () => {
    const root = withFifo({ 'ok.xosc': scenario(simpleGroup('Go')) }, 'lib/stuck.xosc');
    const run = runBounded(['check', '.'], { cwd: root, timeoutMs: 45_000 });
    assert.ok(!run.timedOut, 'did not hang on the FIFO');
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /stuck\.xosc is a FIFO, not a file/);
  });

  it('stats of a library whose main.xosc is a FIFO or a folder ends with a message', () => {
    const root = withFifo(
      { 'lib/good/main.xosc': mainOf('simple.xosc'), 'lib/good/simple.xosc': scenario(simpleGroup('Go')) },
      'lib/fifo/main.xosc',
    );
    fs.mkdirSync(path.join(root, 'lib/folder/main.xosc'), { recursive: true });
    const run = runBounded(['stats', 'lib'], { cwd: root, timeoutMs: 45_000 });
    assert.ok(!run.timedOut, 'did not hang on the FIFO');
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /fifo\/main\.xosc is a FIFO, not a file/);
    assert.match(run.stderr, /folder\/main\.xosc is a folder, not a file/);
    assert.doesNotMatch(run.stderr, /EISDIR|internal error/);
    assert.match(run.stdout, /good/);
  });

  it('a symbolic link to a device is refused, not read without end (in a private /dev)', function () {
    if (!canUnshareMounts()) {
      console.log('    (skipped: no private mount namespace here, and the test must not touch the real /dev)');
      this.skip();
    }
    const root = temporaryWorkspace({});
    fs.symlinkSync('/dev/zero', path.join(root, 'zero.xosc'));
    fs.mkdirSync(path.join(root, 'pkg'));
    fs.symlinkSync('/dev/zero', path.join(root, 'pkg', 'main.xosc'));
    const script = `mount -t tmpfs none /dev && mknod /dev/zero c 1 5 && cd "${root}" && for command in "flatten --schema-version=off pkg" "check --schema-version=off ." "flatten --schema-version=off zero.xosc"; do timeout -s KILL 45 "${process.execPath}" --max-old-space-size=128 "${cliPath}" $command; echo "exit $?"; done`;
    const run = spawnSync('unshare', ['-m', '--propagation', 'private', 'sh', '-c', script], { encoding: 'utf8', timeout: 170_000 });
    assert.deepEqual(run.stdout.match(/exit \d+/g), ['exit 1', 'exit 1', 'exit 1'], run.stderr);
    assert.match(run.stderr, /is a character device, not a file/);
  });

  it('a file over the size bound is reported as too large, not as missing', () => {
    const root = temporaryWorkspace({
      'main.xosc': mainOf('big.xosc'),
      'big.xosc': scenario(simpleGroup('Go')) + `<!-- ${'x'.repeat(4096)} -->`,
    });
    const run = runBounded(['check', 'main.xosc', '--max-file-size', '2K'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /big\.xosc is too large to read \(\d+ bytes; the limit is 2048/);
    assert.doesNotMatch(run.stderr, /no such file/);
  });

  it('check and format of a folder that holds no scenario file say so and exit 1, not a clean pass (a mistyped CI folder)', () => {
    const root = temporaryWorkspace({ 'scenarios/ok.xosc': scenario(simpleGroup('Go')), 'empty/notes.txt': 'not a scenario' });
    for (const format of [[], ['--format', 'json'], ['--format', 'sarif']]) {
      const run = runBounded(['check', 'scenarios', 'empty', ...format], { cwd: root });
      assert.equal(run.status, 1, run.stderr);
      assert.match(run.stderr, /empty: the folder holds no \.xosc or \.mosc file, so nothing was checked; name the folder/);
    }
    const formatted = runBounded(['format', '--check', 'empty'], { cwd: root });
    assert.equal(formatted.status, 1, formatted.stderr);
    assert.match(formatted.stderr, /empty: error: the folder holds no \.xosc file, so nothing was formatted/);
    const clean = runBounded(['check', 'scenarios'], { cwd: root });
    assert.equal(clean.status, 0, clean.stderr);
  });

  it('run and export of a folder without main.xosc say so, as flatten does, not that a main.xosc in it cannot be read at 1:1', () => {
    const root = temporaryWorkspace({ 'pkg/notes.txt': 'not a scenario' });
    for (const args of [
      ['run', 'pkg'],
      ['export', 'pkg', '--target', 'carla', '-o', 'out.xosc'],
      ['flatten', 'pkg'],
    ]) {
      const run = runBounded(args, { cwd: root });
      assert.equal(run.status, 1, run.stderr);
      assert.match(run.stderr, /pkg: the folder holds no main\.xosc, so it is not an unpacked package/, args[0]);
      assert.doesNotMatch(run.stderr, /cannot read|1:1/, args[0]);
    }
    assert.ok(!fs.existsSync(path.join(root, 'out.xosc')));
  });
});
