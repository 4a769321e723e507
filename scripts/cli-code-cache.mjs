// V8's code cache for each of the CLI's bundles (read by server/src/cli/start.ts, the program's entry): a bundle
// is compiled and run here as the entry runs it, on the examples, so that its cache holds the functions its
// commands compile; a run then reads them instead of compiling them.
import { existsSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import path from 'node:path';

/** @typedef {typeof import('../server/src/cli/start')} CliEntry dist/cli.js, the program's entry, built from it */

/** The command lines run on the examples before a bundle's cache is written, by command file of cli/ (`main`: the whole CLI). */
/**
 * @param {string} examples
 * @param {string} out
 * @returns {Record<string, string[][]>}
 */
function warmingRuns(examples, out) {
  const flatten = [
    ['-cmx', path.join(examples, 'braking.mosc'), path.join(out, 'braking.xosc'), '-q'],
    ['flatten', path.join(examples, 'main.xosc'), '-o', path.join(out, 'main.xosc'), '-q'],
  ];
  const pack = [['pack', path.join(examples, 'pedestrian'), '-o', path.join(out, 'pedestrian.mosc'), '-q']];
  const check = [['check', examples, '-q']];
  return {
    main: [...flatten, ...pack, ...check],
    flatten,
    pack,
    check,
    stats: [['stats', examples]],
    // --check writes nothing.
    format: [['format', '--check', examples, '-q']],
    export: [
      ['export', path.join(examples, 'main.xosc'), '--target', 'carla', '--carla', '0.9.15', '-o', path.join(out, 'carla.xosc'), '-q'],
    ],
  };
}

/** The bundle files the program's entry may run: the whole CLI's and each short command's. */
/** @param {CliEntry} entry */
function cliBundles(entry) {
  return [
    { file: entry.CLI_BUNDLE, runs: 'main' },
    ...[...new Set(Object.values(entry.COMMAND_BUNDLES))].map((file) => ({ file: entry.commandBundle(file), runs: file })),
  ];
}

/** @param {string} root */
export async function writeCliCodeCache(root) {
  const dist = path.join(root, 'dist');
  const require = createRequire(path.join(dist, 'cli.js'));
  /** @type {CliEntry} */
  const entry = require('./cli.js');
  const examples = path.join(root, 'examples');
  const out = mkdtempSync(path.join(tmpdir(), 'm2s-code-cache-'));
  const quiet = { out: () => undefined, err: () => undefined };
  try {
    const runs = warmingRuns(examples, out);
    for (const { file, runs: name } of cliBundles(entry)) {
      const { exports: cli, script } = entry.loadBundle(dist, require, undefined, file);
      if (existsSync(path.join(examples, 'braking.mosc'))) for (const argv of runs[name] ?? []) await cli.main(argv, quiet);
      writeFileSync(path.join(dist, file + entry.CODE_CACHE_SUFFIX), script.createCachedData());
    }
  } finally {
    rmSync(out, { recursive: true, force: true });
  }
}
