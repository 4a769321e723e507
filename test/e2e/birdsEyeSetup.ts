import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { repoRoot } from '../support/paths';
import { STALL_MS } from './limits';

/** Where the bird's-eye tests find their scenario, road and run inside the e2e workspace. */
export const BIRDS_EYE_FILES = {
  scenario: 'birdsEye/cut_in.xosc',
  roadFolder: 'roads',
  csv: 'birdsEye/cut_in.csv',
  log: 'birdsEye/cut_in.log',
} as const;

/**
 * esmini's highway_merge.xosc (six cars merging onto a highway) as the corpus has it, beside the road and
 * catalog folders it names, and a second concrete scenario of it (A1 faster, a shorter gap) to compare.
 */
export const HIGHWAY_MERGE_FILES = {
  scenario: 'birdsEye/esmini/highway_merge.xosc',
  variant: 'birdsEye/esmini/highway_merge_fast.xosc',
  csv: 'birdsEye/esmini/highway_merge.csv',
  log: 'birdsEye/esmini/highway_merge.log',
  variantCsv: 'birdsEye/esmini/highway_merge_fast.csv',
  variantLog: 'birdsEye/esmini/highway_merge_fast.log',
} as const;

/**
 * Puts the bird's-eye fixture into the workspace, with esmini's e6mini road in a folder that only the
 * road-path setting points at, and, when esmini is built, a run of it (CSV and log), as the runner would.
 * `step` hears of each esmini run done, as the harness's progress: each run may take up to STALL_MS on a loaded machine.
 */
export function prepareBirdsEye(workspace: string, step: (what: string) => void = () => undefined): void {
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
  const run = spawnSync(
    esmini,
    [
      '--headless',
      '--osc',
      scenario,
      '--fixed_timestep',
      '0.05',
      '--seed',
      '1',
      '--csv_logger',
      path.join(workspace, BIRDS_EYE_FILES.csv),
      '--disable_log',
      '--path',
      path.join(workspace, BIRDS_EYE_FILES.roadFolder),
    ],
    {
      cwd: path.dirname(scenario),
      encoding: 'utf8',
      timeout: STALL_MS,
    },
  );
  if (run.status !== 0) throw new Error(`esmini failed on the bird's-eye fixture (${run.status}):\n${run.stdout}\n${run.stderr}`);
  fs.writeFileSync(path.join(workspace, BIRDS_EYE_FILES.log), run.stdout);
  step(`running esmini on ${BIRDS_EYE_FILES.scenario}`);
  prepareHighwayMerge(workspace, esmini, xodrFolder, step);
}

function prepareHighwayMerge(workspace: string, esmini: string, xodrFolder: string, step: (what: string) => void): void {
  const original = path.resolve(repoRoot, '..', 'shared', 'corpus', 'openscenario', 'esmini', 'highway_merge.xosc');
  const catalog = path.resolve(repoRoot, '..', 'shared', 'esmini', 'Catalogs', 'Vehicles', 'VehicleCatalog.xosc');
  if (![original, catalog, path.join(xodrFolder, 'soderleden.xodr')].every((file) => fs.existsSync(file))) return;
  const folder = path.join(workspace, path.dirname(HIGHWAY_MERGE_FILES.scenario));
  // Where the scenario looks: ../xodr/soderleden.xodr and ../xosc/Catalogs/Vehicles.
  fs.mkdirSync(folder, { recursive: true });
  fs.mkdirSync(path.join(folder, '..', 'xodr'), { recursive: true });
  fs.mkdirSync(path.join(folder, '..', 'xosc', 'Catalogs', 'Vehicles'), { recursive: true });
  fs.copyFileSync(path.join(xodrFolder, 'soderleden.xodr'), path.join(folder, '..', 'xodr', 'soderleden.xodr'));
  fs.copyFileSync(catalog, path.join(folder, '..', 'xosc', 'Catalogs', 'Vehicles', 'VehicleCatalog.xosc'));
  const text = fs.readFileSync(original, 'utf8');
  fs.writeFileSync(path.join(workspace, HIGHWAY_MERGE_FILES.scenario), text);
  const variant = text
    .replace('name="A1_speed" parameterType="double" value="25"', 'name="A1_speed" parameterType="double" value="32"')
    .replace('name="Gap1_time" parameterType="double" value="2.5"', 'name="Gap1_time" parameterType="double" value="1.2"');
  if (variant === text)
    throw new Error('highway_merge.xosc no longer declares A1_speed 25 and Gap1_time 2.5: the compared variant needs another change');
  fs.writeFileSync(path.join(workspace, HIGHWAY_MERGE_FILES.variant), variant);
  for (const [scenario, csv, log] of [
    [HIGHWAY_MERGE_FILES.scenario, HIGHWAY_MERGE_FILES.csv, HIGHWAY_MERGE_FILES.log],
    [HIGHWAY_MERGE_FILES.variant, HIGHWAY_MERGE_FILES.variantCsv, HIGHWAY_MERGE_FILES.variantLog],
  ]) {
    const run = spawnSync(
      esmini,
      [
        '--headless',
        '--osc',
        path.join(workspace, scenario),
        '--fixed_timestep',
        '0.05',
        '--seed',
        '1',
        '--csv_logger',
        path.join(workspace, csv),
        '--disable_log',
      ],
      { cwd: folder, encoding: 'utf8', timeout: STALL_MS },
    );
    if (run.status !== 0) throw new Error(`esmini failed on ${scenario} (${run.status}):\n${run.stdout}\n${run.stderr}`);
    fs.writeFileSync(path.join(workspace, log), run.stdout);
    step(`running esmini on ${scenario}`);
  }
}
