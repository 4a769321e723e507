import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import { mainOf, scenario, simpleGroup } from '../support/fixtures';
import { canUnshareMounts, runBounded, startScript } from '../support/hostile';
import { cliPath, repoRoot } from '../support/paths';
import { listFiles, temporaryWorkspace } from '../support/workspace';

describe('cli: outputs', function () {
  this.timeout(60_000);

  it('pack never writes over a package the folder references, directly or through SCENARIO_PATH', async () => {
    const inner = new JSZip();
    inner.file('main.xosc', scenario(simpleGroup('Go')));
    const innerBytes = await inner.generateAsync({ type: 'uint8array' });
    const root = temporaryWorkspace({
      'pkg/main.xosc': mainOf('inner.mosc'),
      'pkg/inner.mosc': innerBytes,
      'other/main.xosc': mainOf('lib.mosc'),
      'lib/lib.mosc': innerBytes,
    });
    const direct = runBounded(['pack', 'pkg', '-o', 'pkg/inner.mosc'], { cwd: root });
    assert.equal(direct.status, 1, direct.stderr);
    assert.match(direct.stderr, /refusing to write pkg\/inner\.mosc: it is an input/);
    assert.deepEqual(new Uint8Array(fs.readFileSync(path.join(root, 'pkg/inner.mosc'))), innerBytes);
    const throughPath = runBounded(['pack', 'other', '-o', 'lib/lib.mosc'], { cwd: root, env: { SCENARIO_PATH: path.join(root, 'lib') } });
    assert.equal(throughPath.status, 1, throughPath.stderr);
    assert.match(throughPath.stderr, /it is an input/);
    assert.deepEqual(new Uint8Array(fs.readFileSync(path.join(root, 'lib/lib.mosc'))), innerBytes);
  });

  function flatWorkspace(): string {
    return temporaryWorkspace({ 'main.xosc': mainOf('simple.xosc'), 'simple.xosc': scenario(simpleGroup('Go')) });
  }

  it('-o - writes to standard output', () => {
    const root = flatWorkspace();
    const run = runBounded(['flatten', 'main.xosc', '-o', '-'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stdout, /name="Car\.Go"/);
    assert.ok(!fs.existsSync(path.join(root, '-')));
  });

  it('-o /dev/null and /dev/stdout stay devices (in a private /dev)', function () {
    if (!canUnshareMounts()) {
      console.log('    (skipped: no private mount namespace here, and the test must not touch the real /dev)');
      this.skip();
    }
    const root = flatWorkspace();
    const script = `mount -t tmpfs none /dev && mknod /dev/null c 1 3 && ln -s /proc/self/fd/1 /dev/stdout && cd "${root}" && "${process.execPath}" "${cliPath}" flatten --schema-version=off main.xosc -o /dev/null && "${process.execPath}" "${cliPath}" flatten --schema-version=off main.xosc -o /dev/stdout > captured.xosc && stat -c %F /dev/null && ls -a /dev`;
    const run = spawnSync('unshare', ['-m', '--propagation', 'private', 'sh', '-c', script], { encoding: 'utf8', timeout: 30_000 });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stdout, /character special file/);
    assert.doesNotMatch(run.stdout, /\.m2s-.*\.tmp/, 'no temporary file left in /dev');
    assert.match(fs.readFileSync(path.join(root, 'captured.xosc'), 'utf8'), /name="Car\.Go"/);
  });

  it('a read-only output is refused, as a shell redirection would refuse it', () => {
    const root = flatWorkspace();
    const output = path.join(root, 'out.xosc');
    fs.writeFileSync(output, 'keep');
    fs.chmodSync(output, 0o444);
    const run = runBounded(['flatten', 'main.xosc', '-o', 'out.xosc'], { cwd: root });
    assert.equal(run.status, 3, run.stderr);
    assert.match(run.stderr, /out\.xosc is read-only/);
    assert.equal(fs.readFileSync(output, 'utf8'), 'keep');
  });

  it('keeps the mode of an existing output, and a 245-byte output name works', () => {
    const root = flatWorkspace();
    const output = path.join(root, 'out.xosc');
    fs.writeFileSync(output, 'old', { mode: 0o600 });
    fs.chmodSync(output, 0o600);
    assert.equal(runBounded(['flatten', 'main.xosc', '-o', 'out.xosc'], { cwd: root }).status, 0);
    assert.equal(fs.statSync(output).mode & 0o777, 0o600);
    const long = 'n'.repeat(240) + '.xosc';
    const run = runBounded(['flatten', 'main.xosc', '-o', long], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(fs.readFileSync(path.join(root, long), 'utf8'), /Car\.Go/);
  });

  for (const signal of ['SIGINT', 'SIGTERM'] as const) {
    it(`${signal} while an output is written removes the temporary file and leaves the target`, async () => {
      const root = temporaryWorkspace({ 'out.xosc': 'before' });
      const child = startScript(path.join(repoRoot, 'test', 'support', 'slowWrite.ts'), [path.join(root, 'out.xosc')]);
      const ready = await new Promise<boolean>((resolve) => {
        // The writer is a tsx script: its start alone may take tens of seconds on a loaded machine.
        const timer = setTimeout(() => resolve(false), 60_000);
        child.stdout.on('data', (chunk: Buffer) => {
          if (chunk.toString().includes('writing')) {
            clearTimeout(timer);
            resolve(true);
          }
        });
      });
      assert.ok(ready, 'the writer started');
      assert.equal(fs.readdirSync(root).filter((name) => name.endsWith('.tmp')).length, 1, 'a temporary file exists while writing');
      const exited = new Promise<NodeJS.Signals | null>((resolve) => child.on('exit', (_code, received) => resolve(received)));
      child.kill(signal);
      const watchdog = setTimeout(() => child.kill('SIGKILL'), 60_000);
      assert.equal(await exited, signal);
      clearTimeout(watchdog);
      assert.deepEqual(fs.readdirSync(root), ['out.xosc']);
      assert.equal(fs.readFileSync(path.join(root, 'out.xosc'), 'utf8'), 'before');
    });
  }

  it('--out-dir writes all outputs or none', () => {
    const root = flatWorkspace();
    fs.mkdirSync(path.join(root, 'second'));
    fs.copyFileSync(path.join(root, 'main.xosc'), path.join(root, 'second', 'main.xosc'));
    fs.copyFileSync(path.join(root, 'simple.xosc'), path.join(root, 'second', 'simple.xosc'));
    fs.mkdirSync(path.join(root, 'out'));
    // The second output is blocked: a folder stands where it would go.
    fs.mkdirSync(path.join(root, 'out', 'second.xosc'));
    const before = listFiles(root);
    const run = runBounded(['flatten', 'main.xosc', 'second', '--out-dir', 'out'], { cwd: root });
    assert.equal(run.status, 3, run.stderr);
    assert.match(run.stderr, /second\.xosc: error: cannot write the output \(.*is a folder\); nothing was changed/);
    assert.deepEqual(listFiles(root), before, 'the first output was not written either');
  });
});
