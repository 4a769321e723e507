// One bundle per side, so that the extension, the server and the CLI each start from a single file.
import * as esbuild from 'esbuild';
import { chmodSync, mkdirSync, writeFileSync } from 'node:fs';
import { writeCliCodeCache } from './cli-code-cache.mjs';
import { schemaModelFile } from './compile-schemas.mjs';

const watch = process.argv.includes('--watch');
const common = {
  bundle: true,
  platform: 'node',
  target: 'node20',
  format: 'cjs',
  sourcemap: true,
  minify: process.argv.includes('--minify'),
  logLevel: 'warning',
};
const entries = [
  { entryPoints: ['client/src/extension.ts'], outfile: 'dist/client.js', external: ['vscode'] },
  { entryPoints: ['server/src/server.ts'], outfile: 'dist/server.js', banner: { js: '#!/usr/bin/env node' } },
  // The CLI: a small entry that runs the bundle from V8's code cache (server/src/cli/start.ts).
  { entryPoints: ['server/src/cli/start.ts'], outfile: 'dist/cli.js', banner: { js: '#!/usr/bin/env node' } },
  // The Redis queue's client (batch --queue, worker) is loaded from node_modules only when used: start-up stays small.
  { entryPoints: ['server/src/cli.ts'], outfile: 'dist/cli-main.js', external: ['bullmq', 'ioredis'] },
  // The bird's-eye view's page: runs in the webview, everything bundled (no network, no CDN).
  {
    entryPoints: ['client/src/birdsEye/webview/main.ts'],
    outfile: 'dist/birdsEye.js',
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
mkdirSync('dist', { recursive: true });
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
