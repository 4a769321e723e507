import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener, FlatSource, originOf } from '../core/flatten';
import { esminiFindingsOfAnalysis } from '../core/flatten/esminiFindings';
import { packagedFilesFolder } from '../core/flatten/rebase';
import { Problem, problemData } from '../core/problems';
import { foundRoadName, locateRoadFile, RoadFileLookup, roadFolders, scenarioFolderOf } from '../core/semantics/roadFiles';
import { Evaluator, semanticModelOf } from '../core/semantics/model';
import { diskRef, displayRef, nodeFileSystem, ScenarioStore, SourceRef } from '../core/sources';
import { CatalogLoader } from '../core/semantics/catalogs';
import { attribute, attributeValue, descendants, escapeAttributeValue, parseXml, XmlElement } from '../core/xml';
import { anyEntityMoved, parseEsminiLoadedRoad } from '../../../common/src/esminiCsv';
import type { TraceRecord } from '../../../common/src/trace';
import { COLLISION_WHY, collisionWords, secondsText } from '../../../common/src/collisions';
import { ControllerFilesFrom, controllerFilesOfFlattening, withCatalogFolderNote, withControllerFilesFrom } from './controllerFiles';
import { locateEsmini } from './locate';
import { Collision, collisionOf, collisionsIn, EsminiLogMessage, EsminiRemark, isCollisionEnd, isMeantOverlap, readEsminiLog } from './log';
import { esminiMessageSeverity, EsminiProblem, mapEsminiMessages, withoutRunFolder } from './messages';
import {
  EsminiEnd,
  EsminiProcessResult,
  fileLines,
  lastCsvTime,
  makeRunFolder,
  removeRunFolderAt,
  runEsminiProcess,
  sharedRunsFolder,
} from './process';
import { storyboardMapOf, traceFromLog } from './storyboardTrace';
import { LimitKind, NO_END_SECONDS, runLimit, RunLimit, RUNAWAY_SECONDS, withTimeLimit } from './timeLimit';

export const RUN_DEFAULTS = {
  runawaySeconds: RUNAWAY_SECONDS,
  noEndSeconds: NO_END_SECONDS,
  /** Seconds per step, decoupled from the clock. */
  timeStep: 0.05,
  seed: 1,
  /** The largest seed esmini keeps: it reads --seed with std::stoul into an unsigned int (playerbase.cpp:1807), so a larger one is cut or throws 'stoul'. */
  maxSeed: 4_294_967_295,
  /** Wall-clock milliseconds without progress (its CSV neither grows nor advances) after which a run is stopped as hung. */
  stallMs: 60_000,
  maxCsvBytes: 200 * 1024 * 1024,
  maxOutputChars: 8 * 1024 * 1024,
} as const;

/** Whether `value` is a seed esmini keeps (a whole number from 0 to RUN_DEFAULTS.maxSeed): `run --seed` and the debugger's launch configuration both hold to it. */
export function isEsminiSeed(value: unknown): value is number {
  return typeof value === 'number' && Number.isInteger(value) && value >= 0 && value <= RUN_DEFAULTS.maxSeed;
}

export interface EsminiRunOptions {
  /** The configured esmini (setting or --esmini); PATH when empty. */
  esminiPath?: string;
  /** Base of a relative esminiPath (the workspace folder, or the working directory). */
  base?: string;
  /** Extra folders for road files (and catalogs), after the scenario's own folders; relative ones start at `base`. */
  roadPath?: string[];
  /** Simulated seconds at most, set by the user; undefined: the scenario's own end (`runLimit`: the runaway guard, or the default length of a scenario with no stop condition). */
  duration?: number;
  /** Where the user sets `duration` ('--duration', a setting's name): a run's message that a limit ended it names it. */
  durationSetBy?: string;
  timeStep?: number;
  seed?: number;
  /** Wall-clock milliseconds without progress before the run is stopped as hung (`RUN_DEFAULTS.stallMs`). */
  stallMs?: number;
  /** Parent of the private run folder; the system's temporary folder by default. */
  runsFolder?: string;
  /** esmini's global collision detection (`--collision`): each collision is logged as a warning. */
  collision?: boolean;
  onOutput?: (text: string) => void;
  cancel?: AbortSignal;
  /** Run whatever can be flattened despite the scenario's errors (*Run Anyway*, `run --force`); they are listed in `flattenProblems`. */
  force?: boolean;
  /** `runScenarioText`: files written beside the scenario in its run folder, each at its path relative to that folder (a kept run's package files). */
  files?: readonly { path: string; bytes: Uint8Array }[];
  /**
   * The folder the scenario's own relative paths start from and its catalog references: a controller's File named through
   * a `$parameter`, which esmini would miss from the private run folder, is handed as the file it names from there
   * (controllerFiles.ts). `runScenario` sets it itself; `runScenarioText` (a batch's concrete scenario) is given it.
   */
  controllerFilesFrom?: ControllerFilesFrom;
}

/**
 * What a run produced. `csvFile` is esmini's own CSV (`--csv_logger`): 6 header lines, a column
 * line, then one row per step; rows with TimeStamp above `duration` may follow when the run was
 * interrupted, and are to be dropped. The files live in `runFolder` until the caller removes it.
 */
export interface EsminiRunResult {
  outcome:
    /** esmini ran and reported no error (warnings may be in `problems`). */
    | 'ok'
    /** esmini ran, or failed to load the scenario, and reported at least one error. */
    | 'errors'
    /** The scenario could not be flattened: nothing was run; see `flattenProblems`. */
    | 'not-flattened'
    /** No esmini: `message` says how to get it. */
    | 'no-esmini'
    /** esmini could not be started, or was killed. */
    | 'failed'
    | 'cancelled';
  message: string;
  esmini?: string;
  args?: string[];
  runFolder?: string;
  /** The flattened scenario as handed to esmini (with the added time limit). */
  scenarioFile?: string;
  csvFile?: string;
  /** esmini's stdout and stderr. */
  log: string;
  /** Every storyboard transition and condition firing its log reports, as `run --trace` records (absolute file paths). */
  trace?: TraceRecord[];
  end?: EsminiEnd;
  exitCode?: number | null;
  /** Simulated seconds covered by the CSV (its last TimeStamp, at most `duration`). */
  simulatedTime?: number;
  /** The time limit added to the run, in simulated seconds, and where it comes from (`runLimit`). */
  duration: number;
  limitKind: LimitKind;
  /** The added time limit ended the run: the scenario had not ended by itself by then. */
  reachedLimit?: boolean;
  /** Why esmini was stopped before it ended by itself (hung, its CSV past the size bound), as the process runner says. */
  stopReason?: string;
  timeStep: number;
  seed: number;
  wallMs: number;
  problems: EsminiProblem[];
  /** What esmini said about its own road files and 3D models: information, never a problem of the scenario. */
  remarks: EsminiRemark[];
  /** The road file: as written, where it was found (what esmini is given), and what esmini's log says it loaded. */
  roadFile?: RunRoadFile;
  flattenProblems: Problem[];
  /**
   * What the esmini profile finds in the scenario run (core/profiles/esmini.ts: a condition esmini never fires, a position
   * it drops), whatever the simulator the flattening checked for; those `flattenProblems` holds already are not repeated.
   */
  esminiFindings: Problem[];
  /** Not flattened only because of errors: forced (`force`), the same scenario would run. */
  forcible?: boolean;
  /** Where two entities' bounding boxes began to overlap, as esmini's detection logged it, but for overlaps the scenario means (log.ts isMeantOverlap). */
  collisions?: Collision[];
}

export interface RunRoadFile {
  /** As the scenario's LogicFile says, evaluated. */
  filepath: string;
  /** Absolute: the file the bird's-eye view draws too (core/semantics/roadFiles.ts); undefined when not found. */
  resolved?: string;
  /** The package entry holding the road (`/w/pkg.mosc/road.xodr`), which the run writes beside the scenario and the bird's-eye view draws. */
  packaged?: string;
  /** Every path looked at, in order. */
  candidates: string[];
  /** From esmini's log (`Loaded OpenDRIVE:`): the file it read. */
  loaded?: string;
}

/** The folder a scenario's relative file names start from: the main file's folder, or the package's. */
export function sourceFolderOf(ref: SourceRef): string {
  return scenarioFolderOf(ref);
}

/**
 * The scenario text with its LogicFile's filepath replaced by `absolutePath`, so that esmini loads
 * exactly that file: an absolute path is the first place its LocateFile looks. Unchanged when it names none.
 */
export function withRoadFile(text: string, absolutePath: string): string {
  const network = parseXml(text).root?.children.find((child) => child.name === 'RoadNetwork');
  const filepath = network?.children
    .find((child) => child.name === 'LogicFile')
    ?.attributes.find((candidate) => candidate.name === 'filepath');
  if (!filepath) return text;
  return `${text.slice(0, filepath.valueStart)}${escapeAttributeValue(absolutePath, filepath.quote)}${text.slice(filepath.valueEnd)}`;
}

/**
 * Writes the bytes of a road packed with the scenario into a run's private `folder` (`road/NAME`) and returns that file's
 * absolute path, which esmini is handed as a road found on disk is: the copy a flattened text names may be none (a
 * LogicFile that names a `$parameter` is left as written), and by file name esmini would first take a same-named road
 * beside the package.
 */
export function writePackagedRoad(folder: string, name: string, bytes: Uint8Array): string {
  const file = path.join(folder, 'road', path.basename(name));
  writePackagedFiles([{ path: file, bytes }], folder);
  return file;
}

/**
 * Writes the files a self-contained package carries (its catalogs and road, as the flattener returns them) into a run's
 * private `folder`, each at its path (a relative one from `folder`), with the folders they need.
 */
export function writePackagedFiles(files: readonly { path: string; bytes: Uint8Array }[], folder: string): void {
  for (const file of files) {
    const target = path.resolve(folder, file.path);
    fs.mkdirSync(path.dirname(target), { recursive: true });
    fs.writeFileSync(target, file.bytes);
  }
}

/**
 * The copy of a packed road (its `bytes`) among the files a flattening returns, when the flattened text names one: the
 * package files it names are copied in `<name>.files/`, or, through a `$parameter` path, where its value names them.
 * Found by its bytes, so that the road is written once, whichever way the text names it.
 */
export function packagedRoadCopy(files: readonly { path: string; bytes: Uint8Array }[], bytes: Uint8Array): string | undefined {
  const road = Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  return files.find((file) => file.bytes.byteLength === road.byteLength && road.equals(file.bytes))?.path;
}

/** The catalog folders (`Directory path`) the scenario writes, as written. */
function writtenCatalogFolders(source: FlatSource): string[] {
  const root = (source.model ?? source.original)?.document.root;
  const locations = root?.children.find((child) => child.name === 'CatalogLocations');
  if (!locations) return [];
  const folders: string[] = [];
  for (const element of descendants(locations)) {
    if (element.name !== 'Directory') continue;
    const value = attribute(element, 'path')?.value;
    if (value) folders.push(value);
  }
  return folders;
}

/**
 * Where the check found the catalog directories written in a scenario whose relative paths start at `scenarioFolder`:
 * beside it, else in the store's scenario path and catalog path (core/semantics/catalogs.ts reads a SCENARIO_PATH folder
 * D as D/path, D and D/last folder of path). esmini 3.6 looks a catalog up as NAME.xosc in each catalog directory and in
 * each `--path` folder itself (CommonMini.cpp LocateFile, ScenarioReader.cpp LoadCatalog), so handing it these folders
 * makes it load the catalogs the check found, wherever SCENARIO_PATH let the check find them.
 */
export async function foundCatalogFolders(store: ScenarioStore, scenarioFolder: string, written: readonly string[]): Promise<string[]> {
  const loader = new CatalogLoader(store);
  const from = diskRef(path.join(scenarioFolder, 'scenario.xosc'));
  const found: string[] = [];
  for (const entry of written) {
    if (entry.includes('$')) continue;
    for (const directory of await loader.directories(from, entry)) if (!directory.packageRef) found.push(directory.directory);
  }
  return unique(found);
}

/**
 * The folders esmini is handed as `--path` for a run of `main`: the main file's folder, the catalog folders it names
 * (as written, and where the check found them), then the road folders.
 */
export async function esminiSearchPath(flattener: Flattener, main: SourceRef, source: FlatSource, roads: string[]): Promise<string[]> {
  const sourceFolder = sourceFolderOf(main);
  const written = writtenCatalogFolders(source);
  const found = await foundCatalogFolders(flattener.store, sourceFolder, written);
  return unique([
    ...resolvedCatalogFolders(source),
    sourceFolder,
    ...written.filter((value) => !value.includes('$')).map((value) => path.resolve(sourceFolder, value)),
    ...found,
    ...roads,
  ]);
}

/** What a run of a scenario hands esmini: its `--path` folders, and its road file as found there. */
export interface EsminiFolders {
  searchPath: string[];
  /** Undefined when the scenario names no LogicFile (or one through a parameter of unknown value). */
  road?: RoadFileLookup;
}

/**
 * The `--path` folders of a run of `main` (`esminiSearchPath`) and its road file looked for in them by the check's own
 * lookup (core/semantics/roadFiles.ts locateRoadFile), read from disk afresh: the run, the bird's-eye view and the check
 * name one road, also when esmini finds it through a catalog folder (esmini/Catalogs/../xodr/NAME).
 */
export async function esminiFolders(flattener: Flattener, main: SourceRef, source: FlatSource, roads: string[]): Promise<EsminiFolders> {
  const searchPath = await esminiSearchPath(flattener, main, source, roads);
  // The LogicFile as the main file writes it, whatever the flattened text says.
  const document = (source.original ?? source.model)?.document;
  if (!document) return { searchPath };
  const evaluator = source.semantics?.model.document === document ? source.semantics.evaluator : new Evaluator(semanticModelOf(document));
  return { searchPath, road: await locateRoadFile(flattener.store, main, document, evaluator, searchPath, nodeFileSystem) };
}

/**
 * The folders of the catalog files the check took the referenced entries from, in the order the check searched its
 * catalog directories. esmini takes the first NAME.xosc it finds along its search path (CommonMini.cpp LocateFile,
 * ScenarioReader.cpp LoadCatalog), so these go first: otherwise a SCENARIO_PATH folder holding another catalog of that
 * name (CARLA's VehicleCatalog.xosc beside esmini's Catalogs/Vehicles) is the one esmini loads, and the run fails on an
 * entry the check found. The check takes each catalog from one NAME.xosc (core/semantics/catalogs.ts loadedFirst): beside
 * the scenario the first in this order, so a folder before another one here holds no NAME.xosc the check passed over.
 */
export function resolvedCatalogFolders(source: FlatSource): string[] {
  const catalogs = source.semantics?.catalogs;
  const searched = (catalogs?.locations ?? []).flatMap((location) => location.directories.map((directory) => directory.directory));
  const rank = (folder: string) => (searched.includes(folder) ? searched.indexOf(folder) : searched.length);
  const folders: string[] = [];
  for (const reference of catalogs?.references ?? []) {
    const file = reference.entry?.file;
    if (file && file.ref.entries.length === 0) folders.push(path.dirname(file.ref.disk));
  }
  return unique(folders).sort((a, b) => rank(a) - rank(b));
}

function unique(items: string[]): string[] {
  return [...new Set(items)];
}

/**
 * Flattens `main` as the flattener's store sees it (unsaved text included when the store has
 * overlays), writes it to a private folder and runs esmini headless on it with a fixed step and seed
 * for a bounded simulated time. Never throws for a bad scenario or a missing esmini.
 */
export async function runScenario(flattener: Flattener, main: SourceRef, options: EsminiRunOptions = {}): Promise<EsminiRunResult> {
  const started = Date.now();
  const timeStep = options.timeStep ?? RUN_DEFAULTS.timeStep;
  const seed = options.seed ?? RUN_DEFAULTS.seed;
  const base = {
    log: '',
    // Until the scenario is read: a run that does not happen has no other.
    duration: options.duration ?? RUNAWAY_SECONDS,
    limitKind: (options.duration === undefined ? 'runaway' : 'user') as LimitKind,
    timeStep,
    seed,
    problems: [] as EsminiProblem[],
    remarks: [] as EsminiRemark[],
    flattenProblems: [] as Problem[],
    esminiFindings: [] as Problem[],
  };
  const elapsed = () => Date.now() - started;
  checkDuration(options.duration);

  const location = locateEsmini(options.esminiPath, options.base);
  if (!location.found) return { ...base, outcome: 'no-esmini', message: location.message, wallMs: elapsed() };

  // Flattened for the private run folder, so its file paths name the files the sources name (SPEC 11.6).
  const runFolder = makeRunFolder(options.runsFolder ?? sharedRunsFolder());
  const scenarioFile = path.join(runFolder, 'scenario.xosc');
  const flat = await flattener.flatten(main, {
    outputPath: scenarioFile,
    force: options.force,
    roadHanded: true,
    controllerFilesHanded: true,
  });
  const flattenProblems = flat.problems;
  if (flat.text === undefined || withTimeLimit(flat.text, base.duration) === undefined) removeRunFolderAt(runFolder);
  if (flat.text === undefined) {
    const errors = flattenProblems.filter((problem) => problem.severity === 'error').length;
    const counted = `the scenario has ${errors} error${errors === 1 ? '' : 's'}`;
    // Rendered but refused for its errors: forcing runs it.
    if (!options.force && flat.source.text !== undefined) {
      return {
        ...base,
        flattenProblems,
        outcome: 'not-flattened',
        forcible: true,
        esmini: location.program,
        message: `${counted}; nothing was run`,
        wallMs: elapsed(),
      };
    }
    return {
      ...base,
      flattenProblems,
      outcome: 'not-flattened',
      esmini: location.program,
      message: `${counted} and cannot be flattened; nothing was run`,
      wallMs: elapsed(),
    };
  }
  const folders = roadFolders(options.roadPath, options.base ?? process.cwd());
  const { searchPath, road } = await esminiFolders(flattener, main, flat.source, folders);
  const roadFile: RunRoadFile | undefined = road
    ? {
        filepath: road.logic.filepath,
        resolved: road.resolved,
        ...(road.packaged ? { packaged: foundRoadName(road) } : {}),
        candidates: road.candidates,
      }
    : undefined;
  // What esmini is handed: the file found on disk, or a copy of the package's road in the run folder (the flattened one, written with the package's files, when the text names it).
  const packedRoad = !road?.resolved && road?.packaged ? await flattener.store.readBytes(road.packaged) : undefined;
  const handed =
    road?.resolved ??
    (road?.packaged && packedRoad
      ? (packagedRoadCopy(flat.files, packedRoad) ?? writePackagedRoad(runFolder, road.packaged.entries.at(-1) ?? '', packedRoad))
      : undefined);
  const limit = runLimit(flat.text, options.duration, options.durationSetBy);
  const duration = limit.seconds;
  const limited = withTimeLimit(handed ? withRoadFile(flat.text, handed) : flat.text, duration);
  if (limited === undefined) {
    return {
      ...base,
      flattenProblems,
      outcome: 'not-flattened',
      esmini: location.program,
      message: 'the scenario has no <Storyboard>, so esmini has nothing to run',
      wallMs: elapsed(),
    };
  }

  const findings = esminiFindingsOf(flattener, flat.source, flattenProblems);
  // Those the flattening reported already are printed with its problems.
  const esminiFindings = flattener.simulator === 'esmini' ? [] : findings;
  const controllerFilesFrom = controllerFilesOfFlattening(main, flat.source);
  // esmini drives entities through each other without a word unless asked (--collision): a run says where two collide.
  const collision = options.collision ?? true;
  const ran = await runLimitedText(
    location.program,
    limited,
    searchPath,
    { ...options, collision, controllerFilesFrom },
    timeStep,
    seed,
    limit,
    { runFolder, files: flat.files },
  );
  const log = readEsminiLog(ran.run.output);
  if (roadFile) roadFile.loaded = parseEsminiLoadedRoad(ran.run.output);
  // Handed an absolute path, esmini loads that file; should it load another (none was found here), the run and the picture differ: said on the LogicFile.
  if (roadFile?.loaded && path.resolve(runFolder, roadFile.loaded) !== handed) {
    const shown = roadFile.resolved ?? roadFile.packaged;
    const drawn = shown
      ? `the bird's-eye view draws ${shown}`
      : `the bird's-eye view found none (looked for ${roadFile.candidates.join(', ')})`;
    log.messages.unshift({
      level: 'warn',
      time: undefined,
      text: `OpenDRIVE file ${roadFile.loaded} is the road esmini loaded; ${drawn}`,
      logLine: 0,
    });
  }
  // esmini names the run's private folder where it resolves a path from the scenario's copy: said as the files it stands for.
  const copies = new Map<string, string>([[scenarioFile, displayRef(main, undefined)]]);
  if (handed && road && !road.resolved) copies.set(handed, foundRoadName(road) ?? handed);
  const packageOfMain =
    main.entries.length > 0 ? displayRef({ disk: main.disk, entries: main.entries.slice(0, -1) }, undefined) : undefined;
  const filesFolder = path.join(runFolder, packagedFilesFolder(scenarioFile));
  for (const file of flat.files)
    if (packageOfMain && file.path.startsWith(filesFolder + path.sep))
      copies.set(file.path, `${packageOfMain}/${path.relative(filesFolder, file.path).split(path.sep).join('/')}`);
  const messages = log.messages.map((message) => ({
    ...message,
    text: withCatalogFolderNote(
      withoutRunFolder(message.text, runFolder, sourceFolderOf(main), copies),
      controllerFilesFrom.references,
      fs.existsSync,
    ),
  }));
  // A collision is said where the scenario did not mean it: two entities the Init placed on each other, a vehicle and its trailer, a ghost.
  const root = (flat.source.model ?? flat.source.original)?.document.root;
  const declared = new Set((flat.source.model ?? flat.source.original)?.entities.map((entity) => entity.name) ?? []);
  const hitched = root ? hitchedPairs(root) : new Set<string>();
  const meant = (message: EsminiLogMessage) => {
    const collision = collisionOf(message);
    return isCollisionEnd(message.text) || (collision !== undefined && isMeantOverlap(collision, declared, hitched));
  };
  // A collision is no complaint of esmini's about the scenario: said after the run's figures, with where each entity is declared.
  const collisions = collisionsIn(messages.filter((message) => !meant(message)));
  const problems = mapEsminiMessages(
    messages.filter((message) => !collisionOf(message) && !isCollisionEnd(message.text)),
    flat.source,
    main,
  );
  const declaredAt = (name: string) => entityPlace(flat.source, name, sourceFolderOf(main));
  const trace = traceFromLog(storyboardMapOf(flat.source), ran.run.output);
  const errors = problems.filter((problem) => problem.severity === 'error').length;
  const outcome = outcomeOf(
    ran,
    errors,
    problems.length - errors,
    problems.find((problem) => problem.severity === 'error')?.message,
    findings[0] && {
      count: findings.length,
      first: `${displayRef(findings[0].source, sourceFolderOf(main))}:${findings[0].range.start.line + 1}`,
    },
    collisions,
    declaredAt,
  );
  const scenarioErrors = flattenProblems.filter((problem) => problem.severity === 'error').length;
  const forced =
    scenarioErrors > 0 && (outcome.outcome === 'ok' || outcome.outcome === 'errors')
      ? ` (run anyway despite ${scenarioErrors} error${scenarioErrors === 1 ? '' : 's'} in the scenario)`
      : '';
  return {
    ...base,
    flattenProblems,
    esminiFindings,
    problems,
    remarks: log.remarks,
    trace,
    roadFile,
    ...ran.common,
    // The log's tail is shown when esmini fails: its paths name what the private folder stood for, as the messages do.
    log: withoutRunFolder(ran.common.log, runFolder, sourceFolderOf(main), copies),
    duration,
    limitKind: limit.kind,
    esmini: location.program,
    wallMs: elapsed(),
    ...outcome,
    message: outcome.message + forced,
    collisions,
  };
}

/**
 * The esmini profile's findings (code `simulator`) of `main` and of the groups it imports, which a run in esmini names
 * whatever simulator the flattening checked for: those of the flattening when it checked for esmini, else those its
 * analysis gives checked again in esmini's context (`esminiFindingsOfAnalysis`: no file is read or linked again).
 * Those of a StartTrigger whose edge esmini never fires come first: an Act that never starts holds back its Events, whose
 * own findings (an Act that does not start at time 0) follow from it.
 */
function esminiFindingsOf(flattener: Flattener, flattened: FlatSource, flattenProblems: readonly Problem[]): Problem[] {
  const findings =
    flattener.simulator === 'esmini'
      ? flattenProblems.filter((problem) => problem.code === 'simulator')
      : esminiFindingsOfAnalysis(flattened);
  const neverFires = (problem: Problem) => problemData(problem, 'simulator')?.simulationTimeFix === 'edge';
  return [...findings.filter(neverFires), ...findings.filter((problem) => !neverFires(problem))];
}

/** A plain scenario's run (`runScenarioText`): esmini's messages as it printed them, placed on no source line. */
export type EsminiTextRunResult = Omit<EsminiRunResult, 'problems' | 'flattenProblems' | 'esminiFindings'> & {
  messages: EsminiLogMessage[];
};

/**
 * Runs plain OpenSCENARIO text (already flat, such as a concrete scenario of a distribution) as `runScenario`
 * runs a flattened file: the same time limit, step, seed and bounds. `searchPath`: absolute folders for roads
 * and catalogs, in order. Never throws for a bad scenario or a missing esmini.
 */
export async function runScenarioText(text: string, searchPath: string[], options: EsminiRunOptions = {}): Promise<EsminiTextRunResult> {
  const started = Date.now();
  const timeStep = options.timeStep ?? RUN_DEFAULTS.timeStep;
  const seed = options.seed ?? RUN_DEFAULTS.seed;
  checkDuration(options.duration);
  const limit = runLimit(text, options.duration, options.durationSetBy);
  const base = {
    log: '',
    duration: limit.seconds,
    limitKind: limit.kind,
    timeStep,
    seed,
    messages: [] as EsminiLogMessage[],
    remarks: [] as EsminiRemark[],
  };
  const elapsed = () => Date.now() - started;
  const location = locateEsmini(options.esminiPath, options.base);
  if (!location.found) return { ...base, outcome: 'no-esmini', message: location.message, wallMs: elapsed() };
  const limited = withTimeLimit(text, limit.seconds);
  if (limited === undefined)
    return {
      ...base,
      outcome: 'not-flattened',
      esmini: location.program,
      message: 'the scenario has no <Storyboard>, so esmini has nothing to run',
      wallMs: elapsed(),
    };
  const roadPath = (options.roadPath ?? []).map((folder) => path.resolve(options.base ?? process.cwd(), folder));
  const ran = await runLimitedText(location.program, limited, unique([...searchPath, ...roadPath]), options, timeStep, seed, limit, {
    files: options.files,
  });
  const { messages, remarks } = readEsminiLog(ran.run.output);
  // As run counts them (its messages placed by mapEsminiMessages): a colour esmini skips is no failed run.
  const failing = messages.filter((message) => esminiMessageSeverity(message) === 'error');
  const errors = failing.length;
  return {
    ...base,
    messages,
    remarks,
    ...ran.common,
    esmini: location.program,
    wallMs: elapsed(),
    ...outcomeOf(ran, errors, messages.length - errors, failing[0]?.text),
  };
}

interface LimitedRun {
  run: EsminiProcessResult;
  common: Pick<
    EsminiRunResult,
    'args' | 'runFolder' | 'scenarioFile' | 'csvFile' | 'log' | 'end' | 'exitCode' | 'simulatedTime' | 'reachedLimit' | 'stopReason'
  >;
  /** The added time limit, in simulated seconds, and where it comes from. */
  limit: RunLimit;
}

/** Writes the time-limited text (and the files a self-contained package carries) to a private folder and runs esmini on it. */
async function runLimitedText(
  program: string,
  limited: string,
  searchPath: string[],
  options: EsminiRunOptions,
  timeStep: number,
  seed: number,
  limit: RunLimit,
  prepared: { runFolder?: string; files?: readonly { path: string; bytes: Uint8Array }[] } = {},
): Promise<LimitedRun> {
  const duration = limit.seconds;
  const runFolder = prepared.runFolder ?? makeRunFolder(options.runsFolder ?? sharedRunsFolder());
  const scenarioFile = path.join(runFolder, 'scenario.xosc');
  const csvFile = path.join(runFolder, 'trajectories.csv');
  // A controller's File esmini would miss from the private folder is handed as the file the scenario itself reaches.
  const from = options.controllerFilesFrom;
  fs.writeFileSync(
    scenarioFile,
    from ? withControllerFilesFrom(limited, from.scenarioFolder, runFolder, from.references, fs.existsSync) : limited,
  );
  // A package file never replaces the run's own scenario or log.
  const own = new Set([scenarioFile, csvFile]);
  writePackagedFiles(
    (prepared.files ?? []).filter((file) => !own.has(path.resolve(runFolder, file.path))),
    runFolder,
  );
  const run = await runEsminiProcess({
    program,
    scenarioFile,
    workDir: runFolder,
    csvFile,
    searchPath,
    timeStep,
    seed,
    duration,
    collision: options.collision,
    stallMs: options.stallMs ?? RUN_DEFAULTS.stallMs,
    maxCsvBytes: RUN_DEFAULTS.maxCsvBytes,
    maxOutputChars: RUN_DEFAULTS.maxOutputChars,
    onOutput: options.onOutput,
    cancel: options.cancel,
  });
  const hasCsv = fs.existsSync(csvFile);
  const lastTime = hasCsv ? lastCsvTime(csvFile) : undefined;
  // The added StopTrigger fires at the first step past the limit; the CSV's follower interrupts a run that went on.
  const reachedLimit =
    (lastTime !== undefined && lastTime >= duration - timeStep / 2) || (run.end === 'interrupted' && run.stoppedBy === 'time');
  return {
    run,
    limit,
    common: {
      reachedLimit,
      stopReason: run.reason,
      args: run.args,
      runFolder,
      scenarioFile,
      csvFile: hasCsv ? csvFile : undefined,
      log: run.output,
      end: run.end,
      exitCode: run.exitCode,
      simulatedTime: lastTime === undefined ? undefined : Math.min(lastTime, duration),
    },
  };
}

/**
 * How a run ended, in a word and a sentence, from how the process ended and the errors esmini reported
 * (`firstError`: the first one's text). A run that simulated nothing while esmini reported an error did not
 * happen: esmini refused the scenario (a 0.9 header, a controller it does not know), and says why.
 */
function outcomeOf(
  ran: LimitedRun,
  errors: number,
  warnings: number,
  firstError?: string,
  findings?: { count: number; first: string },
  collisions: readonly Collision[] = [],
  declaredAt: (entity: string) => string | undefined = () => undefined,
): Pick<EsminiRunResult, 'outcome' | 'message'> {
  const { run, common } = ran;
  const counts = `${errors} error${errors === 1 ? '' : 's'}, ${warnings} warning${warnings === 1 ? '' : 's'}`;
  if (run.end === 'cancelled') return { outcome: 'cancelled', message: 'the run was cancelled' };
  if (run.end === 'not-started' || run.end === 'killed') return { outcome: 'failed', message: `esmini ${run.reason ?? 'failed'}` };
  if (run.exitCode !== 0 && run.end === 'exited' && errors === 0) {
    return { outcome: 'failed', message: `esmini ended with exit code ${run.exitCode} without an error message; see its log` };
  }
  if (errors > 0 && common.simulatedTime === undefined) {
    const code = run.end === 'exited' && run.exitCode !== 0 ? ` (exit code ${run.exitCode})` : '';
    return { outcome: 'failed', message: `esmini did not run the scenario${code}: ${firstError ?? 'see its log'}` };
  }
  const covered =
    common.simulatedTime === undefined
      ? 'no trajectory: esmini placed no entity (each needs a position in Init, such as a TeleportAction)'
      : `${common.simulatedTime.toFixed(2)} s simulated${common.reachedLimit ? `: ${limitSentence(ran.limit)}` : ''}`;
  // A run in which nothing moved ran, but may not be the one the user meant (the paper's library in esmini): said.
  const still =
    common.csvFile && common.simulatedTime !== undefined && common.simulatedTime > 0 && anyEntityMoved(fileLines(common.csvFile)) === false
      ? `; no entity moved: each stood where the Init placed it for the whole run (${
          findings
            ? `esmini runs it otherwise than written: ${findings.count === 1 ? 'the run names one esmini finding, at' : `the run names ${findings.count} esmini findings, the first at`} ${findings.first}`
            : 'does an Act or Event never start? the check with the simulator set to esmini names such conditions'
        })`
      : '';
  return {
    outcome: errors > 0 ? 'errors' : 'ok',
    message: `esmini: ${counts}; ${covered} (the run took ${(run.wallMs / 1000).toFixed(2)} s)${still}${collisionSentence(collisions, declaredAt)}`,
  };
}

/** `file:line` (from `base`, the main's folder) of the ScenarioObject declaring `name`, in the file it was written in; undefined when the scenario declares none (esmini's own). */
function entityPlace(source: FlatSource, name: string, base: string): string | undefined {
  const root = (source.model ?? source.original)?.document.root;
  const element = root?.children
    .find((child) => child.name === 'Entities')
    ?.children.find((child) => child.name === 'ScenarioObject' && attributeValue(child, 'name') === name);
  if (!element) return undefined;
  const origin = originOf(source, element);
  const document = (origin.source.original ?? origin.source.model)?.document;
  return document
    ? `${displayRef(origin.source.ref, base)}:${document.lines.range(origin.element.start, origin.element.start).start.line + 1}`
    : undefined;
}

/**
 * Each vehicle and trailer the scenario hitches together, `A\u0000B`: a ConnectTrailerAction's actors (its Private's entity
 * or its group's) with its trailerRef, and a Vehicle's Trailer/TrailerRef with the entity declaring it.
 */
function hitchedPairs(root: XmlElement): Set<string> {
  const pairs = new Set<string>();
  const visit = (element: XmlElement, owners: readonly string[]) => {
    let here = owners;
    if (element.name === 'ScenarioObject' || element.name === 'Private')
      here = [attributeValue(element, 'name') ?? attributeValue(element, 'entityRef') ?? ''];
    if (element.name === 'ManeuverGroup')
      here = element.children
        .filter((child) => child.name === 'Actors')
        .flatMap((actors) => actors.children.map((actor) => attributeValue(actor, 'entityRef') ?? ''));
    const trailer =
      element.name === 'ConnectTrailerAction'
        ? attributeValue(element, 'trailerRef')
        : element.name === 'TrailerRef'
          ? attributeValue(element, 'entityRef')
          : undefined;
    if (trailer !== undefined) for (const owner of here) pairs.add(`${owner}\u0000${trailer}`);
    for (const child of element.children) visit(child, here);
  };
  visit(root, []);
  return pairs;
}

/** At most this many collisions are named in a run's message; the rest are counted (each is a warning of the run). */
const NAMED_COLLISIONS = 3;

/** `; A and B collide at t=9.35 s`, for each pair's first collision, as esmini's detection logged it; empty when none. */
export function collisionSentence(
  collisions: readonly Collision[],
  declaredAt: (entity: string) => string | undefined = () => undefined,
): string {
  const first = new Map<string, Collision>();
  for (const collision of collisions) {
    const key = [...collision.entities].sort().join('\u0000');
    if (!first.has(key)) first.set(key, collision);
  }
  if (first.size === 0) return '';
  const said = [...first.values()].slice(0, NAMED_COLLISIONS).map((collision) =>
    collisionWords(collision, (name) => {
      const place = declaredAt(name);
      return place ? `${name} (${place})` : name;
    }),
  );
  const more =
    first.size > NAMED_COLLISIONS ? ` and ${first.size - NAMED_COLLISIONS} more pair${first.size - NAMED_COLLISIONS === 1 ? '' : 's'}` : '';
  return `; ${said.join(', ')}${more} (${COLLISION_WHY})`;
}

/** Why the time limit added to a run ended it, in one sentence (the same on every machine: no wall-clock figure). */
export function limitSentence(limit: RunLimit): string {
  return {
    user: `stopped at the ${secondsText(limit.seconds)} s limit ${limit.setBy ? `set by ${limit.setBy}` : 'set for the run'}, before the scenario ended by itself`,
    'no-end': `the scenario's StopTrigger has no condition, so it has no end of its own and runs ${secondsText(limit.seconds)} s (set a duration${limit.setBy ? ` with ${limit.setBy}` : ''} to run longer)`,
    runaway: `its StopTrigger had not ended it after ${secondsText(limit.seconds)} s simulated, so it was stopped as a runaway`,
  }[limit.kind];
}

function checkDuration(duration: number | undefined): void {
  if (duration !== undefined && (!(duration > 0) || !Number.isFinite(duration)))
    throw new Error(`the duration must be a positive number of seconds, not ${duration}`);
}

/** Removes a run's private folder (its CSV and scenario copy). */
export function removeRunFolder(result: Pick<EsminiRunResult, 'runFolder'>): void {
  if (result.runFolder) removeRunFolderAt(result.runFolder);
}
