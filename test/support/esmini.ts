import * as fs from 'node:fs';
import * as path from 'node:path';
import { repoRoot, sharedDir } from './fixtures';

/** Where the test setup (scripts/test-all.sh) builds esmini from ../shared/esmini. */
export const esminiProgram = path.join(repoRoot, '.cache', 'esmini', 'bin', 'esmini');
/** The road files (and CARLA's Town05) shipped with the esmini source package. */
export const sharedRoads = path.join(sharedDir, 'esmini', 'xodr');
export const sharedCatalogs = path.join(sharedDir, 'esmini', 'Catalogs');

/**
 * Skips the calling test, with a message, when esmini or its road files are absent; fails instead
 * when M2S_REQUIRE_ESMINI is set (CI), so that the simulator tests cannot be skipped silently there.
 */
export function requireEsmini(context: Mocha.Context): void {
  const missing = [esminiProgram, sharedRoads].filter((item) => !fs.existsSync(item));
  if (missing.length === 0) return;
  const message = `${missing.join(' and ')} ${missing.length === 1 ? 'is' : 'are'} absent (build esmini with: bash ../shared/esmini/build.sh .cache/esmini)`;
  if (process.env.M2S_REQUIRE_ESMINI) throw new Error(`M2S_REQUIRE_ESMINI is set, but ${message}`);
  console.log(`    (skipped: ${message})`);
  context.skip();
}

export interface CsvTrack {
  time: number;
  x: number;
  y: number;
}

/** Each entity's positions from esmini's CSV: 31 columns per entity, name first, X and Y at 11 and 12. */
export function readTracks(csvFile: string): Map<string, CsvTrack[]> {
  const lines = fs.readFileSync(csvFile, 'utf8').split('\n');
  const columns = lines.findIndex((line) => line.startsWith('Index [-]'));
  const tracks = new Map<string, CsvTrack[]>();
  for (const line of lines.slice(columns + 1)) {
    const cells = line.split(',').map((cell) => cell.trim());
    if (cells.length < 33) continue;
    const time = Number(cells[1]);
    for (let first = 2; first + 30 < cells.length; first += 31) {
      const name = cells[first];
      if (!tracks.has(name)) tracks.set(name, []);
      tracks.get(name)?.push({ time, x: Number(cells[first + 11]), y: Number(cells[first + 12]) });
    }
  }
  return tracks;
}
