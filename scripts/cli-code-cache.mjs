// V8's code cache for each of the CLI's bundles (read by server/src/cli/start.ts, the program's entry): a bundle
// is compiled and run here as the entry runs it, on the examples, so that its cache holds the functions its
// commands compile; a run then reads them instead of compiling them.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

/** @typedef {typeof import('../server/src/cli/start')} CliEntry dist/cli.js, the program's entry, built from it */

/**
 * A plain scenario on an .xodr road of the library, with catalog entries and the three shapes an export samples: a plain
 * export (most of them) runs code a modular main's does not, which would be compiled at each run without it.
 */
const EXPORT_WARM_UP = path.join(path.dirname(fileURLToPath(import.meta.url)), 'code-cache-warm-up', 'export.xosc');

/**
 * The command lines run on the examples before a bundle's cache is written, by command file of cli/ (`main`: the whole CLI).
 * @param {string} examples
 * @param {string} out
 * @returns {Record<string, string[][]>}
 */
export function warmingRuns(examples, out) {
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
    // The export bundle's second cache (PLAIN_EXPORT_CACHE_SUFFIX), for a plain scenario's export.
    plainExport: [['export', EXPORT_WARM_UP, '--target', 'carla', '--carla', '0.9.15', '-o', path.join(out, 'plain.xosc'), '-q']],
  };
}

/** The bundle files the program's entry may run (the whole CLI's and each short command's), each cache file and its runs. */
/** @param {CliEntry} entry */
function cliBundles(entry) {
  const exportBundle = entry.commandBundle(entry.COMMAND_BUNDLES.export);
  return [
    { file: entry.CLI_BUNDLE, cache: entry.CLI_BUNDLE + entry.CODE_CACHE_SUFFIX, runs: 'main' },
    ...[...new Set(Object.values(entry.COMMAND_BUNDLES))].map((file) => ({
      file: entry.commandBundle(file),
      cache: entry.commandBundle(file) + entry.CODE_CACHE_SUFFIX,
      runs: file,
    })),
    { file: exportBundle, cache: exportBundle + entry.PLAIN_EXPORT_CACHE_SUFFIX, runs: 'plainExport' },
  ];
}

/**
 * Writes the caches of `root`/dist, or only `only` (a cache file name). V8 keeps each script it compiled for the
 * same source, so a second cache of one bundle is written by a process of its own, or it would hold the first's.
 * @param {string} root
 * @param {string} [only]
 */
export async function writeCliCodeCache(root, only) {
  const dist = path.join(root, 'dist');
  const require = createRequire(path.join(dist, 'cli.js'));
  /** @type {CliEntry} */
  const entry = require('./cli.js');
  const examples = path.join(root, 'examples');
  const out = mkdtempSync(path.join(tmpdir(), 'm2s-code-cache-'));
  const quiet = { out: () => undefined, err: () => undefined };
  try {
    const runs = warmingRuns(examples, out);
    const written = new Set();
    for (const { file, cache, runs: name } of cliBundles(entry)) {
      if (only !== undefined && cache !== only) continue;
      if (only === undefined && written.has(file)) {
        const child = spawnSync(process.execPath, [fileURLToPath(import.meta.url), root, cache], { stdio: 'inherit' });
        if (child.status !== 0) throw new Error(`writing ${cache} failed (${child.status ?? child.signal})`);
        continue;
      }
      written.add(file);
      const { exports: cli, script } = entry.loadBundle(dist, require, undefined, file);
      if (existsSync(path.join(examples, 'braking.mosc'))) for (const argv of runs[name] ?? []) await cli.main(argv, quiet);
      writeFileSync(path.join(dist, cache), script.createCachedData());
    }
  } finally {
    rmSync(out, { recursive: true, force: true });
  }
}

// node scripts/cli-code-cache.mjs ROOT CACHE: one cache file (writeCliCodeCache's second cache of a bundle).
if (process.argv[1] === fileURLToPath(import.meta.url))
  writeCliCodeCache(process.argv[2], process.argv[3]).catch((error) => {
    console.error(error);
    process.exitCode = 1;
  });
