import { MAX_ROAD_FILE_BYTES, openDriveSignals } from '../opendrive/road';
import { foundRoadName, readFoundRoad, RoadFileLookup } from './roadFiles';
import { ScenarioStore } from '../sources';
import { decodeUtf8 } from '../text';
import { CORE_MEMOS, coreMemo } from '../memos';

/** What the road-network rules and Insert into Main need of the OpenDRIVE file a scenario names (its `RoadNetwork/LogicFile`). */
export interface RoadSignals {
  /** The road file, absolute, or the package entry that holds it (`foundRoadName`). */
  file: string;
  signalIds: ReadonlySet<string>;
  /** The ids of its roads of left-hand traffic (`rule="LHT"`), where Insert into Main mirrors a module's placement. */
  leftHandRoads: ReadonlySet<string>;
}

/**
 * What a store (a workspace's, a CLI run's) remembers of road files. `reads`: a road file read in the
 * last moments is not read again, so a folder check reads each road file about once, while an editor
 * (one store for the session) sees a changed road file on its next analysis after that. `summaries`: the
 * signals by path and content hash, as a road file is large and rarely changes (bounded, the oldest out).
 */
interface RoadMemory {
  reads: Map<string, { readAt: number; pending: Promise<RoadSignals | undefined> }>;
  summaries: Map<string, { hash: string; signals: RoadSignals }>;
}

const memories = coreMemo<ScenarioStore, RoadMemory>('roadSignals');
const { entries: SUMMARY_LIMIT, freshMs: FRESH_MS } = CORE_MEMOS.roadSignals.bound;

function memoryOf(store: ScenarioStore): RoadMemory {
  let memory = memories.get(store);
  if (!memory) memories.set(store, (memory = { reads: new Map(), summaries: new Map() }));
  return memory;
}

/**
 * The signals of the road file a scenario names, found where a run has esmini find it (`locateRoadFile`,
 * core/semantics/roadFiles.ts). Undefined when the document names none or it cannot be found or read: the road rules then say nothing.
 */
export async function roadSignalsOf(store: ScenarioStore, road: RoadFileLookup | undefined): Promise<RoadSignals | undefined> {
  const file = road && foundRoadName(road);
  if (!road || !file) return undefined;
  const known = memoryOf(store).reads;
  const now = Date.now();
  let entry = known.get(file);
  if (!entry || now - entry.readAt > FRESH_MS) {
    entry = { readAt: now, pending: readRoadSignals(store, road, file) };
    known.set(file, entry);
  }
  return entry.pending;
}

async function readRoadSignals(store: ScenarioStore, road: RoadFileLookup, file: string): Promise<RoadSignals | undefined> {
  // Unreadable (too large, not a regular file, gone): not a problem of these rules.
  const bytes = await readFoundRoad(store, road, MAX_ROAD_FILE_BYTES).catch(() => undefined);
  if (!bytes || bytes.byteLength > MAX_ROAD_FILE_BYTES) return undefined;
  // Loaded here, not with the module: a run that reads no road file (most CLI runs) does not pay for Node's crypto.
  const { createHash } = await import('node:crypto');
  const hash = createHash('sha1').update(bytes).digest('hex');
  const summaries = memoryOf(store).summaries;
  const cached = summaries.get(file);
  if (cached?.hash === hash) return cached.signals;
  const network = openDriveSignals(decodeUtf8(bytes));
  // Not an OpenDRIVE file, or one with no roads: nothing to resolve a signal against.
  const signals = network.hasRoads ? { file, signalIds: network.signalIds, leftHandRoads: network.leftHandRoads } : undefined;
  summaries.delete(file);
  if (signals) summaries.set(file, { hash, signals });
  while (summaries.size > SUMMARY_LIMIT) summaries.delete(summaries.keys().next().value as string);
  return signals;
}
