import { isAscii } from 'node:buffer';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { Script } from 'node:vm';

// Runs a bundle of dist/ in a vm.Script, as Node's CommonJS loader would, so that it can be given V8's code cache: the
// CLI's entry (cli/start.ts) and the debug adapter's session (debug/codeCache.ts). No side effects: both entries import it.

export interface LoadedBundle<Exports> {
  exports: Exports;
  script: Script;
}

/**
 * A bundle's text. An ASCII bundle (esbuild escapes what is not, but in comments) is read as Latin-1, the
 * same characters without UTF-8 decoding, which was a noticeable part of a short run's start-up.
 */
function bundleSource(bytes: Buffer): string {
  return typeof isAscii === 'function' && isAscii(bytes) ? bytes.toString('latin1') : bytes.toString('utf8');
}

/** Module.wrap's text, written out: loading node:module for it cost a quarter of a millisecond at each start. */
function wrapAsModule(source: string): string {
  return '(function (exports, require, module, __filename, __dirname) { ' + source + '\n});';
}

/** Compiles and runs a bundle as Node's CommonJS loader would, with the code cache when there is one. */
export function loadModuleBundle<Exports>(
  folder: string,
  requireFn: NodeJS.Require,
  cachedData: Buffer | undefined,
  bundleFile: string,
): LoadedBundle<Exports> {
  const filename = join(folder, bundleFile);
  const script = new Script(wrapAsModule(bundleSource(readFileSync(filename))), { filename, cachedData });
  const bundle = { exports: {} as Exports, filename, id: filename, loaded: false };
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
