#!/usr/bin/env node
// `npm run package [-- --out FILE.vsix]`: the minified bundles and the manifest's assets in a .vsix.
// Everything runs from the bundles but koffi (copied into dist/node_modules below), so no node_modules go in
// (--no-dependencies); .vscodeignore lists what does.
import { spawnSync } from 'node:child_process';
import { cpSync, readdirSync, rmSync, statSync } from 'node:fs';
import * as path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const outIndex = process.argv.indexOf('--out');
const out = path.resolve(outIndex > 0 ? process.argv[outIndex + 1] : path.join(root, 'modular2simple.vsix'));

/** @param {string[]} args */
function run(args) {
  const result = spawnSync(process.execPath, args, { cwd: root, stdio: 'inherit' });
  if (result.status !== 0) process.exit(result.status ?? 1);
}

run([path.join(root, 'scripts', 'build.mjs'), '--minify']);

// The debug adapter calls esmini's library through koffi, a native module no bundle can hold: its JavaScript and the
// platform's binary package go beside the bundles, where dist/debugSession.js's require('koffi') finds them.
const shipped = path.join(root, 'dist', 'node_modules');
rmSync(shipped, { recursive: true, force: true });
const keep = /\.(c?js|json|node|txt|md)$/;
cpSync(path.join(root, 'node_modules', 'koffi'), path.join(shipped, 'koffi'), {
  recursive: true,
  filter: (source) => !/[\\/](doc|vendor)$/.test(source) && (statSync(source).isDirectory() || keep.test(source)),
});
for (const name of readdirSync(path.join(root, 'node_modules', '@koromix')).filter((entry) => entry.startsWith('koffi-')))
  cpSync(path.join(root, 'node_modules', '@koromix', name), path.join(shipped, '@koromix', name), { recursive: true });
run([
  path.join(root, 'node_modules', '@vscode', 'vsce', 'vsce'),
  'package',
  '--no-dependencies',
  '--allow-missing-repository',
  '--skip-license',
  // The extension's page is a README for its users; the repository's README.md is for people working on the code.
  '--readme-path',
  'docs/marketplace/README.md',
  // A README that links to files of this repository would point nowhere: there is no public address to rewrite them to.
  '--no-rewrite-relative-links',
  '--out',
  out,
]);
