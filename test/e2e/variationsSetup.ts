import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { repoRoot } from '../support/paths';
import { STALL_MS } from './limits';

/** Where the Variations test finds its batch inside the e2e workspace. */
export const VARIATIONS_FILES = {
  folder: 'variations',
  results: 'variations/results',
} as const;

/**
 * Puts follow.xosc and its 36-scenario distribution into the workspace and, when esmini is built, runs the batch
 * as a person would (`batch d.xosc --results results --keep-runs`), with the road in the workspace's road folder.
 */
export function prepareVariations(workspace: string, roadFolder: string): void {
  const folder = path.join(workspace, VARIATIONS_FILES.folder);
  fs.mkdirSync(folder, { recursive: true });
  const fixtures = path.join(repoRoot, 'test', 'fixtures', 'variations');
  fs.copyFileSync(path.join(fixtures, 'follow.xosc'), path.join(folder, 'follow.xosc'));
  fs.copyFileSync(path.join(fixtures, 'follow_distribution.xosc'), path.join(folder, 'd.xosc'));
  const esmini = path.join(repoRoot, '.cache', 'esmini', 'bin', 'esmini');
  const cli = path.join(repoRoot, 'dist', 'cli.js');
  if (!fs.existsSync(esmini) || !fs.existsSync(path.join(workspace, roadFolder, 'e6mini.xodr'))) return;
  const run = spawnSync(
    process.execPath,
    [
      cli,
      'batch',
      'd.xosc',
      '--results',
      'results',
      '--jobs',
      '2',
      '--keep-runs',
      '--quiet',
      '--road-path',
      path.join(workspace, roadFolder),
      '--esmini',
      esmini,
    ],
    {
      cwd: folder,
      encoding: 'utf8',
      // 36 esmini runs two at a time: half a minute at a load of 20, more on a busier machine.
      timeout: STALL_MS,
    },
  );
  if (run.status !== 0) throw new Error(`the batch for the Variations test failed (${run.status}):\n${run.stdout}\n${run.stderr}`);
}
