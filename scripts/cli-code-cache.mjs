// V8's code cache for the CLI's bundle (read by server/src/cli/start.ts, the program's entry): the bundle is
// compiled and run here as the entry runs it, on the examples, so that the cache holds the functions a
// flatten, a pack and a check compile; a run then reads them instead of compiling them.
import { existsSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import path from 'node:path';

export async function writeCliCodeCache(root) {
  const dist = path.join(root, 'dist');
  const require = createRequire(path.join(dist, 'cli.js'));
  const entry = require('./cli.js');
  const { exports: cli, script } = entry.loadBundle(dist, require, undefined);
  const examples = path.join(root, 'examples');
  if (existsSync(path.join(examples, 'braking.mosc'))) {
    const out = mkdtempSync(path.join(tmpdir(), 'm2s-code-cache-'));
    const quiet = { out: () => undefined, err: () => undefined };
    try {
      await cli.main(['-cmx', path.join(examples, 'braking.mosc'), path.join(out, 'braking.xosc'), '-q'], quiet);
      await cli.main(['flatten', path.join(examples, 'main.xosc'), '-o', path.join(out, 'main.xosc'), '-q'], quiet);
      await cli.main(['pack', path.join(examples, 'pedestrian'), '-o', path.join(out, 'pedestrian.mosc'), '-q'], quiet);
      await cli.main(['check', examples, '-q'], quiet);
    } finally {
      rmSync(out, { recursive: true, force: true });
    }
  }
  writeFileSync(path.join(dist, entry.CLI_CODE_CACHE), script.createCachedData());
}
