import * as assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import { main } from '../../server/src/cli';
import { isWellFormed, parseXml } from '../../server/src/core/xml';
import { outerGroup, scenario, simpleGroup } from '../support/fixtures';
import { canUnshareMounts, rawZip, runBounded, scalingRatio, startScript } from '../support/hostile';
import { cliPath, repoRoot } from '../support/paths';
import { listFiles, temporaryWorkspace } from '../support/workspace';

/** A main file importing group Go of `file` for the outer group Car. */
function mainOf(file: string, groupName = 'Go'): string {
  return scenario(outerGroup('Car', 'car', [{ file, groups: [{ name: groupName }] }]));
}

function assertNoTrace(stderr: string): void {
  assert.doesNotMatch(stderr, /\n\s+at .*:\d+:\d+\)?/, 'no stack trace');
  assert.doesNotMatch(stderr, /internal error/);
}

describe('cli: hostile archives', function () {
  this.timeout(60_000);

  it('refuses entries that share one compressed stream, without inflating each of them', () => {
    const zeros = new Uint8Array(8 * 1024 * 1024);
    const aliases = Array.from({ length: 300 }, (_, index) => ({ name: `s${index}.xosc`, of: 1 }));
    const root = temporaryWorkspace({ 'bomb.mosc': rawZip([{ name: 'main.xosc', data: mainOf('s0.xosc') }, { name: 'pad.xosc', data: zeros, deflate: true }], aliases) });
    const run = runBounded(['check', 'bomb.mosc'], { cwd: root, timeoutMs: 15_000, heapMb: 128 });
    assert.ok(!run.timedOut, `finished in ${run.ms} ms`);
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /overlap in the archive/);
    assertNoTrace(run.stderr);
  });

  it('bounds what one run unpacks from all packages together, not per package', async () => {
    // Four packages of 3 MB each (a few KB compressed): each within any bound, together over 8M.
    const padding = `<!-- ${'x'.repeat(3 * 1024 * 1024)} -->`;
    const files: Record<string, Uint8Array | string> = {};
    const groups: string[] = [];
    for (let index = 0; index < 4; index++) {
      const zip = new JSZip();
      zip.file('main.xosc', scenario(simpleGroup('Go')).replace('</OpenSCENARIO>', `${padding}</OpenSCENARIO>`));
      files[`p${index}.mosc`] = await zip.generateAsync({ type: 'uint8array', compression: 'DEFLATE' });
      groups.push(outerGroup(`Car${index}`, 'car', [{ file: `p${index}.mosc`, groups: [{ name: 'Go' }] }]));
    }
    files['main.xosc'] = scenario(groups.join(''));
    const root = temporaryWorkspace(files);
    const within = runBounded(['check', 'main.xosc', '--max-unpacked-size', '16M'], { cwd: root });
    assert.equal(within.status, 0, within.stderr);
    const over = runBounded(['check', 'main.xosc', '--max-unpacked-size', '8M'], { cwd: root });
    assert.equal(over.status, 1, over.stderr);
    assert.match(over.stderr, /exceed the 8388608 bytes that one run may unpack from all packages together/);
    assert.match(over.stderr, /--max-unpacked-size/);
  });

  for (const [label, second] of [
    ['main.xosc twice', 'main.xosc'],
    ['main.xosc and ./main.xosc', './main.xosc'],
  ]) {
    it(`refuses a package holding ${label}`, () => {
      const evil = mainOf('missing.xosc');
      const root = temporaryWorkspace({ 'dup.mosc': rawZip([{ name: 'main.xosc', data: scenario(simpleGroup('Go')) }, { name: second, data: evil }]) });
      const run = runBounded(['flatten', 'dup.mosc'], { cwd: root });
      assert.equal(run.status, 1, run.stderr);
      assert.match(run.stderr, /holds the entry 'main\.xosc' twice/);
      assert.equal(run.stdout, '', 'nothing was flattened from either copy');
    });
  }
});

describe('cli: inputs that are not regular files', function () {
  this.timeout(60_000);

  function withFifo(files: Record<string, string>, fifo: string): string {
    const root = temporaryWorkspace(files);
    fs.mkdirSync(path.dirname(path.join(root, fifo)), { recursive: true });
    execFileSync('mkfifo', [path.join(root, fifo)]);
    return root;
  }

  it('flatten of a FIFO named main.xosc ends with a message', () => {
    const root = withFifo({}, 'pkg/main.xosc');
    const run = runBounded(['flatten', 'pkg'], { cwd: root, timeoutMs: 10_000 });
    assert.ok(!run.timedOut, 'did not hang on the FIFO');
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /is a FIFO, not a file/);
  });

  it('check of a folder holding a FIFO ends with a message', () => {
    const root = withFifo({ 'ok.xosc': scenario(simpleGroup('Go')) }, 'lib/stuck.xosc');
    const run = runBounded(['check', '.'], { cwd: root, timeoutMs: 10_000 });
    assert.ok(!run.timedOut, 'did not hang on the FIFO');
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /stuck\.xosc is a FIFO, not a file/);
  });

  it('stats of a library whose main.xosc is a FIFO or a folder ends with a message', () => {
    const root = withFifo({ 'lib/good/main.xosc': mainOf('simple.xosc'), 'lib/good/simple.xosc': scenario(simpleGroup('Go')) }, 'lib/fifo/main.xosc');
    fs.mkdirSync(path.join(root, 'lib/folder/main.xosc'), { recursive: true });
    const run = runBounded(['stats', 'lib'], { cwd: root, timeoutMs: 10_000 });
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
    const script = `mount -t tmpfs none /dev && mknod /dev/zero c 1 5 && cd "${root}" && for command in "flatten --schema-version=off pkg" "check --schema-version=off ." "flatten --schema-version=off zero.xosc"; do timeout -s KILL 10 "${process.execPath}" --max-old-space-size=128 "${cliPath}" $command; echo "exit $?"; done`;
    const run = spawnSync('unshare', ['-m', '--propagation', 'private', 'sh', '-c', script], { encoding: 'utf8', timeout: 60_000 });
    assert.deepEqual(run.stdout.match(/exit \d+/g), ['exit 1', 'exit 1', 'exit 1'], run.stderr);
    assert.match(run.stderr, /is a character device, not a file/);
  });

  it('a file over the size bound is reported as too large, not as missing', () => {
    const root = temporaryWorkspace({ 'main.xosc': mainOf('big.xosc'), 'big.xosc': scenario(simpleGroup('Go')) + `<!-- ${'x'.repeat(4096)} -->` });
    const run = runBounded(['check', 'main.xosc', '--max-file-size', '2K'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /big\.xosc is too large to read \(\d+ bytes; the limit is 2048/);
    assert.doesNotMatch(run.stderr, /no such file/);
  });
});

describe('cli: reuse blow-up', function () {
  this.timeout(120_000);

  it('a group imported twice at each of 20 levels is an error naming the chain, not an out-of-memory crash', () => {
    const files: Record<string, string> = { 'l20.xosc': scenario(simpleGroup('G')) };
    for (let level = 0; level < 20; level++) {
      // G holds two groups that each import G of the next level, so G doubles at every level.
      const half = (name: string) => outerGroup(name, 'car', [{ file: `l${level + 1}.xosc`, groups: [{ name: 'G' }] }]);
      const group = `        <ManeuverGroup name="G" maximumExecutionCount="1">\n          <Actors selectTriggeringEntities="false"><EntityRef entityRef="car"/></Actors>\n${half('X')}${half('Y')}        </ManeuverGroup>\n`;
      files[`l${level}.xosc`] = scenario(group);
    }
    const root = temporaryWorkspace(files);
    const run = runBounded(['flatten', 'l0.xosc', '-o', 'out.xosc', '--max-output-size', '4M'], { cwd: root, timeoutMs: 60_000, heapMb: 256 });
    assert.ok(!run.timedOut, 'finished');
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /would exceed 4,194,304 characters/);
    assert.match(run.stderr, /l\d+\.xosc -> l\d+\.xosc -> .*l20\.xosc/);
    assert.ok(!fs.existsSync(path.join(root, 'out.xosc')));
    // The same with the default bound: still an error, in bounded memory.
    const byDefault = runBounded(['check', 'l0.xosc'], { cwd: root, timeoutMs: 90_000, heapMb: 512 });
    assert.equal(byDefault.status, 1, byDefault.stderr.slice(-2000));
    assert.match(byDefault.stderr, /would exceed/);
  });

  it('references nested deeper than the bound are an error naming the chain', () => {
    const files: Record<string, string> = { 'd30.xosc': scenario(simpleGroup('Go')) };
    for (let level = 0; level < 30; level++) files[`d${level}.xosc`] = scenario(simpleGroup('Go').replace('</ManeuverGroup>', '</ManeuverGroup>\n' + outerGroup('Car', 'car', [{ file: `d${level + 1}.xosc`, groups: [{ name: 'Go' }] }])));
    const root = temporaryWorkspace(files);
    const run = runBounded(['check', 'd0.xosc', '--max-depth', '10'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /references nest deeper than 10 files: d0\.xosc -> d1\.xosc/);
    assert.equal(runBounded(['check', 'd0.xosc', '--max-depth', '40'], { cwd: root }).status, 0);
  });
});

describe('cli: parsing and resolution scale linearly', function () {
  this.timeout(600_000);
  // Ratios of times at two sizes, best of three runs each, in a child process: a linear operation
  // gives about 4 for 4x the size, a quadratic one 16. The bound of 10 leaves room for a busy machine
  // and for the garbage collector, whose share grows with the heap.
  it('duplicate attributes: 4x the attributes take under 10x the time', () => {
    const { ratio, smallMs, largeMs } = scalingRatio('attributes', 50_000);
    assert.ok(ratio < 10, `50,000 attributes: ${smallMs.toFixed(0)} ms; 200,000: ${largeMs.toFixed(0)} ms (x${ratio.toFixed(1)})`);
  });

  it('end tags that match nothing: 4x the tags take under 10x the time', () => {
    const { ratio, smallMs, largeMs } = scalingRatio('end-tags', 250_000);
    assert.ok(ratio < 10, `250,000 end tags: ${smallMs.toFixed(0)} ms; 1,000,000: ${largeMs.toFixed(0)} ms (x${ratio.toFixed(1)})`);
  });

  it('nested packages: twice the levels take under 6x the time (the bytes unpacked grow as n^2; n^4 was the bug)', () => {
    const { ratio, smallMs, largeMs } = scalingRatio('nested-packages', 100, 2);
    assert.ok(ratio < 6, `100 levels: ${smallMs.toFixed(0)} ms; 200: ${largeMs.toFixed(0)} ms (x${ratio.toFixed(1)})`);
  });
});

describe('cli: text that is not what it claims', function () {
  this.timeout(60_000);

  it('NUL, other control characters and references to non-characters are errors at their position', () => {
    const simple = scenario(simpleGroup('Go'))
      .replace('name="GoManeuver"', 'name="Go\u0001Maneuver"')
      .replace('<Event name="Go"', '<Event name="a&#1;b"')
      .replace('<Action name="Go"', '<Action name="&#xFFFE;"');
    const root = temporaryWorkspace({ 'main.xosc': mainOf('simple.xosc'), 'simple.xosc': simple });
    const run = runBounded(['flatten', 'main.xosc'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    const line = (needle: string) => simple.split('\n').findIndex((text) => text.includes(needle)) + 1;
    assert.match(run.stderr, new RegExp(`simple\\.xosc:${line('GoManeuver') || line('Maneuver name')}:\\d+: error: the character U\\+0001 is not allowed`));
    assert.match(run.stderr, new RegExp(`simple\\.xosc:${line('&#1;')}:\\d+: error: the character reference '&#1;' names U\\+0001`));
    assert.match(run.stderr, /character reference '&#xFFFE;' names U\+FFFE/);
    assert.equal(run.stdout, '');
  });

  it('decodes ISO-8859-1 as declared and UTF-16 with a byte-order mark; the output is UTF-8 and says so', () => {
    const latin = scenario(simpleGroup('Go')).replace('encoding="UTF-8"', 'encoding="ISO-8859-1"').replace('name="GoManeuver"', 'name="Gr\u00fc\u00dfe"');
    const utf16 = Buffer.concat([Buffer.from([0xff, 0xfe]), Buffer.from(mainOf('latin.xosc').replace('encoding="UTF-8"', 'encoding="UTF-16"'), 'utf16le')]);
    const root = temporaryWorkspace({ 'main.xosc': utf16, 'latin.xosc': Buffer.from(latin, 'latin1') });
    const run = runBounded(['flatten', 'main.xosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stdout, /^<\?xml version="1.0" encoding="UTF-8"\?>/);
    assert.match(run.stdout, /name="Gr\u00fc\u00dfe"/);
    assert.doesNotMatch(run.stdout, /\uFFFD/);
  });

  it('refuses invalid UTF-8 and an encoding it cannot read, naming them', () => {
    const broken = Buffer.from(scenario(simpleGroup('Go')).replace('name="GoManeuver"', 'name="Gr\u00fc"'), 'latin1');
    const ebcdic = scenario(simpleGroup('Go')).replace('encoding="UTF-8"', 'encoding="EBCDIC-US"');
    const root = temporaryWorkspace({ 'a.xosc': broken, 'b.xosc': ebcdic, 'main.xosc': scenario(outerGroup('A', 'car', [{ file: 'a.xosc', groups: [{ name: 'Go' }] }]) + outerGroup('B', 'car', [{ file: 'b.xosc', groups: [{ name: 'Go' }] }])) });
    const run = runBounded(['check', 'main.xosc'], { cwd: root });
    assert.equal(run.status, 1, run.stderr);
    assert.match(run.stderr, /a\.xosc:\d+:1: error: .*byte 0xfc at offset \d+ is not valid UTF-8/);
    assert.match(run.stderr, /encoding="EBCDIC-US", which cannot be read/);
    assert.doesNotMatch(run.stderr, /\uFFFD/);
  });

  it('an internal DTD entity used inside an imported group is expanded in the copy', () => {
    const simple = scenario(simpleGroup('Go'))
      .replace('<OpenSCENARIO>', '<!DOCTYPE OpenSCENARIO [\n  <!ENTITY speed "12.5">\n  <!ENTITY who "car &amp; co">\n]>\n<OpenSCENARIO>')
      .replace('z="0"', 'z="&speed;"')
      .replace('<Event name="Go" priority="overwrite">', '<Event name="Go" priority="overwrite">\n              <!-- &who; -->\n              <Note>&who; at &speed;</Note>');
    const root = temporaryWorkspace({ 'main.xosc': mainOf('simple.xosc'), 'simple.xosc': simple });
    const run = runBounded(['flatten', 'main.xosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.ok(isWellFormed(parseXml(run.stdout)), 'the output is well-formed');
    assert.match(run.stdout, /z="12\.5"/);
    assert.match(run.stdout, /<Note>car &amp; co at 12\.5<\/Note>/);
  });
});

describe('cli: outputs', function () {
  this.timeout(60_000);

  it('pack never writes over a package the folder references, directly or through SCENARIO_PATH', async () => {
    const inner = new JSZip();
    inner.file('main.xosc', scenario(simpleGroup('Go')));
    const innerBytes = await inner.generateAsync({ type: 'uint8array' });
    const root = temporaryWorkspace({ 'pkg/main.xosc': mainOf('inner.mosc'), 'pkg/inner.mosc': innerBytes, 'other/main.xosc': mainOf('lib.mosc'), 'lib/lib.mosc': innerBytes });
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
        const timer = setTimeout(() => resolve(false), 20_000);
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
      const watchdog = setTimeout(() => child.kill('SIGKILL'), 10_000);
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

describe('cli: messages', () => {
  it('an internal error exits with 4, not with 3 (could not write)', async () => {
    const errors: string[] = [];
    const code = await main(['--version'], {
      out: () => {
        throw new Error('a bug');
      },
      err: (text) => errors.push(text),
    });
    assert.equal(code, 4);
    assert.match(errors.join('\n'), /internal error: .*a bug/);
    assert.match(fs.readFileSync(path.join(repoRoot, 'README.md'), 'utf8'), /\| 4 \| internal error/);
  });
});
