import * as fs from 'node:fs';
import * as path from 'node:path';
import { Flattener, FlatSource } from '../core/flatten';
import { packagedFilesFolder } from '../core/flatten/rebase';
import { ESMINI_ELEMENT_TYPES, MappedElement, StoryboardMap } from '../core/flatten/storyboardMap';
import { Problem } from '../core/problems';
import { roadFolders } from '../core/semantics/roadFiles';
import { SourceRef } from '../core/sources';
import { escapeAttributeValue } from '../core/xml';
import { EsminiLibrary, EsminiObjectState, loadEsminiLibrary } from '../esmini/library';
import { readEsminiLog } from '../esmini/log';
import { EsminiProblem, mapEsminiMessages } from '../esmini/messages';
import { ControllerFilesFrom, controllerFilesOfFlattening, withCatalogFolderNote } from '../esmini/controllerFiles';
import { makeRunFolder, removeRunFolderAt, sharedRunsFolder } from '../esmini/process';
import {
  esminiFolders,
  packagedRoadCopy,
  RUN_DEFAULTS,
  sourceFolderOf,
  withRoadFile,
  writePackagedFiles,
  writePackagedRoad,
} from '../esmini/run';
import { CONDITION_LOG, ConditionReason, conditionReason, storyboardMapOf } from '../esmini/storyboardTrace';
import { runLimit } from '../esmini/timeLimit';
import type { StepCounter } from './progressPage';

export { conditionReason, type ConditionReason };

/*
 * A scenario run step by step in esmini's library, editor-free: the debug adapter (debug/adapter.ts) and the CLI's
 * `run --trace` both drive it. Every storyboard transition and condition firing esmini reports through its callbacks
 * comes back with the element it names in the flattened scenario and where that was written in the modular sources.
 */

export type ElementState = 'standby' | 'running' | 'complete';
const STATES: Record<number, ElementState> = { 1: 'standby', 2: 'running', 3: 'complete' };

const NO_EVENTS: readonly StoryboardEvent[] = Object.freeze([]);

/** One storyboard transition or condition firing, as esmini reported it. */
export interface StoryboardEvent {
  time: number;
  /** esmini's full path (`Story::Act::ManeuverGroup::Maneuver::Event`); a condition's owner path then its name. */
  element: string;
  name: string;
  type: string;
  /** For a condition: `true` (it fired). */
  state: ElementState | 'true';
  /** The element in the flattened scenario (undefined when the map has no element of that path). */
  mapped: MappedElement | undefined;
  /** For a condition: the rule and threshold as the scenario writes them, and what esmini measured. */
  reason?: ConditionReason;
  /** For a condition: when esmini's callback reported it, in ms of the system's monotonic clock (process.hrtime), for the pause latency (bench/debugger.mjs). */
  reportedAtMs?: number;
}

export interface SimulationOptions {
  timeStep?: number;
  /** Simulated seconds after which the run ends, when the scenario's StopTrigger has not ended it. */
  duration?: number;
  seed?: number;
  roadPath?: string[];
  base?: string;
  esminiLibrary?: string;
  force?: boolean;
  /** Called inside esmini's callbacks, before its step goes on: how far the run got, should esmini crash in that step. */
  onCallback?: (time: number, what: string) => void;
  /** Told the steps esmini has made after each step: the time reached, should esmini crash in a step that reports nothing (progressPage.ts). */
  stepCounter?: StepCounter;
}

/** What the debugger shows of a run at one moment, read from esmini then. */
export interface SimulationView {
  time: number;
  entities: EntityState[];
  pairs: EntityPair[];
  parameters: NamedValue[];
  variables: NamedValue[];
}

export interface NamedValue {
  name: string;
  value: string | number | boolean | undefined;
}

export interface EntityState extends EsminiObjectState {
  name: string;
  acceleration: number;
}

/** Time-to-collision and gap from one entity to another. */
export interface EntityPair {
  from: string;
  to: string;
  /** Longitudinal free-space distance along the road (esmini's SE_GetDistanceToObject ds). */
  gap: number | undefined;
  ttc: number | undefined;
}

/** A scenario that could not be started: the messages name the source lines when they can. */
export class SimulationLoadError extends Error {
  constructor(
    message: string,
    readonly problems: (Problem | EsminiProblem)[] = [],
  ) {
    super(message);
  }
}

/** The scenario as esmini will read it, with its map back to the sources. */
export interface PreparedScenario {
  main: SourceRef;
  text: string;
  searchPath: string[];
  /**
   * A road packed with the scenario, which the simulation hands esmini as a copy in its private folder: its copy among
   * `packagedFiles` when the flattened text names it (`copy`), else one it writes (its file name and bytes).
   */
  packagedRoad?: { copy: string } | { name: string; bytes: Uint8Array };
  /**
   * The package files the text names (a self-contained package's catalogs and road), each by its path relative to the
   * main file's folder (`.modular2simple-debug.files/…`): the simulation writes them into its private folder, never
   * beside the user's files, and names them there.
   */
  packagedFiles: { path: string; bytes: Uint8Array }[];
  flat: FlatSource;
  map: StoryboardMap;
  flattenProblems: Problem[];
  /**
   * The folder esmini runs in, the main file's (esmini given a text, not a file, looks a controller File up from its working
   * folder alone), with the catalog references whose entries name controller Files: as Run in esmini takes them.
   */
  controllerFiles: ControllerFilesFrom;
}

/** The name the scenario is flattened to, beside the main file (never written): its packaged files are named in `<name>.files/`. */
const DEBUG_OUTPUT_NAME = '.modular2simple-debug.xosc';

/**
 * The text with every path into `<DEBUG_OUTPUT_NAME>.files` (written by the flattener, relative to the main file's
 * folder) made absolute in `folder`, where the simulation writes those files.
 */
export function withPackagedFilesIn(text: string, folder: string): string {
  const written = packagedFilesFolder(DEBUG_OUTPUT_NAME);
  // The flattener writes the name at a value's start, followed by `/` or the value's end.
  const pattern = new RegExp(`(["'])${written.replace(/\./g, '\\.')}(?=[/"'])`, 'g');
  const absolute = path.join(folder, written);
  return text.replace(pattern, (_whole, quote: '"' | "'") => `${quote}${escapeAttributeValue(absolute, quote)}`);
}

/** Flattens `main` and finds its road and catalog folders as Run in esmini does (esmini/run.ts). */
export async function prepareScenario(flattener: Flattener, main: SourceRef, options: SimulationOptions): Promise<PreparedScenario> {
  const sourceFolder = sourceFolderOf(main);
  // Flattened as if written beside the main file, so that its relative file paths name the files the sources name.
  const flat = await flattener.flatten(main, { outputPath: path.join(sourceFolder, DEBUG_OUTPUT_NAME), force: options.force });
  if (flat.text === undefined) {
    const errors = flat.problems.filter((problem) => problem.severity === 'error');
    throw new SimulationLoadError(
      `the scenario has ${errors.length} error${errors.length === 1 ? '' : 's'}${options.force ? ' and cannot be flattened' : ' (force: true runs it anyway)'}; nothing was run`,
      errors,
    );
  }
  const folders = roadFolders(options.roadPath, options.base ?? process.cwd());
  const { searchPath, road } = await esminiFolders(flattener, main, flat.source, folders);
  const text = road?.resolved ? withRoadFile(flat.text, road.resolved) : flat.text;
  const map = storyboardMapOf(flat.source);
  const roadBytes = road?.packaged && (await flattener.store.readBytes(road.packaged));
  const roadCopy = roadBytes && packagedRoadCopy(flat.files, roadBytes);
  const packagedRoad =
    road?.packaged &&
    roadBytes &&
    (roadCopy ? { copy: path.relative(sourceFolder, roadCopy) } : { name: road.packaged.entries.at(-1) ?? '', bytes: roadBytes });
  return {
    main,
    text,
    searchPath,
    ...(packagedRoad ? { packagedRoad } : {}),
    packagedFiles: flat.files.map((file) => ({ path: path.relative(sourceFolder, file.path), bytes: file.bytes })),
    flat: flat.source,
    map,
    flattenProblems: flat.problems,
    controllerFiles: controllerFilesOfFlattening(main, flat.source),
  };
}

/**
 * One run of a prepared scenario in esmini's library. Only one can be open per process (the library's state is
 * global): `close` before the next.
 */
export class Simulation {
  readonly timeStep: number;
  readonly duration: number;
  private readonly library: EsminiLibrary;
  private readonly folder: string;
  private readonly logFile: string;
  private logOffset = 0;
  private pending: StoryboardEvent[] = [];
  /** The last condition line of the log per condition name (its delay may fire it steps later). */
  private readonly conditionLines = new Map<string, string>();
  /** The state of each element by path. */
  readonly states = new Map<
    string,
    { state: ElementState; since: number; mapped: MappedElement | undefined; type: string; name: string }
  >();
  private closed = false;
  private steps = 0;
  /**
   * Whether a step's start is read from esmini in its first callback (holdStepStart): set by the debugger while a
   * stop at a transition may come (a breakpoint on an element, Step Over, Step Out), as it costs esmini calls.
   */
  keepStepStart = false;
  /** The current step's start, read in its first callback when keepStepStart. */
  private stepStart: SimulationView | undefined;
  /** The moment shown instead of esmini's state now, while stopped at a step's start (holdStepStart). */
  private held: SimulationView | undefined;
  ended = false;
  /** What esmini reported while loading the scenario it then ran (errors and warnings, on their source lines), as a run reports them. */
  loadProblems: EsminiProblem[] = [];

  constructor(
    readonly scenario: PreparedScenario,
    readonly options: SimulationOptions = {},
  ) {
    this.timeStep = options.timeStep ?? RUN_DEFAULTS.timeStep;
    // As Run in esmini: the scenario's own end unless a duration is set (esmini/timeLimit.ts runLimit).
    this.duration = runLimit(scenario.text, options.duration).seconds;
    if (!(this.timeStep > 0) || !(this.duration > 0))
      throw new SimulationLoadError('timeStep and duration must be positive numbers of seconds');
    this.library = loadEsminiLibrary(options.esminiLibrary, options.base);
    this.folder = makeRunFolder(sharedRunsFolder());
    this.logFile = path.join(this.folder, 'log.txt');
  }

  /** Loads the scenario into esmini; throws SimulationLoadError with esmini's messages on their source lines when it refuses it. */
  start(): StoryboardEvent[] {
    this.load();
    this.options.stepCounter?.start(this.timeStep);
    // Stories start, and their Acts go to standby, during SE_Init, before a callback can be registered: reported here, at time 0.
    const started: StoryboardEvent[] = this.scenario.map.elements
      .filter((element) => element.kind === 'Story' || element.kind === 'Act')
      .map((element) => ({
        time: 0,
        element: element.path,
        name: element.name,
        type: element.kind,
        state: element.kind === 'Story' ? 'running' : 'standby',
        mapped: element,
      }));
    for (const event of started)
      this.states.set(event.element, {
        state: event.state as ElementState,
        since: 0,
        mapped: event.mapped,
        type: event.type,
        name: event.name,
      });
    return started;
  }

  /**
   * The scenario's text, the package files it names written into the private folder and named there, and a road packed
   * with it named there by its absolute path (as Run in esmini does), written once.
   */
  private textToLoad(): string {
    const { packagedRoad: road, packagedFiles } = this.scenario;
    writePackagedFiles(packagedFiles, this.folder);
    const roadFile = road && ('copy' in road ? path.join(this.folder, road.copy) : writePackagedRoad(this.folder, road.name, road.bytes));
    const text = roadFile ? withRoadFile(this.scenario.text, roadFile) : this.scenario.text;
    return packagedFiles.length > 0 ? withPackagedFilesIn(text, this.folder) : text;
  }

  /** esmini's SE_Init on the scenario, the callbacks registered. */
  private load(): void {
    const library = this.library;
    library.logToConsole(false);
    library.setLogFilePath(this.logFile);
    library.clearPaths();
    for (const folder of this.scenario.searchPath) library.addPath(folder);
    library.setSeed(this.options.seed ?? RUN_DEFAULTS.seed);
    // esmini reads relative file names from its working folder: the main file's, where the text was flattened for (the search path starts with catalog folders).
    const previous = process.cwd();
    let result: number;
    try {
      process.chdir(this.scenario.controllerFiles.scenarioFolder);
      result = library.initWithString(this.textToLoad());
    } finally {
      process.chdir(previous);
    }
    library.flushLog();
    const problems = this.loadMessages(this.readLog());
    if (result !== 0) {
      library.close();
      this.closed = true;
      this.removeFolder();
      const errors = problems.filter((problem) => problem.severity === 'error');
      throw new SimulationLoadError(`esmini did not load the scenario: ${errors[0]?.message ?? 'see its log'}`, errors);
    }
    // Loaded despite them (a controller File esmini missed), as a run reports them.
    this.loadProblems = problems;
    // The conditions' lines come after what esmini logged loading the scenario: their first read starts there.
    this.logOffset = fileSize(this.logFile);
    library.onStoryboardChange((name, type, state, fullPath) => this.transition(name, type, state, fullPath));
    library.onCondition((name, timestamp) => this.conditionFired(name, timestamp));
  }

  /**
   * Shows the run at the start of its last step, where what that step reported happened, until the next step or
   * release. In a step esmini weighs the triggers and starts elements at the step's start time (the time its callbacks
   * and its log give), then moves the entities one step on (ScenarioEngine::step); the state at the start is read in
   * the step's first callback, before anything in the step changed it (keepStepStart). Returns false when there is
   * none (the last step reported nothing, or keepStepStart was off).
   */
  holdStepStart(): boolean {
    this.held = this.stepStart;
    return this.held !== undefined;
  }

  /** Back to esmini's state now (the end of the last step): what Continue goes on from. */
  release(): void {
    this.held = undefined;
  }

  /** Whether the run is shown at its last step's start (holdStepStart). */
  get holding(): boolean {
    return this.held !== undefined;
  }

  get time(): number {
    return this.held?.time ?? this.library.simulationTime();
  }

  /** One step of `timeStep` seconds; what esmini reported during it (most steps: nothing, the one shared empty list). */
  step(): readonly StoryboardEvent[] {
    if (this.ended || this.closed) return NO_EVENTS;
    this.held = undefined;
    this.stepStart = undefined;
    this.library.stepDT(this.timeStep);
    this.steps++;
    this.options.stepCounter?.steps(this.steps);
    // A step costs esmini microseconds, so each call counts: esmini's time is asked for only from a step before the end,
    // its quit flag (the storyboard complete, which the callback reports) when something was reported, else every 64 steps.
    const nearEnd = (this.steps + 1) * this.timeStep >= this.duration;
    const quitMayBeSet = this.pending.length > 0 || this.steps % 64 === 0;
    if ((quitMayBeSet && this.library.quitFlag() !== 0) || (nearEnd && this.library.simulationTime() >= this.duration - 1e-9))
      this.ended = true;
    if (this.pending.length === 0) return NO_EVENTS;
    const events = this.pending;
    this.pending = [];
    this.attributeConditions(events);
    return events;
  }

  /** The steps made since the run started. */
  get stepsMade(): number {
    return this.steps;
  }

  /**
   * Up to `count` steps, ending early after the first step that reported something, ended the run or after which
   * `interrupted()` is true: what that step reported. A small loop of its own, which V8 optimizes within a run's
   * first slice; the same loop inside the debugger's slice function stayed in V8's baseline tier (perf), about 0.2 µs a
   * step against esmini's 2.5 µs (docs/benchmarks.md).
   */
  stepMany(count: number, interrupted: () => boolean): readonly StoryboardEvent[] {
    for (let made = 0; made < count; made++) {
      const events = this.step();
      if (events.length > 0 || this.ended || interrupted()) return events;
    }
    return NO_EVENTS;
  }

  private transition(name: string, type: number, state: number, fullPath: string): void {
    this.keepStepStartNow();
    const kind = ESMINI_ELEMENT_TYPES[type] ?? `type ${type}`;
    const element = fullPath || name;
    const mapped = this.scenario.map.atPath(element);
    const stateName = STATES[state] ?? 'standby';
    const time = this.library.simulationTime();
    this.options.onCallback?.(time, `${kind} ${name} ${stateName}`);
    this.states.set(element, { state: stateName, since: time, mapped, type: kind, name });
    this.pending.push({ time, element, name, type: kind, state: stateName, mapped });
  }

  private conditionFired(name: string, timestamp: number): void {
    this.keepStepStartNow();
    this.options.onCallback?.(timestamp, `Condition ${name} true`);
    this.library.flushLog();
    for (const line of this.readLog().split('\n')) {
      const match = CONDITION_LOG.exec(line);
      if (match) this.conditionLines.set(match[1], match[2]);
    }
    const detail = this.conditionLines.get(name);
    const candidates = this.scenario.map.conditionsNamed(name);
    this.pending.push({
      time: timestamp,
      element: candidates[0]?.path ?? name,
      name,
      type: 'Condition',
      state: 'true',
      mapped: candidates[0],
      reason: detail === undefined ? undefined : conditionReason(detail),
      reportedAtMs: Number(process.hrtime.bigint()) / 1e6,
    });
  }

  /**
   * In a step's first callback, the run as it is at the step's start: esmini calls back while it weighs the triggers,
   * which it does before it steps any action or moves any entity (StoryBoardElement::EvalTriggers before Step).
   */
  private keepStepStartNow(): void {
    if (!this.keepStepStart || this.stepStart) return;
    const entities = this.liveEntities();
    this.stepStart = {
      time: this.library.simulationTime(),
      entities,
      pairs: this.livePairs(entities),
      parameters: this.liveParameters(),
      variables: this.liveVariables(),
    };
  }

  /**
   * esmini names a condition only by its name, which the copies of an imported group share: the one meant is the one
   * whose owner started in the same step, when one did.
   */
  private attributeConditions(events: StoryboardEvent[]): void {
    const started = new Set(events.filter((event) => event.state === 'running').map((event) => event.element));
    // Two copies firing in one step are two firings: each takes a copy the other has not.
    const taken = new Set<MappedElement>();
    for (const event of events) {
      if (event.type !== 'Condition') continue;
      const candidates = this.scenario.map.conditionsNamed(event.name);
      if (candidates.length < 2) continue;
      const owned = candidates.find((candidate) => !taken.has(candidate) && candidate.parent && started.has(candidate.parent.path));
      if (owned) {
        taken.add(owned);
        event.mapped = owned;
        event.element = owned.path;
      }
    }
  }

  /** esmini's messages in `log`, on their source lines; a controller File missed beside its catalog said so, as Run in esmini says it. */
  private loadMessages(log: string): EsminiProblem[] {
    const messages = readEsminiLog(log).messages.map((message) => ({
      ...message,
      text: withCatalogFolderNote(message.text, this.scenario.controllerFiles.references, fs.existsSync),
    }));
    return mapEsminiMessages(messages, this.scenario.flat, this.scenario.main);
  }

  private readLog(): string {
    let fd: number;
    try {
      fd = fs.openSync(this.logFile, 'r');
    } catch {
      return '';
    }
    try {
      const size = fs.fstatSync(fd).size;
      if (size <= this.logOffset) return '';
      const buffer = Buffer.alloc(size - this.logOffset);
      fs.readSync(fd, buffer, 0, buffer.length, this.logOffset);
      this.logOffset = size;
      return buffer.toString('utf8');
    } finally {
      fs.closeSync(fd);
    }
  }

  /** Every entity's state now (at the step's start while held). */
  entities(): EntityState[] {
    return this.held ? this.held.entities : this.liveEntities();
  }

  private liveEntities(): EntityState[] {
    const entities: EntityState[] = [];
    const count = this.library.objectCount();
    for (let index = 0; index < count; index++) {
      const id = this.library.objectId(index);
      const state = this.library.objectState(id);
      if (!state) continue;
      entities.push({ ...state, name: this.library.objectName(id), acceleration: this.library.objectAcceleration(id) });
    }
    return entities;
  }

  /** TTC and gap from each entity to each other. */
  pairs(entities?: EntityState[]): EntityPair[] {
    return this.held ? this.held.pairs : this.livePairs(entities ?? this.liveEntities());
  }

  private livePairs(entities: EntityState[]): EntityPair[] {
    const pairs: EntityPair[] = [];
    for (const from of entities)
      for (const to of entities) {
        if (from.id === to.id) continue;
        pairs.push({
          from: from.name,
          to: to.name,
          gap: this.library.distance(from.id, to.id, true)?.ds,
          ttc: this.library.timeToCollision(from.id, to.id),
        });
      }
    return pairs;
  }

  parameters(): NamedValue[] {
    return this.held ? this.held.parameters : this.liveParameters();
  }

  private liveParameters(): NamedValue[] {
    return this.library.parameterNames().map(({ name, type }) => ({ name, value: this.library.parameterValue(name, type) }));
  }

  variables(): NamedValue[] {
    return this.held ? this.held.variables : this.liveVariables();
  }

  private liveVariables(): NamedValue[] {
    return this.library.variableNames().map(({ name, type }) => ({ name, value: this.library.variableValue(name, type) }));
  }

  /** The elements running now, outermost first. */
  running(): { path: string; type: string; name: string; since: number; mapped: MappedElement | undefined }[] {
    return [...this.states.entries()]
      .filter(([, value]) => value.state === 'running')
      .map(([key, value]) => ({ path: key, type: value.type, name: value.name, since: value.since, mapped: value.mapped }));
  }

  close(): void {
    if (!this.closed) {
      this.closed = true;
      this.library.close();
    }
    this.removeFolder();
  }

  private removeFolder(): void {
    removeRunFolderAt(this.folder);
  }
}

function fileSize(file: string): number {
  try {
    return fs.statSync(file).size;
  } catch {
    return 0;
  }
}
