import * as fs from 'node:fs';
import * as path from 'node:path';
import { EsminiRun, parseEsminiCsv, parseEsminiLoadedRoad } from '../../../common/src/esminiCsv';
import type { TraceRecord } from '../../../common/src/trace';
import { collisionNote, RunCollision } from '../../../common/src/collisions';
import type { RunTracks } from './messages';

/** The view draws at most this many frames of a run; longer runs are evenly thinned. */
const MAX_FRAMES = 6000;
/** A CSV larger than this is not read whole (esmini writes some 70 MB per simulated second when unbounded). */
const MAX_CSV_BYTES = 256 * 1024 * 1024;

/**
 * A file of a batch's kept run (RESULTS/runs/I/, variations/panel.ts keptRun) named as the Variations view lists the run,
 * `#I of RESULTS`: each of them is a trajectories.csv beside a scenario.xosc, which says nothing of which run it is.
 */
export function keptRunName(file: string): string | undefined {
  const runFolder = path.dirname(file);
  const runs = path.dirname(runFolder);
  if (path.basename(runs) !== 'runs' || !/^\d+$/.test(path.basename(runFolder))) return undefined;
  return `#${path.basename(runFolder)} of ${path.basename(path.dirname(runs))}`;
}

export interface RunSource {
  csvPath: string;
  /** esmini's log (its stdout or log.txt), for when storyboard events started. */
  logPath?: string;
  logText?: string;
  /** The run's storyboard trace when known (Run in esmini reads it from the log); else it is read from the log. */
  trace?: TraceRecord[];
  /**
   * The road the run loaded as the view names it, where the runner knows better than the log: Run in esmini on a road packed
   * in the scenario's .mosc names the package entry (`/w/pkg.mosc/road.xodr`), whose copy esmini loaded from the run's folder.
   */
  roadFile?: string;
  /** How the view names the run, where its file's name says nothing (Run in esmini's trajectories.csv in a temporary folder). */
  label?: string;
  /** The run's time limit, s: rows after it (esmini logs one more step) are left out. */
  until?: number;
  /** Where two entities began to collide, as the run that made the CSV said (Run in esmini); a CSV alone says nothing of it. */
  collisions?: RunCollision[];
}

/** A run read: what the view draws (its event starts still empty) and esmini's log of it, when found. */
export interface LoadedRun {
  tracks: RunTracks;
  log?: string;
}

const round = (value: number) => Math.round(value * 100) / 100;

/** The run as the view needs it: thinned to MAX_FRAMES, rounded to centimetres; `starts` by element path (eventList.ts). */
export function runTracks(
  run: EsminiRun,
  label: string,
  starts: Record<string, number> = {},
  collisions: readonly RunCollision[] = [],
): RunTracks {
  const every = Math.max(1, Math.ceil(run.times.length / MAX_FRAMES));
  const indices: number[] = [];
  for (let i = 0; i < run.times.length; i += every) indices.push(i);
  if (run.times.length > 0 && indices[indices.length - 1] !== run.times.length - 1) indices.push(run.times.length - 1);
  const notes: string[] = [];
  if (run.truncated) notes.push('the run is longer than the view reads; its end is left out');
  if (every > 1) notes.push(`every ${every}th of ${run.times.length} steps is drawn`);
  for (const collision of collisions) notes.push(collisionNote(collision));
  return {
    label,
    times: indices.map((i) => run.times[i]),
    entities: run.entities.map((track) => ({
      name: track.name,
      length: track.length,
      width: track.width,
      centerX: track.centerX,
      x: indices.map((i) => round(track.x[i])),
      y: indices.map((i) => round(track.y[i])),
      hdg: indices.map((i) => Math.round(track.hdg[i] * 1000) / 1000),
      ...(track.speed.some(Number.isFinite) ? { speed: indices.map((i) => round(track.speed[i])) } : {}),
    })),
    starts,
    notes,
  };
}

/**
 * Reads an esmini CSV into what the view draws, and its log (given, or found beside the CSV): the road file it
 * loaded, and the text the event starts are read from (by the language server, which knows the flattened elements).
 */
export async function loadRun(source: RunSource): Promise<LoadedRun> {
  const stat = await fs.promises.stat(source.csvPath);
  if (stat.size > MAX_CSV_BYTES)
    throw new Error(
      `${source.csvPath} is ${Math.round(stat.size / 1024 / 1024)} MB; the view reads runs up to ${MAX_CSV_BYTES / 1024 / 1024} MB`,
    );
  const parsed = parseEsminiCsv(await fs.promises.readFile(source.csvPath, 'utf8'));
  // esmini logs the step after the limit too: the run ends where the run's message says (protocol.ts RunEsminiResult.csvFile).
  const kept = source.until === undefined ? parsed.times.length : parsed.times.findIndex((time) => time > source.until! + 1e-9);
  const run = kept < 0 || kept === parsed.times.length ? parsed : { ...parsed, times: parsed.times.subarray(0, kept) };
  let logText = source.logText;
  if (logText === undefined) {
    // esmini writes log.txt beside where it ran unless told otherwise; a CSV's sibling is the usual place.
    const candidates = source.logPath
      ? [source.logPath]
      : [source.csvPath.replace(/\.csv$/i, '.log'), path.join(path.dirname(source.csvPath), 'log.txt')];
    for (const candidate of candidates) {
      logText = await fs.promises.readFile(candidate, 'utf8').catch(() => undefined);
      if (logText !== undefined) break;
    }
  }
  const tracks = runTracks(run, source.label ?? keptRunName(source.csvPath) ?? path.basename(source.csvPath), {}, source.collisions);
  const roadFile = source.roadFile ?? (logText ? parseEsminiLoadedRoad(logText) : undefined);
  return { tracks: roadFile ? { ...tracks, roadFile } : tracks, ...(logText !== undefined ? { log: logText } : {}) };
}
