import * as fs from 'node:fs';
import * as path from 'node:path';
import { esminiBinDir, esminiXodrDir, requireEsminiProgram } from './esminiBinaries';
import { runBounded } from './processes';
import { Collision, collisionsIn, parseEsminiLog } from '../../server/src/esmini/log';

/** esmini as built by `bash ../shared/esmini/build.sh .cache/esmini`. */
export const esminiBinary = path.join(esminiBinDir, 'esmini');
export const esminiRoads = esminiXodrDir;
/** The catalogs that esmini's own scenarios use, shipped with its source package. */
export const esminiCatalogs = path.join(esminiXodrDir, '..', 'Catalogs');

/** Skips the calling test with a message when esmini is not built; fails instead with M2S_REQUIRE_ESMINI set. */
export function requireEsmini(context: Mocha.Context): void {
  requireEsminiProgram(context, 'esmini');
}

/** esmini's arguments for a headless run that repeats exactly (a fixed step of 0.05 s, seed 1), its steps logged to `csv`. */
export function repeatableRunArgs(scenario: string, csv: string, ...more: string[]): string[] {
  return ['--headless', '--osc', scenario, '--fixed_timestep', '0.05', '--seed', '1', '--csv_logger', csv, '--disable_log', ...more];
}

/** One step of a run: simulated time and each entity's world position. */
export interface EsminiStep {
  time: number;
  positions: Record<string, [number, number, number]>;
}

/**
 * Runs a scenario headless with a fixed step and seed (runs then repeat exactly) and returns the
 * steps up to `maxTime` seconds of simulated time. The scenario's StopTrigger should end it; a
 * wall-clock limit kills it otherwise.
 */
export async function runEsmini(scenario: string, maxTime: number, wallLimitMs = 60_000): Promise<EsminiStep[]> {
  const directory = path.dirname(scenario);
  const csv = path.join(directory, `${path.basename(scenario, '.xosc')}.esmini.csv`);
  fs.rmSync(csv, { force: true });
  const args = repeatableRunArgs(scenario, csv, '--path', esminiXodrDir);
  const { code, output } = await runBounded(esminiBinary, args, { cwd: directory }, wallLimitMs);
  if (code !== 0 || !fs.existsSync(csv)) throw new Error(`esmini failed on ${scenario} (exit ${code}):\n${output.slice(-2000)}`);
  const steps = readEsminiCsv(csv, maxTime);
  fs.rmSync(csv, { force: true });
  return steps;
}

/** The collisions esmini's global detection (`--collision`) logs in a headless run of the scenario (fixed step and seed), as each begins. */
export async function esminiCollisions(scenario: string, wallLimitMs = 60_000): Promise<Collision[]> {
  const directory = path.dirname(scenario);
  const csv = path.join(directory, `${path.basename(scenario, '.xosc')}.collisions.csv`);
  const args = repeatableRunArgs(scenario, csv, '--path', esminiXodrDir, '--collision');
  const { code, output } = await runBounded(esminiBinary, args, { cwd: directory }, wallLimitMs);
  fs.rmSync(csv, { force: true });
  if (code !== 0) throw new Error(`esmini failed on ${scenario} (exit ${code}):\n${output.slice(-2000)}`);
  return collisionsIn(parseEsminiLog(output));
}

/** The steps of esmini's CSV log (`--csv_logger`) up to `maxTime` seconds of simulated time. */
export function readEsminiCsv(csv: string, maxTime = Infinity): EsminiStep[] {
  const lines = fs
    .readFileSync(csv, 'utf8')
    .split(/\r?\n/)
    .slice(6)
    .filter((line) => line.trim());
  const header = lines[0].split(',').map((cell) => cell.trim());
  const entityColumns = header.flatMap((cell, index) => (/^#\d+ Entity_Name/.test(cell) ? [index] : []));
  const offsetOf = (name: string) =>
    header.findIndex((cell) => cell === `#1 ${name}`) - header.findIndex((cell) => cell === '#1 Entity_Name [-]');
  const [x, y, z] = ['World_Position_X [m]', 'World_Position_Y [m]', 'World_Position_Z [m]'].map(offsetOf);
  const steps: EsminiStep[] = [];
  for (const line of lines.slice(1)) {
    const cells = line.split(',').map((cell) => cell.trim());
    const time = Number(cells[1]);
    if (time > maxTime) break;
    const positions: EsminiStep['positions'] = {};
    for (const column of entityColumns)
      positions[cells[column]] = [Number(cells[column + x]), Number(cells[column + y]), Number(cells[column + z])];
    steps.push({ time, positions });
  }
  return steps;
}

/** Each entity's track (time and position) from the steps of a run. */
export function tracksOf(steps: EsminiStep[]): Map<string, { time: number; x: number; y: number }[]> {
  const tracks = new Map<string, { time: number; x: number; y: number }[]>();
  for (const step of steps) {
    for (const [name, [x, y]] of Object.entries(step.positions)) {
      if (!tracks.has(name)) tracks.set(name, []);
      tracks.get(name)?.push({ time: step.time, x, y });
    }
  }
  return tracks;
}
