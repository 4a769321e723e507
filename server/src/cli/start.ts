// Named imports: a bundled namespace import copies every export of the module (fs has a hundred) at each start.
import { existsSync, readFileSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { LoadedBundle, loadModuleBundle } from '../bundleLoader';
import type { CliOutput } from './common';

/**
 * The program's entry (dist/cli.js): it runs one of the CLI's bundles from V8's code cache, which
 * `npm run build` writes beside each bundle after running its commands (scripts/cli-code-cache.mjs).
 * A short command (a flatten, a pack, a check) runs a bundle of its own that holds only its code, so
 * that reading, deserializing and evaluating the code of the other commands is not paid at each start;
 * every other command line (help, run, batch, a wrong command) runs the whole CLI (dist/cli-main.js).
 * Compiling the bundle and the functions a command calls is most of a short run's start-up; with the
 * cache V8 reads them back. A cache that does not fit (another Node) is rejected by V8 and the bundle
 * is compiled as usual.
 */

/** The whole CLI's bundle; a bundle's code cache is its name followed by CODE_CACHE_SUFFIX. */
export const CLI_BUNDLE = 'cli-main.js';
export const CODE_CACHE_SUFFIX = '.cache';

/**
 * The commands that have a bundle of their own (`cli-<file>.js`, built by scripts/build.mjs from
 * cli.ts with only that file of cli/), by the name the command line gives. A command not listed runs
 * the whole CLI, so a command added to cli.ts alone works, only without the faster start.
 */
export const COMMAND_BUNDLES: Readonly<Record<string, string>> = {
  flatten: 'flatten',
  '-cmx': 'flatten',
  '--convert-mosc-to-xosc': 'flatten',
  pack: 'pack',
  '-cxm': 'pack',
  '--convert-xosc-into-mosc': 'pack',
  check: 'check',
  stats: 'stats',
  format: 'format',
  export: 'export',
};

/** The bundle file of a command file of cli/ (a value of COMMAND_BUNDLES). */
export function commandBundle(commandFile: string): string {
  return `cli-${commandFile}.js`;
}

/** What a bundle of cli.ts exports to this entry: declared here, as cli.ts sits above cli/ (cli.ts imports this folder). */
export interface CliEntry {
  main(argv: string[], io: CliOutput): Promise<number>;
  runFromCommandLine(): void;
}

/** Compiles and runs a bundle of the CLI, with the code cache when there is one. */
export function loadBundle(
  folder: string,
  requireFn: NodeJS.Require,
  cachedData: Buffer | undefined,
  bundleFile: string = CLI_BUNDLE,
): LoadedBundle<CliEntry> {
  return loadModuleBundle<CliEntry>(folder, requireFn, cachedData, bundleFile);
}

function readCache(folder: string, bundleFile: string, cacheFile: string = bundleFile + CODE_CACHE_SUFFIX): Buffer | undefined {
  try {
    const cache = join(folder, cacheFile);
    // V8 checks a cache against its source by length alone: a bundle rebuilt after its cache (watch mode) is compiled as usual.
    if (statSync(cache).mtimeMs < statSync(join(folder, bundleFile)).mtimeMs) return undefined;
    return readFileSync(cache);
  } catch {
    // No cache (a build without it): the bundle is compiled as usual.
    return undefined;
  }
}

/** The bundle a command line runs: its command's own when the build wrote one (the .vsix ships only the whole CLI). */
export function bundleFor(folder: string, argv: readonly string[]): string {
  const name = argv[0];
  if (name === undefined || !Object.hasOwn(COMMAND_BUNDLES, name)) return CLI_BUNDLE;
  const own = commandBundle(COMMAND_BUNDLES[name]);
  return existsSync(join(folder, own)) ? own : CLI_BUNDLE;
}

/**
 * The export bundle's second code cache, written after a plain scenario's export alone: V8 reads every function of a
 * cache at each start, and a plain export (most of them) needs none of the flattener's, which the first holds for a
 * modular main's export.
 */
export const PLAIN_EXPORT_CACHE_SUFFIX = '.plain' + CODE_CACHE_SUFFIX;

/** Export's options that take a value (those of cli/export.ts EXPORT_OPTIONS, not imported here: the entry loads no command): the word after them is no input. */
export const EXPORT_VALUE_OPTIONS: ReadonlySet<string> = new Set([
  '--target',
  '-o',
  '--output',
  '--report',
  '--carla',
  '--blueprints',
  '--road',
  '--road-path',
  '--ego',
  '--index',
  '--scenario-path',
]);

/**
 * The code cache file of a command line's bundle: for an export of a plain .xosc (no ScenarioReference, no
 * distribution), the cache without the flattener. A wrong guess costs time only: any cache of the bundle runs it.
 */
export function cacheFileFor(bundleFile: string, argv: readonly string[]): string {
  const own = bundleFile + CODE_CACHE_SUFFIX;
  if (bundleFile !== commandBundle(COMMAND_BUNDLES.export)) return own;
  const inputs = argv.slice(1).filter((arg, index, args) => !arg.startsWith('-') && !EXPORT_VALUE_OPTIONS.has(args[index - 1]));
  if (inputs.length !== 1 || !inputs[0].toLowerCase().endsWith('.xosc')) return own;
  try {
    const text = readFileSync(inputs[0], 'latin1');
    // Not a regular expression: the first one a process runs costs it about a megabyte.
    return text.includes('<ScenarioReference') || text.includes('<ParameterValueDistribution')
      ? own
      : bundleFile + PLAIN_EXPORT_CACHE_SUFFIX;
  } catch {
    // Unreadable: the export says why, with either cache.
    return own;
  }
}

/**
 * V8 optimizes a function after a fixed amount of its bytecode has run; in a run of a few hundred
 * milliseconds most of that optimizing (on another thread) is never paid back: a 31-file flatten spent a
 * fifth of its CPU time on it. A command's own bundle waits eight times longer before optimizing, which
 * a long run hardly notices. Set after the bundle is compiled: V8 checks a code cache against the flags.
 */
export const INTERRUPT_BUDGET_FLAG = '--interrupt-budget=540672';

if (require.main === module) {
  const bundleFile = bundleFor(__dirname, process.argv.slice(2));
  const cacheFile = cacheFileFor(bundleFile, process.argv.slice(2));
  // A build without the second cache: the bundle's own.
  const cache = readCache(__dirname, bundleFile, cacheFile) ?? readCache(__dirname, bundleFile);
  const { exports } = loadBundle(__dirname, require, cache, bundleFile);
  if (bundleFile !== CLI_BUNDLE) (require('node:v8') as typeof import('node:v8')).setFlagsFromString(INTERRUPT_BUDGET_FLAG);
  exports.runFromCommandLine();
}
