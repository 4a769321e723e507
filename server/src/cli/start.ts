import * as fs from 'node:fs';
import Module from 'node:module';
import * as path from 'node:path';
import * as vm from 'node:vm';
import type * as Cli from '../cli';

/**
 * The program's entry (dist/cli.js): it runs the CLI's bundle (dist/cli-main.js) from V8's code cache,
 * which `npm run build` writes beside it after a flatten, a pack and a check (scripts/cli-code-cache.mjs).
 * Compiling the bundle and the functions a command calls is most of a short run's start-up; with the
 * cache V8 reads them back. A cache that does not fit (another Node) is rejected by V8 and the bundle
 * is compiled as usual.
 */

/** The bundle and its code cache, as the build writes them and this entry reads them. */
export const CLI_BUNDLE = 'cli-main.js';
export const CLI_CODE_CACHE = 'cli-main.js.cache';

export interface LoadedBundle {
  exports: Pick<typeof Cli, 'main' | 'runFromCommandLine'>;
  script: vm.Script;
}

/** Compiles and runs the bundle as Node's CommonJS loader would, with the code cache when there is one. */
export function loadBundle(folder: string, requireFn: NodeJS.Require, cachedData: Buffer | undefined): LoadedBundle {
  const filename = path.join(folder, CLI_BUNDLE);
  const script = new vm.Script(Module.wrap(fs.readFileSync(filename, 'utf8')), { filename, cachedData });
  const bundle = { exports: {} as LoadedBundle['exports'], filename, id: filename, loaded: false };
  const run = script.runInThisContext() as (
    exports: unknown,
    require: NodeJS.Require,
    module: unknown,
    filename: string,
    dirname: string,
  ) => void;
  run.call(bundle.exports, bundle.exports, requireFn, bundle, filename, folder);
  return { exports: bundle.exports, script };
}

function readCache(folder: string): Buffer | undefined {
  try {
    const cache = path.join(folder, CLI_CODE_CACHE);
    // V8 checks a cache against its source by length alone: a bundle rebuilt after its cache (watch mode) is compiled as usual.
    if (fs.statSync(cache).mtimeMs < fs.statSync(path.join(folder, CLI_BUNDLE)).mtimeMs) return undefined;
    return fs.readFileSync(cache);
  } catch {
    // No cache (a build without it): the bundle is compiled as usual.
    return undefined;
  }
}

if (require.main === module) loadBundle(__dirname, require, readCache(__dirname)).exports.runFromCommandLine();
