// One bundle per side, so that the extension, the server and the CLI each start from a single file (the CLI: one per short command too).
import * as esbuild from 'esbuild';
import { chmodSync, mkdirSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { writeCliCodeCache } from './cli-code-cache.mjs';
import { schemaModelFile } from './compile-schemas.mjs';

const watch = process.argv.includes('--watch');
/** @type {esbuild.BuildOptions} */
const common = {
  bundle: true,
  platform: 'node',
  target: 'node20',
  format: 'cjs',
  sourcemap: true,
  minify: process.argv.includes('--minify'),
  logLevel: 'warning',
};

/**
 * A command's own bundle is cli.ts with only that file of cli/: cli.ts's lazy imports of the other
 * command files (and of help, which imports them) load a module that throws, as the program's entry
 * runs this bundle for that command alone (server/src/cli/start.ts, COMMAND_BUNDLES). What cli.ts
 * imports statically it always needs, and is bundled.
 * @param {string} commandFile
 * @returns {esbuild.Plugin}
 */
function onlyCommandFile(commandFile) {
  return {
    name: 'only-command-file',
    setup(build) {
      build.onResolve({ filter: /^\.\/cli\/\w+$/ }, (args) => {
        const file = args.path.slice('./cli/'.length);
        if (args.kind !== 'dynamic-import' || path.resolve(args.importer) !== path.resolve('server/src/cli.ts') || file === commandFile)
          return undefined;
        return { path: file, namespace: 'other-command' };
      });
      build.onLoad({ filter: /.*/, namespace: 'other-command' }, (args) => ({
        contents: `throw new Error(${JSON.stringify(`cli/${args.path} is not in the bundle of cli/${commandFile} (scripts/build.mjs)`)});`,
        loader: 'js',
      }));
    },
  };
}

/**
 * The CLI's bundles run in a vm.Script (server/src/cli/start.ts), which has no module loader for `import()`:
 * a lazily imported Node module (`await import('node:crypto')`) is required instead, when it is first used.
 * @type {esbuild.Plugin}
 */
const builtinsRequired = {
  name: 'builtins-required',
  setup(build) {
    build.onResolve({ filter: /^node:/ }, (args) =>
      args.kind === 'dynamic-import' ? { path: args.path, namespace: 'builtin-required' } : undefined,
    );
    build.onLoad({ filter: /.*/, namespace: 'builtin-required' }, (args) => ({
      contents: `module.exports = require(${JSON.stringify(args.path)});`,
      loader: 'js',
    }));
  },
};

/**
 * proj4js (core/opendrive/geo.ts, a GeoPosition's projection; 300 KB) is a bundle of its own, dist/proj4.js, required
 * only when an export meets a GeoPosition: in the CLI's bundles it would be read at every start. Its lazy
 * `import('proj4')` becomes a require of that file beside the bundle (the CLI's vm.Script has no `import()`).
 * @type {esbuild.Plugin}
 */
const proj4Beside = {
  name: 'proj4-beside',
  setup(build) {
    build.onResolve({ filter: /^proj4$/ }, (args) =>
      args.kind === 'dynamic-import' ? { path: 'proj4', namespace: 'proj4-beside' } : undefined,
    );
    build.onLoad({ filter: /.*/, namespace: 'proj4-beside' }, () => ({
      contents: 'module.exports = require("./proj4.js");',
      loader: 'js',
    }));
    build.onResolve({ filter: /^\.\/proj4\.js$/ }, (args) =>
      args.namespace === 'proj4-beside' ? { path: args.path, external: true } : undefined,
    );
  },
};

/**
 * The debug adapter's entry (dist/debugAdapter.js) requires the session (server/src/debugSession.ts) only in its child:
 * the session is a bundle of its own beside it, dist/debugSession.js, so that the supervising process neither reads
 * nor runs it.
 * @type {esbuild.Plugin}
 */
const debugSessionBeside = {
  name: 'debug-session-beside',
  setup(build) {
    build.onResolve({ filter: /^\.\/debugSession$/ }, (args) =>
      args.kind === 'require-call' ? { path: './debugSession.js', external: true } : undefined,
    );
  },
};

/**
 * `import * as fs from 'node:fs'` in each of N files is, bundled, N copies of fs's hundred properties as
 * getters (esbuild's __toESM) at every start; through one module that re-exports the built-in they are
 * made once. For the CLI's bundles, whose start-up is most of a short run.
 * @type {esbuild.Plugin}
 */
const sharedBuiltinNamespaces = {
  name: 'shared-builtin-namespaces',
  setup(build) {
    build.onResolve({ filter: /^node:(fs|path)$/ }, (args) =>
      args.kind === 'import-statement' && args.namespace === 'file' ? { path: args.path, namespace: 'shared-builtin' } : undefined,
    );
    build.onLoad({ filter: /.*/, namespace: 'shared-builtin' }, (args) => ({
      // No default export: a default import of these (none today) fails the build rather than being undefined.
      contents: `export * from ${JSON.stringify(args.path)};\n`,
      loader: 'js',
    }));
  },
};

// The CLI's entry: a small file that runs a bundle from V8's code cache (server/src/cli/start.ts); built first, as it names the command bundles.
const starter = { entryPoints: ['server/src/cli/start.ts'], outfile: 'dist/cli.js', banner: { js: '#!/usr/bin/env node' } };
mkdirSync('dist', { recursive: true });
await esbuild.build({ ...common, ...starter });
const { COMMAND_BUNDLES, commandBundle } = createRequire(import.meta.url)(path.resolve('dist/cli.js'));
const commandFiles = [...new Set(Object.values(COMMAND_BUNDLES))];

/** @type {esbuild.BuildOptions[]} */
const entries = [
  { entryPoints: ['client/src/extension.ts'], outfile: 'dist/client.js', external: ['vscode'] },
  { entryPoints: ['server/src/server.ts'], outfile: 'dist/server.js', banner: { js: '#!/usr/bin/env node' }, plugins: [proj4Beside] },
  // proj4js on its own, required by the bundles above and below when a GeoPosition is exported (proj4Beside).
  { entryPoints: ['proj4'], outfile: 'dist/proj4.js', minify: true },
  // The debug adapter, a process of its own (esmini crashing ends it, not the editor), and the session its child runs
  // (dist/debugSession.js, required by the first only in the child); koffi is native, loaded from node_modules.
  { entryPoints: ['server/src/debugAdapter.ts'], outfile: 'dist/debugAdapter.js', external: ['koffi'], plugins: [debugSessionBeside] },
  // The session may run in a vm.Script (server/src/debug/codeCache.ts), which has no import(): builtinsRequired.
  { entryPoints: ['server/src/debugSession.ts'], outfile: 'dist/debugSession.js', external: ['koffi'], plugins: [builtinsRequired] },
  starter,
  // The whole CLI. The Redis queue's client (batch --queue, worker) is loaded from node_modules only when used: start-up stays small.
  {
    entryPoints: ['server/src/cli.ts'],
    outfile: 'dist/cli-main.js',
    external: ['bullmq', 'ioredis', 'koffi'],
    plugins: [builtinsRequired, sharedBuiltinNamespaces, proj4Beside],
  },
  // The short commands' own bundles.
  ...commandFiles.map((file) => ({
    entryPoints: ['server/src/cli.ts'],
    outfile: `dist/${commandBundle(file)}`,
    external: ['bullmq', 'ioredis', 'koffi'],
    plugins: [onlyCommandFile(file), builtinsRequired, sharedBuiltinNamespaces, proj4Beside],
  })),
  // The bird's-eye view's page: runs in the webview, everything bundled (no network, no CDN).
  {
    entryPoints: ['client/src/birdsEye/webview/main.ts'],
    outfile: 'dist/birdsEye.js',
    platform: 'browser',
    format: 'iife',
    target: 'es2022',
  },
  // The storyboard timeline's page, likewise.
  {
    entryPoints: ['client/src/timeline/webview/main.ts'],
    outfile: 'dist/timeline.js',
    platform: 'browser',
    format: 'iife',
    target: 'es2022',
  },
  // The Variations view's page (batch results: table and scatter), likewise.
  {
    entryPoints: ['client/src/variations/webview/main.ts'],
    outfile: 'dist/variations.js',
    platform: 'browser',
    format: 'iife',
    target: 'es2022',
  },
];
// The OpenSCENARIO schemas are compiled once here, so that nothing interprets XSD at run time.
writeFileSync('dist/openscenario-schemas.json', schemaModelFile());
const contexts = await Promise.all(entries.map((entry) => esbuild.context({ ...common, ...entry })));
if (watch) {
  await Promise.all(contexts.map((context) => context.watch()));
} else {
  await Promise.all(contexts.map((context) => context.rebuild()));
  await Promise.all(contexts.map((context) => context.dispose()));
  chmodSync('dist/server.js', 0o755);
  chmodSync('dist/cli.js', 0o755);
  await writeCliCodeCache(process.cwd());
}
