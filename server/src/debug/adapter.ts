import {
  Breakpoint,
  BreakpointEvent,
  DebugSession,
  Event,
  InitializedEvent,
  OutputEvent,
  Scope,
  Source,
  StackFrame,
  StoppedEvent,
  TerminatedEvent,
  Thread,
} from '@vscode/debugadapter';
import { DebugProtocol } from '@vscode/debugprotocol';
import * as fs from 'node:fs';
import * as path from 'node:path';
import type { Writable } from 'node:stream';
import { DEBUG_STATE_EVENT, DebugState } from '../../../common/src/debugState';
import { Flattener } from '../core/flatten';
import { ImportPlace, MappedElement } from '../core/flatten/storyboardMap';
import { Problem } from '../core/problems';
import { roadFolders } from '../core/semantics/roadFiles';
import { childRef, diskRef, displayRef, ScenarioStore, SourceRef, splitScenarioPath } from '../core/sources';
import { EsminiLibraryError } from '../esmini/library';
import { EsminiProblem } from '../esmini/messages';
import { isEsminiSeed, RUN_DEFAULTS } from '../esmini/run';
import { EntityState, prepareScenario, Simulation, SimulationLoadError, SimulationOptions, StoryboardEvent } from './simulation';
import { STORYBOARD_EVENT, type StoryboardEventBody } from '../../../common/src/trace';
import { describeEvent, traceRecord } from './trace';
import { type SessionPage, type SessionProgress } from './progressPage';
import {
  evaluateWatch,
  hitConditionMet,
  settled,
  shownFixed,
  shownValue,
  timeBreakpoint,
  WatchContext,
  WatchError,
  WatchValue,
} from './watchExpression';

/*
 * The Debug Adapter Protocol over a Simulation (simulation.ts): breakpoints on storyboard element lines, conditions
 * and hit counts, time breakpoints, stepping by simulation step or storyboard transition. It runs in a process of its
 * own (dist/debugAdapter.js), so that esmini crashing ends the session and nothing else.
 */

/** The launch configuration (package.json `debuggers`, docs/debugging.md). */
export interface ScenarioLaunchArguments extends DebugProtocol.LaunchRequestArguments {
  /** A `.xosc`, a `.mosc`, or a folder holding a main.xosc. */
  program: string;
  timeStep?: number;
  duration?: number;
  seed?: number;
  roadPath?: string[];
  scenarioPath?: string[];
  esminiLibrary?: string;
  /** Base of relative paths; the program's folder by default. */
  cwd?: string;
  stopOnEntry?: boolean;
  force?: boolean;
}

const THREAD_ID = 1;

/** Where the session says how far it got, for its supervisor to tell after a crash (supervisor.ts); nowhere by default. */
let reportProgress: ((progress: SessionProgress) => void) | undefined;
/** The page shared with the supervisor: each step's count goes there for the same, and pause requests come from there (progressPage.ts). */
let sessionPage: SessionPage | undefined;
export function reportProgressTo(sink: ((progress: SessionProgress) => void) | undefined, page?: SessionPage): void {
  reportProgress = sink;
  sessionPage = page;
}
/** While running, the bird's-eye view gets the entities at most this often (wall ms): enough to watch them move. */
const STATE_INTERVAL_MS = 100;
/** Wall ms of stepping between two turns of the event loop, where requests are read (a pause sooner, through the supervisor's page). */
const SLICE_MS = 15;
const ELEMENT_KINDS = 'Story, Act, ManeuverGroup, Maneuver, Event, Action or Condition';

interface LineBreakpoint {
  id: number;
  line: number;
  condition?: string;
  hitCondition?: string;
  hits: number;
  elements: MappedElement[];
}

interface FunctionBreakpoint {
  id: number;
  /** Simulated seconds, or an element name. */
  time?: number;
  name?: string;
  condition?: string;
  hitCondition?: string;
  hits: number;
  done: boolean;
}

type RunMode = 'continue' | 'step' | 'next' | 'stepOut';

interface Stop {
  reason: string;
  description: string;
  /** The element the stop is about: frame 0. */
  element?: MappedElement;
  /** For a breakpoint on a ManeuverGroup that imports the element: that group, shown as frame 0 (the breakpoint's line). */
  importedAt?: ImportPlace;
  event?: StoryboardEvent;
  /** Conditions that fired in the stopping step, for "why it fired". */
  firings: StoryboardEvent[];
  breakpointIds: number[];
}

/** The main file an input names: a package's or a folder's main.xosc, or the file itself. */
function mainRef(input: string): SourceRef {
  if (fs.existsSync(input) && fs.statSync(input).isDirectory()) return diskRef(path.join(input, 'main.xosc'));
  return input.toLowerCase().endsWith('.mosc') ? childRef(diskRef(input), 'main.xosc') : diskRef(input);
}

function entityFields(entity: EntityState): Record<string, number> {
  return {
    x: entity.x,
    y: entity.y,
    z: entity.z,
    h: entity.h,
    heading: entity.h,
    road: entity.roadId,
    lane: entity.laneId,
    laneOffset: entity.laneOffset,
    s: entity.s,
    t: entity.t,
    speed: entity.speed,
    acceleration: entity.acceleration,
  };
}

export class ScenarioDebugSession extends DebugSession {
  private launchArgs: ScenarioLaunchArguments | undefined;
  private simulation: Simulation | undefined;
  private lineBreakpoints = new Map<string, LineBreakpoint[]>();
  private functionBreakpoints: FunctionBreakpoint[] = [];
  private nextBreakpointId = 1;
  private configured: () => void = () => undefined;
  private readonly configurationDone = new Promise<void>((resolve) => (this.configured = resolve));
  private pauseRequested = false;
  private running = false;
  private stopped: Stop | undefined;
  private frames: { place: Pick<MappedElement, 'source' | 'range'> | undefined; label: string }[] = [];
  private variableHandles = new Map<number, () => DebugProtocol.Variable[]>();
  /** The files inside a package that a frame or an output line named, by the source reference given each (1, 2, ...). */
  private packagedSources = new Map<number, SourceRef>();
  private terminated = false;
  private lastStateAt = 0;
  /** The run of the scenario: 1 from the launch, one more at each restart (StoryboardEventBody.run). */
  private runNumber = 0;
  /** The stream the protocol is written to (stdout, a pipe, as the editor or the supervisor starts the session). */
  private protocolOut: Partial<Pick<Writable, 'cork' | 'uncork'>> | undefined;

  override start(inStream: NodeJS.ReadableStream, outStream: NodeJS.WritableStream): void {
    this.protocolOut = outStream as Partial<Writable>;
    super.start(inStream, outStream);
  }

  constructor() {
    super();
    this.setDebuggerLinesStartAt1(false);
    this.setDebuggerColumnsStartAt1(false);
  }

  protected override initializeRequest(response: DebugProtocol.InitializeResponse): void {
    response.body = {
      supportsConfigurationDoneRequest: true,
      supportsConditionalBreakpoints: true,
      supportsHitConditionalBreakpoints: true,
      supportsFunctionBreakpoints: true,
      supportsEvaluateForHovers: true,
      supportsRestartRequest: true,
      supportsTerminateRequest: true,
    };
    this.sendResponse(response);
  }

  protected override configurationDoneRequest(response: DebugProtocol.ConfigurationDoneResponse): void {
    this.configured();
    this.sendResponse(response);
  }

  protected override launchRequest(response: DebugProtocol.LaunchResponse, args: ScenarioLaunchArguments): void {
    this.guard(response, async () => {
      this.launchArgs = args;
      if (!(await this.load(response))) return;
      this.sendEvent(new InitializedEvent());
      await this.configurationDone;
      this.sendResponse(response);
      this.begin();
    });
  }

  /** Restart (VS Code's restart button too, the session keeping its id): a new run of the scenario, numbered for the views. */
  protected override restartRequest(response: DebugProtocol.RestartResponse, args: DebugProtocol.RestartArguments): void {
    this.guard(response, async () => {
      // VS Code sends the launch configuration as it reads it now: an edited launch.json applies to the new run.
      const relaunch = args?.arguments as Partial<ScenarioLaunchArguments> | undefined;
      if (relaunch && typeof relaunch.program === 'string') this.launchArgs = relaunch as ScenarioLaunchArguments;
      this.simulation?.close();
      this.simulation = undefined;
      this.running = false;
      if (!(await this.load(response))) return;
      this.sendResponse(response);
      this.begin();
    });
  }

  /** Flattens and loads the scenario; on failure answers `response` with the reason, ends the session, and says false. */
  private async load(response: DebugProtocol.Response): Promise<boolean> {
    const args = this.launchArgs;
    if (!args || typeof args.program !== 'string' || !args.program) {
      this.fail(response, 'the launch configuration names no program: a .xosc, a .mosc or a folder with a main.xosc');
      return false;
    }
    const base = args.cwd ?? path.dirname(path.resolve(args.program));
    const program = path.resolve(base, args.program);
    if (!fs.existsSync(program)) {
      this.fail(response, `${program}: no such file or folder`);
      return false;
    }
    const seed: unknown = args.seed;
    if (seed !== undefined && !isEsminiSeed(seed)) {
      // As run --seed: esmini reads the seed into an unsigned int.
      this.fail(
        response,
        `the launch configuration's seed takes a whole number from 0 to ${RUN_DEFAULTS.maxSeed}, not ${JSON.stringify(seed)}`,
      );
      return false;
    }
    const options: SimulationOptions = {
      timeStep: args.timeStep,
      duration: args.duration,
      seed: args.seed,
      roadPath: args.roadPath,
      base,
      esminiLibrary: args.esminiLibrary,
      force: args.force,
      onCallback: reportProgress && ((time, what) => reportProgress?.({ time, what })),
      stepCounter: sessionPage,
    };
    const store = new ScenarioStore({
      scenarioPath: [...(args.scenarioPath ?? []), ...splitScenarioPath(process.env.SCENARIO_PATH)],
      // esmini is handed the road folders as --path, where it finds catalogs too: so does the check before the run.
      catalogPath: roadFolders(args.roadPath, base),
      root: fs.statSync(program).isDirectory() ? program : path.dirname(program),
      workingDirectory: base,
    });
    try {
      reportProgress?.({ time: 0, what: 'loading the scenario' });
      const prepared = await prepareScenario(new Flattener(store), mainRef(program), options);
      for (const problem of prepared.flattenProblems) if (problem.severity === 'error') this.problemOutput(problem);
      const simulation = new Simulation(prepared, options);
      const started = simulation.start();
      // What esmini said loading it (a controller File it missed): printed, as a run prints it.
      for (const problem of simulation.loadProblems) this.problemOutput(problem);
      this.simulation = simulation;
      this.runNumber++;
      for (const function_ of this.functionBreakpoints) ((function_.done = false), (function_.hits = 0));
      for (const list of this.lineBreakpoints.values()) for (const breakpoint of list) breakpoint.hits = 0;
      this.reverify();
      this.output(
        `esmini's library ${path.basename(args.esminiLibrary ?? 'libesminiLib.so')}: ${displayRef(prepared.main, base)} loaded; step ${simulation.timeStep} s, at most ${simulation.duration} s\n`,
      );
      this.report(started);
      return true;
    } catch (error) {
      if (error instanceof SimulationLoadError || error instanceof EsminiLibraryError) {
        if (error instanceof SimulationLoadError) for (const problem of error.problems) this.problemOutput(problem);
        this.fail(response, error.message);
        return false;
      }
      throw error;
    }
  }

  private begin(): void {
    if (this.launchArgs?.stopOnEntry)
      this.stopWith({ reason: 'entry', description: 'Paused before the first step', firings: [], breakpointIds: [] });
    else this.run('continue');
  }

  private fail(response: DebugProtocol.Response, message: string): void {
    this.output(`${message}\n`, 'stderr');
    this.sendErrorResponse(response, { id: 1001, format: message.replaceAll('{', '(').replaceAll('}', ')'), showUser: true });
    this.end();
  }

  private end(): void {
    if (this.terminated) return;
    this.terminated = true;
    this.running = false;
    // The timeline's last time: where the run ended (its bars drawn to there, not to the run's limit).
    if (this.simulation) this.sendStoryboard([]);
    this.simulation?.close();
    this.simulation = undefined;
    this.sendEvent(new TerminatedEvent());
  }

  /** Runs an async handler; an exception is logged with its stack and answered as an error, never swallowed. */
  private guard(response: DebugProtocol.Response, body: () => Promise<void> | void): void {
    const failed = (error: unknown) => {
      const stack = error instanceof Error ? (error.stack ?? error.message) : String(error);
      process.stderr.write(`modular2simple debug adapter: ${response.command} failed: ${stack}\n`);
      this.output(`internal error in ${response.command}: ${stack}\n`, 'stderr');
      this.sendErrorResponse(response, {
        id: 1002,
        format: `internal error: ${String(error instanceof Error ? error.message : error).replaceAll('{', '(')}`,
        showUser: true,
      });
    };
    try {
      const result = body();
      if (result) result.catch(failed);
    } catch (error) {
      failed(error);
    }
  }

  // ---- breakpoints

  private sourceKey(ref: SourceRef): string {
    return ref.entries.length === 0 ? path.resolve(ref.disk) : displayRef(ref, undefined);
  }

  protected override setBreakPointsRequest(
    response: DebugProtocol.SetBreakpointsResponse,
    args: DebugProtocol.SetBreakpointsArguments,
  ): void {
    this.guard(response, () => {
      // A file inside a package is named by its source reference alone by some clients (the path is optional in DAP).
      const packaged = this.packagedSources.get(args.source.sourceReference ?? 0);
      const key = args.source.path
        ? path.resolve(args.source.path)
        : packaged
          ? this.sourceKey(packaged)
          : `#${args.source.sourceReference ?? 0}`;
      const previous = this.lineBreakpoints.get(key) ?? [];
      const list = (args.breakpoints ?? []).map((requested): LineBreakpoint => {
        const line = this.convertClientLineToDebugger(requested.line);
        const kept = previous.find((candidate) => candidate.line === line);
        return {
          id: kept?.id ?? this.nextBreakpointId++,
          line,
          condition: requested.condition,
          hitCondition: requested.hitCondition,
          hits: kept?.hits ?? 0,
          elements: [],
        };
      });
      this.lineBreakpoints.set(key, list);
      response.body = { breakpoints: list.map((breakpoint) => this.verify(key, breakpoint)) };
      this.sendResponse(response);
    });
  }

  private verify(key: string, breakpoint: LineBreakpoint): DebugProtocol.Breakpoint {
    const map = this.simulation?.scenario.map;
    breakpoint.elements = map ? map.atLine((ref) => this.sourceKey(ref) === key, breakpoint.line) : [];
    const result: DebugProtocol.Breakpoint = new Breakpoint(
      breakpoint.elements.length > 0,
      this.convertDebuggerLineToClient(breakpoint.line),
    );
    result.id = breakpoint.id;
    if (!map) result.message = 'the scenario is not loaded yet';
    else if (breakpoint.elements.length === 0) {
      const isFile = (ref: SourceRef) => this.sourceKey(ref) === key;
      const written = map.writtenAt(isFile, breakpoint.line);
      result.message = written
        ? `${written.kind} ${written.name} is not in the scenario being debugged: no reference of ${path.basename(displayRef(map.flat.ref, undefined))} imports it`
        : map.writesIn(isFile)
          ? `no storyboard element starts on this line: a breakpoint stops on the line of a ${ELEMENT_KINDS}`
          : 'this file is not part of the scenario being debugged';
    } else {
      const first = breakpoint.elements[0];
      const copies = breakpoint.elements.length > 1 ? ` (${breakpoint.elements.length} flattened copies)` : '';
      result.message = `${first.kind} ${first.name}${copies}`;
    }
    return result;
  }

  private reverify(): void {
    for (const [key, list] of this.lineBreakpoints)
      for (const breakpoint of list) this.sendEvent(new BreakpointEvent('changed', this.verify(key, breakpoint)));
  }

  protected override setFunctionBreakPointsRequest(
    response: DebugProtocol.SetFunctionBreakpointsResponse,
    args: DebugProtocol.SetFunctionBreakpointsArguments,
  ): void {
    this.guard(response, () => {
      const map = this.simulation?.scenario.map;
      this.functionBreakpoints = args.breakpoints.map((requested) => {
        const time = timeBreakpoint(requested.name);
        return {
          id: this.nextBreakpointId++,
          time,
          name: time === undefined ? requested.name.trim() : undefined,
          condition: requested.condition,
          hitCondition: requested.hitCondition,
          hits: 0,
          done: this.simulation !== undefined && time !== undefined && this.simulation.time >= time - 1e-9,
        };
      });
      response.body = {
        breakpoints: this.functionBreakpoints.map((breakpoint) => {
          const named = breakpoint.name === undefined || !map || map.elements.some((element) => element.name === breakpoint.name);
          const result: DebugProtocol.Breakpoint = { id: breakpoint.id, verified: named };
          result.message =
            breakpoint.time !== undefined
              ? `at ${breakpoint.time} s of simulated time`
              : named
                ? `when ${breakpoint.name} starts`
                : `no storyboard element is named ${breakpoint.name}: write t=5.0 for a time, or an element's name`;
          return result;
        }),
      };
      this.sendResponse(response);
    });
  }

  // ---- running

  protected override continueRequest(response: DebugProtocol.ContinueResponse): void {
    response.body = { allThreadsContinued: true };
    this.resume(response, 'continue');
  }

  /** Step over: run to the next storyboard state change. */
  protected override nextRequest(response: DebugProtocol.NextResponse): void {
    this.resume(response, 'next');
  }

  /** Step into: one simulation step. */
  protected override stepInRequest(response: DebugProtocol.StepInResponse): void {
    this.resume(response, 'step');
  }

  /** Step out: run until the element stopped on ends. */
  protected override stepOutRequest(response: DebugProtocol.StepOutResponse): void {
    this.resume(response, 'stepOut');
  }

  private resume(response: DebugProtocol.Response, mode: RunMode): void {
    this.sendResponse(response);
    this.run(mode);
  }

  protected override pauseRequest(response: DebugProtocol.PauseResponse): void {
    this.sendResponse(response);
    if (this.running) this.pauseRequested = true;
  }

  protected override terminateRequest(response: DebugProtocol.TerminateResponse): void {
    this.sendResponse(response);
    this.end();
  }

  protected override disconnectRequest(response: DebugProtocol.DisconnectResponse): void {
    this.running = false;
    this.simulation?.close();
    this.simulation = undefined;
    this.sendResponse(response);
  }

  private run(mode: RunMode): void {
    const simulation = this.simulation;
    if (!simulation || this.running) return;
    const stepOutOf = mode === 'stepOut' ? this.stopped?.element?.path : undefined;
    this.running = true;
    this.pauseRequested = false;
    this.stopped = undefined;
    // Stopped at a step's start (Simulation.holdStepStart): esmini has made that step already, so one step on is its end.
    const stepEnded = simulation.holding;
    simulation.release();
    // Pause requests the supervisor counted before this run are answered (a pause while stopped does nothing).
    const pausesBefore = sessionPage?.pauseRequests();
    /**
     * Steps between two reads of the clock in a slice: doubled while a read finds the millisecond of the read before, halved
     * when more than one passed, so about one read a millisecond from the run's first slice on.
     */
    let stride = 1;
    const pause = () =>
      this.stopWith({ reason: 'pause', description: `Paused at ${shownFixed(simulation.time)} s`, firings: [], breakpointIds: [] });
    // A pause is read after every step from the supervisor's page.
    const page = sessionPage;
    const pauseCounted = page ? () => page.pauseRequests() !== pausesBefore : () => false;
    const slice = () => {
      if (!this.running || this.simulation !== simulation) return;
      try {
        reportProgress?.({ time: simulation.time, what: 'stepping on from there' });
        if (mode === 'step' && stepEnded)
          return this.stopWith({
            reason: 'step',
            description: `Stepped to ${shownFixed(simulation.time)} s`,
            firings: [],
            breakpointIds: [],
          });
        // Steps in slices of a few milliseconds, so that requests (a change of breakpoints) are read between them; a pause
        // is read after every step from the supervisor's page, else here.
        if (this.pauseRequested) return pause();
        const timed = this.functionBreakpoints.some((breakpoint) => breakpoint.time !== undefined && !breakpoint.done);
        // esmini's state at a step's start is kept only while a stop there may come: it costs esmini calls in each step that reports something.
        simulation.keepStepStart = mode === 'next' || mode === 'stepOut' || this.breaksOnElements();
        let clock = Date.now();
        const until = clock + SLICE_MS;
        let clockAt = simulation.stepsMade + stride;
        // One step a call while each step may stop (Step Into, a time breakpoint), else a stride of steps.
        const oneByOne = mode === 'step' || timed;
        do {
          if (simulation.ended) return this.finished(simulation);
          const events = simulation.stepMany(oneByOne ? 1 : stride, pauseCounted);
          // Most steps report nothing: no breakpoint to weigh unless a time breakpoint is due (bench/debugger.mjs).
          if (events.length > 0 || mode === 'step' || (timed && this.timeBreakpointDue(simulation))) {
            this.report(events);
            const stop = this.breakpointStop(simulation, events) ?? this.stepStop(simulation, events, mode, stepOutOf);
            if (stop) return this.stopWith(stop);
          }
          if (pauseCounted()) return pause();
          if (simulation.stepsMade < clockAt) continue;
          // A read of the clock costs a twentieth of a small scenario's step (docs/benchmarks.md).
          const now = Date.now();
          if (now === clock) stride = Math.min(64, stride * 2);
          else if (now - clock > 1) stride = Math.max(1, stride >> 1);
          clock = now;
          clockAt = simulation.stepsMade + stride;
        } while (clock < until);
        if (Date.now() - this.lastStateAt >= STATE_INTERVAL_MS) this.publishState(simulation, false);
        setImmediate(slice);
      } catch (error) {
        this.running = false;
        const stack = error instanceof Error ? (error.stack ?? error.message) : String(error);
        process.stderr.write(`modular2simple debug adapter: the run failed: ${stack}\n`);
        this.output(`the run failed: ${stack}\n`, 'stderr');
        this.end();
      }
    };
    setImmediate(slice);
  }

  /** Whether a breakpoint may stop on an element's start or a condition (a line breakpoint on one, or an element's name). */
  private breaksOnElements(): boolean {
    for (const list of this.lineBreakpoints.values()) if (list.some((breakpoint) => breakpoint.elements.length > 0)) return true;
    return this.functionBreakpoints.some((breakpoint) => breakpoint.name !== undefined);
  }

  private timeBreakpointDue(simulation: Simulation): boolean {
    let time: number | undefined;
    for (const breakpoint of this.functionBreakpoints)
      if (breakpoint.time !== undefined && !breakpoint.done && (time ??= simulation.time) >= breakpoint.time - 1e-9) return true;
    return false;
  }

  /** The entities and running elements now, for the bird's-eye view (common/src/debugState.ts). */
  private publishState(simulation: Simulation, paused: boolean): void {
    this.lastStateAt = Date.now();
    const state: DebugState = {
      time: simulation.time,
      entities: simulation.entities().map((entity) => ({
        name: entity.name,
        x: entity.x,
        y: entity.y,
        h: entity.h,
        speed: entity.speed,
        length: entity.length,
        width: entity.width,
        centerX: entity.centerOffsetX,
      })),
      running: simulation
        .running()
        .map((element) => ({ name: element.name, path: element.path, type: element.type, since: element.since })),
      paused,
      run: this.runNumber,
    };
    this.sendEvent(new Event(DEBUG_STATE_EVENT, state));
  }

  private finished(simulation: Simulation): void {
    this.running = false;
    this.publishState(simulation, true);
    this.output(`The scenario ended at ${shownFixed(simulation.time)} s\n`);
    this.end();
  }

  private stepStop(
    simulation: Simulation,
    events: readonly StoryboardEvent[],
    mode: RunMode,
    stepOutOf: string | undefined,
  ): Stop | undefined {
    const firings = events.filter((event) => event.type === 'Condition');
    if (mode === 'step') return { reason: 'step', description: `Stepped to ${shownFixed(simulation.time)} s`, firings, breakpointIds: [] };
    const transitions = events.filter((event) => event.type !== 'Condition');
    let stopOn: StoryboardEvent | undefined;
    if (mode === 'next' && transitions.length > 0) stopOn = transitions.find((event) => event.state === 'running') ?? transitions[0];
    else if (mode === 'stepOut' && stepOutOf)
      stopOn = transitions.find((event) => event.element === stepOutOf && event.state !== 'running');
    if (!stopOn) return undefined;
    // At the step's start, where esmini made the transition (Simulation.holdStepStart).
    simulation.holdStepStart();
    return { reason: 'step', description: describeEvent(stopOn), element: stopOn.mapped, event: stopOn, firings, breakpointIds: [] };
  }

  private watchContext(simulation: Simulation): WatchContext {
    let entities: EntityState[] | undefined;
    const all = () => (entities ??= simulation.entities());
    let values: Map<string, WatchValue | undefined> | undefined;
    return {
      time: simulation.time,
      entity: (name) => {
        const entity = all().find((candidate) => candidate.name === name);
        return entity ? entityFields(entity) : undefined;
      },
      parameter: (name) => {
        values ??= new Map([...simulation.parameters(), ...simulation.variables()].map((entry) => [entry.name, entry.value]));
        return values.get(name);
      },
      pair: (measure, from, to) => {
        const pair = simulation.pairs(all()).find((candidate) => candidate.from === from && candidate.to === to);
        return pair?.[measure];
      },
    };
  }

  /** Whether a breakpoint's condition holds and its hit count is reached; a broken condition stops and says why. */
  private shouldStop(
    simulation: Simulation,
    breakpoint: { condition?: string; hitCondition?: string; hits: number },
  ): { stop: boolean; note?: string } {
    if (breakpoint.condition?.trim()) {
      try {
        const value = evaluateWatch(breakpoint.condition, this.watchContext(simulation));
        if (!(typeof value === 'string' ? value === 'true' : Boolean(value))) return { stop: false };
      } catch (error) {
        if (!(error instanceof WatchError)) throw error;
        return { stop: true, note: `the condition '${breakpoint.condition}' cannot be evaluated: ${error.message}` };
      }
    }
    breakpoint.hits++;
    try {
      return { stop: hitConditionMet(breakpoint.hitCondition, breakpoint.hits) };
    } catch (error) {
      if (!(error instanceof WatchError)) throw error;
      return { stop: true, note: error.message };
    }
  }

  private breakpointStop(simulation: Simulation, events: readonly StoryboardEvent[]): Stop | undefined {
    const firings = events.filter((event) => event.type === 'Condition');
    const ids: number[] = [];
    let stopEvent: StoryboardEvent | undefined;
    let stopImportedAt: ImportPlace | undefined;
    const notes: string[] = [];
    const hits: { breakpoint: LineBreakpoint | FunctionBreakpoint; event: StoryboardEvent; importedAt?: ImportPlace }[] = [];
    const map = simulation.scenario.map;
    for (const event of events) {
      if (event.state !== 'running' && event.state !== 'true') continue;
      const candidates = event.type === 'Condition' ? map.conditionsNamed(event.name) : [];
      for (const [key, list] of this.lineBreakpoints)
        for (const breakpoint of list) {
          const mapped = event.mapped;
          if (mapped && breakpoint.elements.includes(mapped)) {
            const place = map.placeAtLine(mapped, (ref) => this.sourceKey(ref) === key, breakpoint.line);
            hits.push({ breakpoint, event, importedAt: place && place !== mapped ? (place as ImportPlace) : undefined });
          } else if (candidates.some((candidate) => breakpoint.elements.includes(candidate))) {
            // A condition esmini names only by name: any copy of it on the breakpoint's line.
            hits.push({ breakpoint, event });
          }
        }
      for (const breakpoint of this.functionBreakpoints)
        if (breakpoint.name !== undefined && breakpoint.name === event.name) hits.push({ breakpoint, event });
    }
    if (hits.length > 0) {
      // Conditions weighed, and the stop made, at the step's start, where esmini started the element (Simulation.holdStepStart).
      simulation.holdStepStart();
      for (const { breakpoint, event, importedAt } of hits) {
        const verdict = this.shouldStop(simulation, breakpoint);
        if (verdict.note) notes.push(verdict.note);
        if (!verdict.stop) continue;
        ids.push(breakpoint.id);
        if (stopEvent) continue;
        stopEvent = event;
        stopImportedAt = importedAt;
      }
      // No stop: esmini's state now again, the step's end.
      if (ids.length === 0) simulation.release();
    }
    for (const breakpoint of this.functionBreakpoints) {
      if (breakpoint.time === undefined || breakpoint.done || simulation.time < breakpoint.time - 1e-9) continue;
      breakpoint.done = true;
      const verdict = this.shouldStop(simulation, breakpoint);
      if (verdict.note) notes.push(verdict.note);
      if (verdict.stop) ids.push(breakpoint.id);
    }
    if (ids.length === 0) return undefined;
    const note = notes.length > 0 ? ` (${notes.join('; ')})` : '';
    if (!stopEvent)
      return { reason: 'function breakpoint', description: `At ${shownFixed(simulation.time)} s${note}`, firings, breakpointIds: ids };
    return {
      reason: 'breakpoint',
      description: `${describeEvent(stopEvent)}${note}`,
      element: stopEvent.mapped,
      importedAt: stopImportedAt,
      event: stopEvent,
      firings,
      breakpointIds: ids,
    };
  }

  private stopWith(stop: Stop): void {
    this.running = false;
    this.stopped = stop;
    if (this.simulation) this.publishState(this.simulation, true);
    this.variableHandles.clear();
    const event = new StoppedEvent(stop.reason, THREAD_ID) as DebugProtocol.StoppedEvent;
    event.body.description = stop.description;
    event.body.text = stop.description;
    event.body.allThreadsStopped = true;
    if (stop.breakpointIds.length > 0) event.body.hitBreakpointIds = stop.breakpointIds;
    this.sendEvent(event);
    // The timeline's cursor goes to the time of the stop.
    this.sendStoryboard([]);
  }

  // ---- output

  private output(text: string, category = 'console', where?: { source: SourceRef; line: number }, data?: unknown): void {
    const event = new OutputEvent(text, category, data) as DebugProtocol.OutputEvent;
    if (where) {
      event.body.source = this.sourceOf(where.source);
      event.body.line = this.convertDebuggerLineToClient(where.line);
    }
    this.sendEvent(event);
  }

  private problemOutput(problem: Problem | EsminiProblem): void {
    const where = `${displayRef(problem.source, undefined)}:${problem.range.start.line + 1}`;
    this.output(`${where}: ${problem.severity}: ${problem.message}\n`, 'stderr', {
      source: problem.source,
      line: problem.range.start.line,
    });
  }

  /**
   * A line in the Debug Console per transition and condition firing, with its time and source line; a condition's
   * carries in `data` when esmini reported it (the monotonic clock's ms), from which a client measures the pause latency.
   */
  private report(events: readonly StoryboardEvent[]): void {
    if (events.length === 0) return;
    // A step's messages in one write, not one each: a write to the pipe is a system call that wakes the reader.
    this.protocolOut?.cork?.();
    try {
      for (const event of events) {
        const where = event.mapped ? { source: event.mapped.source, line: event.mapped.range.start.line } : undefined;
        const data = event.reportedAtMs === undefined ? undefined : { element: event.element, reportedAtMs: event.reportedAtMs };
        this.output(`[${shownFixed(event.time)}] ${describeEvent(event)}\n`, 'console', where, data);
      }
      // The storyboard timeline follows the session: the same records as run --trace, files as absolute paths.
      this.sendStoryboard(events);
    } finally {
      this.protocolOut?.uncork?.();
    }
  }

  private sendStoryboard(events: readonly StoryboardEvent[]): void {
    const body: StoryboardEventBody = {
      records: events.map((event) => traceRecord(event, undefined, this.simulation?.scenario.map)),
      time: settled(this.simulation?.time ?? 0),
      run: this.runNumber,
    };
    this.sendEvent(new Event(STORYBOARD_EVENT, body));
  }

  private sourceOf(ref: SourceRef): Source {
    if (ref.entries.length === 0) return new Source(path.basename(ref.disk), this.convertDebuggerPathToClient(ref.disk));
    // A file inside a .mosc: its text served by the adapter.
    const key = displayRef(ref, undefined);
    let id = [...this.packagedSources].find(([, known]) => displayRef(known, undefined) === key)?.[0];
    if (id === undefined) {
      id = this.packagedSources.size + 1;
      this.packagedSources.set(id, ref);
    }
    return new Source(ref.entries[ref.entries.length - 1], key, id);
  }

  protected override sourceRequest(response: DebugProtocol.SourceResponse, args: DebugProtocol.SourceArguments): void {
    const ref = this.packagedSources.get(args.sourceReference);
    const text = ref && this.simulation?.scenario.map.textOf(ref);
    if (text === undefined) {
      const format = ref
        ? `the text of ${displayRef(ref, undefined)} is not known to this session: open the package's file from a stack frame of a running session`
        : `no source has the reference ${args.sourceReference}`;
      return this.sendErrorResponse(response, { id: 1003, format, showUser: true });
    }
    response.body = { content: text, mimeType: 'text/xml' };
    this.sendResponse(response);
  }

  // ---- inspection

  protected override threadsRequest(response: DebugProtocol.ThreadsResponse): void {
    response.body = { threads: [new Thread(THREAD_ID, 'Storyboard')] };
    this.sendResponse(response);
  }

  protected override stackTraceRequest(response: DebugProtocol.StackTraceResponse): void {
    this.guard(response, () => {
      const simulation = this.simulation;
      this.frames = [];
      const seen = new Set<string>();
      const push = (place: Pick<MappedElement, 'source' | 'range'> | undefined, label: string, key: string) => {
        if (seen.has(key)) return;
        seen.add(key);
        this.frames.push({ place, label });
      };
      const stopped = this.stopped;
      const label = (element: MappedElement) =>
        `${element.kind} ${element.name}${element === stopped?.element && stopped.event ? ` (${stopped.event.state})` : ''}`;
      // A stop on the line of a group that imports the element shows that line first, as its breakpoint is there; the
      // copy itself, where its source writes it, is then among the running elements.
      const shownLevel = stopped?.importedAt ? (stopped.element?.importedAt ?? []).indexOf(stopped.importedAt) : -1;
      for (let element = stopped?.element; element; element = element.parent) {
        const fromLevel = element === stopped?.element && shownLevel >= 0 ? shownLevel : -1;
        if (fromLevel < 0) push(element, label(element), element.path);
        // A copy of an imported group: each group whose ScenarioReference imports it, as a call's callers.
        (element.importedAt ?? []).forEach((place, level) => {
          const key = `${element.path} imported at ${level}`;
          if (level === fromLevel) push(place, label(element), key);
          else if (level > fromLevel) push(place, `ManeuverGroup ${place.name} (imports ${place.imports})`, key);
        });
      }
      if (simulation) {
        // Then every other running element, the deepest first: the storyboard path of what runs.
        const running = simulation
          .running()
          .sort((a, b) => b.path.split('::').length - a.path.split('::').length || a.path.localeCompare(b.path));
        for (const item of running) push(item.mapped, `${item.type} ${item.name} (running since ${shownFixed(item.since)} s)`, item.path);
      }
      if (this.frames.length === 0) this.frames.push({ place: undefined, label: `Storyboard at ${shownFixed(simulation?.time)} s` });
      const frames = this.frames.map((frame, index) => {
        const source = frame.place ? this.sourceOf(frame.place.source) : undefined;
        const line = frame.place ? this.convertDebuggerLineToClient(frame.place.range.start.line) : 0;
        const column = frame.place ? this.convertDebuggerColumnToClient(frame.place.range.start.character) : 0;
        return new StackFrame(index, frame.label, source, line, column);
      });
      response.body = { stackFrames: frames, totalFrames: frames.length };
      this.sendResponse(response);
    });
  }

  private handle(children: () => DebugProtocol.Variable[]): number {
    const id = this.variableHandles.size + 1;
    this.variableHandles.set(id, children);
    return id;
  }

  protected override scopesRequest(response: DebugProtocol.ScopesResponse): void {
    this.guard(response, () => {
      const simulation = this.simulation;
      const scopes: DebugProtocol.Scope[] = [];
      if (simulation) {
        // Entities first: VS Code opens the first scope of a stop.
        scopes.push(
          new Scope(
            'Entities',
            this.handle(() => this.entityVariables(simulation)),
          ),
        );
        const why = this.whyItFired();
        if (why.length > 0)
          scopes.push(
            new Scope(
              'Why it fired',
              this.handle(() => why),
            ),
          );
        scopes.push(
          new Scope(
            'Parameters',
            this.handle(() => valueVariables(simulation.parameters())),
          ),
        );
        scopes.push(
          new Scope(
            'Variables',
            this.handle(() => valueVariables(simulation.variables())),
          ),
        );
        scopes.push(
          new Scope(
            'Gaps and TTC',
            this.handle(() => this.pairVariables(simulation)),
            true,
          ),
        );
      }
      response.body = { scopes };
      this.sendResponse(response);
    });
  }

  /** The conditions that fired in the stopping step, each with its rule, threshold and what esmini measured. */
  private whyItFired(): DebugProtocol.Variable[] {
    const stop = this.stopped;
    if (!stop) return [];
    const firings = stop.event?.type === 'Condition' ? [stop.event] : stop.firings;
    return firings.map((firing) => {
      const spec = firing.mapped?.condition;
      const reason = firing.reason;
      const fields: DebugProtocol.Variable[] = [
        { name: 'condition', value: firing.element, variablesReference: 0 },
        { name: 'type', value: spec?.type ?? '—', variablesReference: 0 },
        { name: 'rule', value: spec?.rule ?? reason?.rule ?? '—', variablesReference: 0 },
        {
          name: 'threshold',
          value: reason?.threshold !== undefined ? String(reason.threshold) : (spec?.value ?? '—'),
          variablesReference: 0,
        },
        {
          name: 'measured',
          value: reason?.measured !== undefined ? `${reason.measured}${reason.quantity ? ` (${reason.quantity})` : ''}` : '—',
          variablesReference: 0,
        },
        { name: 'esmini', value: reason?.detail ?? '—', variablesReference: 0 },
        { name: 'time', value: shownFixed(firing.time, 3), variablesReference: 0 },
      ];
      const summary =
        reason?.measured !== undefined
          ? `${reason.quantity}: ${reason.measured} ${reason.rule} ${reason.threshold}`
          : (reason?.detail ?? 'true');
      return { name: firing.name, value: summary, variablesReference: this.handle(() => fields) };
    });
  }

  private entityVariables(simulation: Simulation): DebugProtocol.Variable[] {
    return simulation.entities().map((entity) => {
      const fields = entityFields(entity);
      const children = Object.entries(fields)
        .filter(([name]) => name !== 'heading')
        .map(([name, value]) => ({ name, value: Number.isInteger(value) ? String(value) : shownFixed(value, 3), variablesReference: 0 }));
      return {
        name: entity.name,
        value: `x ${shownFixed(entity.x)}, y ${shownFixed(entity.y)}, speed ${shownFixed(entity.speed)} m/s, lane ${entity.laneId}`,
        variablesReference: this.handle(() => children),
        evaluateName: entity.name,
      };
    });
  }

  private pairVariables(simulation: Simulation): DebugProtocol.Variable[] {
    return simulation.pairs().map((pair) => ({
      name: `${pair.from} → ${pair.to}`,
      value: `gap ${shownFixed(pair.gap)} m, TTC ${pair.ttc === undefined ? 'none' : `${shownFixed(pair.ttc)} s`}`,
      variablesReference: 0,
      evaluateName: `gap(${pair.from}, ${pair.to})`,
    }));
  }

  protected override variablesRequest(response: DebugProtocol.VariablesResponse, args: DebugProtocol.VariablesArguments): void {
    this.guard(response, () => {
      response.body = { variables: this.variableHandles.get(args.variablesReference)?.() ?? [] };
      this.sendResponse(response);
    });
  }

  protected override evaluateRequest(response: DebugProtocol.EvaluateResponse, args: DebugProtocol.EvaluateArguments): void {
    this.guard(response, () => {
      const simulation = this.simulation;
      if (!simulation) return this.sendErrorResponse(response, { id: 1004, format: 'no scenario is running', showUser: false });
      const expression = args.expression.trim();
      const entity = simulation.entities().find((candidate) => candidate.name === expression);
      if (entity) {
        const fields = entityFields(entity);
        response.body = {
          result: `x ${shownFixed(entity.x)}, y ${shownFixed(entity.y)}, speed ${shownFixed(entity.speed)} m/s`,
          variablesReference: this.handle(() =>
            Object.entries(fields).map(([name, value]) => ({ name, value: String(value), variablesReference: 0 })),
          ),
        };
        return this.sendResponse(response);
      }
      try {
        const value = evaluateWatch(expression, this.watchContext(simulation));
        response.body = {
          result: shownValue(value),
          variablesReference: 0,
        };
        this.sendResponse(response);
      } catch (error) {
        if (!(error instanceof WatchError)) throw error;
        this.sendErrorResponse(response, { id: 1005, format: error.message.replaceAll('{', '('), showUser: args.context === 'repl' });
      }
    });
  }
}

function valueVariables(values: { name: string; value: string | number | boolean | undefined }[]): DebugProtocol.Variable[] {
  return values.map((entry) => ({
    name: `$${entry.name}`,
    value: entry.value === undefined ? '—' : String(entry.value),
    variablesReference: 0,
    evaluateName: `$${entry.name}`,
  }));
}
