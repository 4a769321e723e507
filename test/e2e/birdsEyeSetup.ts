import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { repoRoot } from '../support/paths';

/** Where the bird's-eye tests find their scenario, road and run inside the e2e workspace. */
export const BIRDS_EYE_FILES = {
  scenario: 'birdsEye/cut_in.xosc',
  roadFolder: 'roads',
  csv: 'birdsEye/cut_in.csv',
  log: 'birdsEye/cut_in.log',
} as const;

/**
 * Puts the bird's-eye fixture into the workspace, with esmini's e6mini road in a folder that only the
 * road-path setting points at, and, when esmini is built, a run of it (CSV and log), as the runner would.
 */
export function prepareBirdsEye(workspace: string): void {
  const scenario = path.join(workspace, BIRDS_EYE_FILES.scenario);
  fs.mkdirSync(path.dirname(scenario), { recursive: true });
  fs.copyFileSync(path.join(repoRoot, 'test', 'fixtures', 'birdsEye', 'cut_in.xosc'), scenario);
  const xodrFolder = path.resolve(repoRoot, '..', 'shared', 'esmini', 'xodr');
  if (!fs.existsSync(path.join(xodrFolder, 'e6mini.xodr'))) return;
  fs.mkdirSync(path.join(workspace, BIRDS_EYE_FILES.roadFolder), { recursive: true });
  fs.copyFileSync(path.join(xodrFolder, 'e6mini.xodr'), path.join(workspace, BIRDS_EYE_FILES.roadFolder, 'e6mini.xodr'));
  const esmini = path.join(repoRoot, '.cache', 'esmini', 'bin', 'esmini');
  if (!fs.existsSync(esmini)) return;
  // The road folder of the workspace, as the view's roadPath: the run's log then names the file the view draws.
  const run = spawnSync(esmini, ['--headless', '--osc', scenario, '--fixed_timestep', '0.05', '--seed', '1', '--csv_logger', path.join(workspace, BIRDS_EYE_FILES.csv), '--disable_log', '--path', path.join(workspace, BIRDS_EYE_FILES.roadFolder)], {
    cwd: path.dirname(scenario),
    encoding: 'utf8',
    timeout: 60_000,
  });
  if (run.status !== 0) throw new Error(`esmini failed on the bird's-eye fixture (${run.status}):\n${run.stdout}\n${run.stderr}`);
  fs.writeFileSync(path.join(workspace, BIRDS_EYE_FILES.log), run.stdout);
}
