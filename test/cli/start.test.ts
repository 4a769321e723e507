import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { createRequire } from 'node:module';
import { Script } from 'node:vm';
import * as fs from 'node:fs';
import * as path from 'node:path';
import {
  bundleFor,
  cacheFileFor,
  CLI_BUNDLE,
  CliEntry,
  CODE_CACHE_SUFFIX,
  COMMAND_BUNDLES,
  commandBundle,
  EXPORT_VALUE_OPTIONS,
  loadBundle,
  PLAIN_EXPORT_CACHE_SUFFIX,
} from '../../server/src/cli/start';
import { warmingRuns } from '../../scripts/cli-code-cache.mjs';
import { EXPORT_OPTIONS } from '../../server/src/cli/export';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';

const dist = path.join(repoRoot, 'dist');
const examples = path.join(repoRoot, 'examples');

describe("cli: the program's entry runs a command's own bundle", function () {
  this.timeout(60_000);

  it('a short command runs its own bundle, every other command line the whole CLI', () => {
    assert.equal(bundleFor(dist, ['flatten', 'x.mosc']), 'cli-flatten.js');
    assert.equal(bundleFor(dist, ['-cmx', 'a.mosc', 'b.xosc']), 'cli-flatten.js');
    assert.equal(bundleFor(dist, ['--convert-xosc-into-mosc', 'a.xosc', 'b.mosc']), 'cli-pack.js');
    assert.equal(bundleFor(dist, ['check', '.']), 'cli-check.js');
    for (const argv of [[], ['--help'], ['--version'], ['run', 'x.xosc'], ['batch'], ['nonsense'], ['toString'], ['__proto__']])
      assert.equal(bundleFor(dist, argv), CLI_BUNDLE, argv.join(' '));
  });

  it('the build wrote every command bundle with a code cache that V8 accepts', () => {
    const exportBundle = commandBundle(COMMAND_BUNDLES.export);
    for (const [file, cache] of [
      ...[CLI_BUNDLE, ...new Set(Object.values(COMMAND_BUNDLES).map(commandBundle))].map((each) => [each, each + CODE_CACHE_SUFFIX]),
      [exportBundle, exportBundle + PLAIN_EXPORT_CACHE_SUFFIX],
    ]) {
      const { script, exports } = loadBundle(dist, require, fs.readFileSync(path.join(dist, cache)), file);
      assert.equal(script.cachedDataRejected, false, `${cache} was rejected`);
      assert.equal(typeof exports.main, 'function', file);
    }
  });

  it("a plain .xosc's export reads the export bundle's cache without the flattener; a modular main's, anything else, the bundle's own", () => {
    const exportBundle = commandBundle(COMMAND_BUNDLES.export);
    const own = exportBundle + CODE_CACHE_SUFFIX;
    const exportOf = (input: string, ...rest: string[]) => cacheFileFor(exportBundle, ['export', input, '--target', 'carla', ...rest]);
    assert.equal(exportOf(path.join(examples, 'crossing.xosc'), '-o', 'out.xosc'), exportBundle + PLAIN_EXPORT_CACHE_SUFFIX);
    assert.equal(exportOf(path.join(examples, 'crossing.xosc'), '--road-path', 'x.xosc', '-q'), exportBundle + PLAIN_EXPORT_CACHE_SUFFIX);
    // A modular main, a package, a folder, a file not there, two inputs.
    assert.equal(exportOf(path.join(examples, 'main.xosc'), '-o', 'out.xosc'), own);
    assert.equal(exportOf(path.join(examples, 'braking.mosc'), '-o', 'out.xosc'), own);
    assert.equal(exportOf(path.join(examples, 'pedestrian'), '-o', 'out.xosc'), own);
    assert.equal(exportOf(path.join(examples, 'absent.xosc'), '-o', 'out.xosc'), own);
    assert.equal(exportOf(path.join(examples, 'crossing.xosc'), path.join(examples, 'lane_change.xosc')), own);
    assert.equal(
      cacheFileFor(commandBundle(COMMAND_BUNDLES.flatten), ['flatten', path.join(examples, 'crossing.xosc')]),
      'cli-flatten.js' + CODE_CACHE_SUFFIX,
    );
  });

  it("the entry knows export's options that take a value, as export declares them (a word after one is no input)", () => {
    const takingValue = Object.entries(EXPORT_OPTIONS).flatMap(([name, option]) =>
      option.type === 'string' ? [`--${name}`, ...('short' in option ? [`-${option.short}`] : [])] : [],
    );
    assert.deepEqual([...EXPORT_VALUE_OPTIONS].sort(), takingValue.sort());
  });

  it('without the command bundles (the .vsix ships only the whole CLI) the same command gives the same output', () => {
    const shipped = temporaryFolder('m2s-start-');
    try {
      for (const file of ['cli.js', CLI_BUNDLE, CLI_BUNDLE + CODE_CACHE_SUFFIX, 'openscenario-schemas.json'])
        fs.copyFileSync(path.join(dist, file), path.join(shipped, file));
      assert.equal(bundleFor(shipped, ['flatten', 'x.mosc']), CLI_BUNDLE);
      const flatten = (entry: string, output: string) =>
        spawnSync(process.execPath, [entry, '-cmx', path.join(examples, 'braking.mosc'), path.join(shipped, output)], { encoding: 'utf8' });
      const own = flatten(path.join(dist, 'cli.js'), 'own.xosc');
      const whole = flatten(path.join(shipped, 'cli.js'), 'whole.xosc');
      assert.equal(own.status, 0, own.stderr);
      assert.equal(whole.status, 0, whole.stderr);
      assert.equal(whole.stderr.replace('whole.xosc', 'own.xosc'), own.stderr);
      assert.equal(fs.readFileSync(path.join(shipped, 'whole.xosc'), 'utf8'), fs.readFileSync(path.join(shipped, 'own.xosc'), 'utf8'));
    } finally {
      fs.rmSync(shipped, { recursive: true, force: true });
    }
  });

  it("a plain scenario's export starts none of the flattener's modules nor the semantic checks (their start-up is the export's)", async () => {
    // esbuild's module wrapper (__esm) in the export bundle, made to note each module it starts.
    const file = path.join(dist, commandBundle(COMMAND_BUNDLES.export));
    const source = fs.readFileSync(file, 'latin1');
    const wrapper = 'var __esm = (fn, res, err) => function __init() {';
    assert.ok(source.includes(wrapper), "the bundle has esbuild's module wrapper as this test expects");
    const started: string[] = [];
    const noted = source.replace(wrapper, `${wrapper} if (fn) __started.push(Object.keys(fn)[0]);`);
    const run = new Script(`(function (exports, require, module, __filename, __dirname, __started) { ${noted}\n})`).runInThisContext() as (
      ...args: unknown[]
    ) => void;
    const bundle = { exports: {} as CliEntry };
    run(bundle.exports, createRequire(file), bundle, file, dist, started);
    const out = temporaryFolder('m2s-start-export-');
    const quiet = { out: () => undefined, err: () => undefined };
    const exportOf = (input: string) =>
      bundle.exports.main(['export', input, '--target', 'carla', '--carla', '0.9.15', '-o', path.join(out, 'carla.xosc'), '-q'], quiet);
    assert.equal(await exportOf(path.join(examples, 'crossing.xosc')), 0);
    const unneeded = /^server\/src\/core\/(flatten\/(?!besideOutput\.ts)|semantics\/checks|semantics\/ranges|variations\/)/;
    assert.deepEqual(
      started.filter((module) => unneeded.test(module)),
      [],
    );
    // A modular main does start the flattener: the notes above would have seen it.
    assert.equal(await exportOf(path.join(examples, 'main.xosc')), 0);
    assert.ok(started.includes('server/src/core/flatten/flattener.ts'), started.join(', '));
  });

  it("the export bundle's plain cache is written after a plain export that reads a road and samples every shape", async () => {
    // A warm-up that failed would leave its code out of the cache silently: each of the build's export runs succeeds.
    const out = temporaryFolder('m2s-start-warm-up-');
    const runs = warmingRuns(examples, out).plainExport;
    const { exports: cli } = loadBundle(dist, require, undefined, commandBundle(COMMAND_BUNDLES.export));
    const messages: string[] = [];
    const io = { out: (text: string) => messages.push(text), err: (text: string) => messages.push(text) };
    for (const argv of runs) assert.equal(await cli.main(argv, io), 0, `${argv.join(' ')}: ${messages.join('\n')}`);
    const plain = fs.readFileSync(path.join(out, 'plain.xosc'), 'utf8');
    assert.match(plain, /<LogicFile filepath="[^"]*straight_1000m\.xodr"/);
    assert.equal(plain.match(/<Polyline>/g)?.length, 3, 'the Clothoid, the ClothoidSpline and the Nurbs sampled');
    assert.doesNotMatch(plain, /<CatalogReference/);
  });
});
