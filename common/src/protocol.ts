/**
 * The contract between the VS Code client and the language server: the custom requests with their
 * parameters and results, typed for both sides (both bundles import this file).
 */
import { RequestType, WorkspaceEdit } from 'vscode-languageserver-protocol';
import type { LineSegment } from './lineSegments';
import {
  LibraryCollisionsRequest,
  LibraryInsertRequest,
  LibraryModulesRequest,
  NewFromTemplateRequest,
  TemplatesRequest,
} from './libraryProtocol';
import { RunTraceRequest, SceneRequest } from './sceneProtocol';
import type { RunCollision } from './collisions';
import type { TraceRecord } from './trace';

export interface FlattenOptions {
  /** Write (or show) the flattened scenario even when errors were found, skipping what cannot be resolved. */
  force?: boolean;
}

export interface FlattenToTextParams {
  /** A main.xosc, a .mosc or a package folder, as a `file:` or `mosc:` URI. */
  uri: string;
  options?: FlattenOptions;
}

export interface FlattenToFileParams {
  uri: string;
  /** A file system path or a `file:` URI, ending in .xosc. */
  outputPath: string;
  options?: FlattenOptions;
  /** The user agreed to write outside the workspace folders (see WriteResult.needsConfirmation). */
  outsideWorkspace?: boolean;
}

export interface PackParams {
  /** File URIs of a folder, of a main.xosc, or of files to put at the root of a new package. */
  inputs: string[];
  outputPath: string;
  /** Store the road networks, catalogs and other files the scenarios name inside the package. */
  selfContained?: boolean;
}

export interface StructureParams {
  uri: string;
}

export interface ExportForCarlaParams {
  /** A .xosc, a modular main, a .mosc or an unpacked package folder, as a `file:` or `mosc:` URI. */
  uri: string;
  /** A file system path or a `file:` URI, ending in .xosc. */
  outputPath: string;
  /** The user agreed to write outside the workspace folders (see WriteResult.needsConfirmation). */
  outsideWorkspace?: boolean;
}

/** Writes the scenario as OpenSCENARIO 1.0 for ScenarioRunner; the loss report comes back as problems at their source lines. */
export const ExportForCarlaRequest = new RequestType<ExportForCarlaParams, WriteResult, void>('modular2simple/exportForCarla');

/** *Check in CARLA ScenarioRunner*: the scenario exported for ScenarioRunner and loaded by ScenarioRunner's own code, without CARLA. */
export interface CheckInScenarioRunnerParams {
  /** A .xosc, a modular main, a .mosc or an unpacked package folder, as a `file:` or `mosc:` URI (its unsaved text is used). */
  uri: string;
  /** Setting modular2simple.carla.scenarioRunnerPath: the ScenarioRunner folder (scenario_runner.py). */
  scenarioRunnerPath?: string;
  /** Setting modular2simple.carla.python: a Python with ScenarioRunner's requirements (default `python3`). */
  python?: string;
  /** Setting modular2simple.carla.timeLimit: seconds before the check is stopped (default 120). */
  timeLimitSeconds?: number;
}

export interface CheckInScenarioRunnerResult {
  /**
   * `built`: ScenarioRunner loaded the export and built its behaviour tree; `refused`: it raised (the problems say
   * where); `not-exported`: the export refused the scenario; the rest: the check could not run (the message says what to set).
   */
  outcome: 'built' | 'refused' | 'not-exported' | 'no-scenario-runner' | 'no-python' | 'requirements' | 'timeout' | 'failed';
  /** One sentence for the user, saying what to do when the check did not run. */
  message: string;
  /** ScenarioRunner's refusal at the source line of the element it failed on; the export's refusals when not exported. */
  problems: ProblemSummary[];
  /** ScenarioRunner's warnings and the harness's output, for the output channel. */
  log: string;
  /** The command run (program and arguments), when one was. */
  command?: string[];
}

export const CheckInScenarioRunnerRequest = new RequestType<CheckInScenarioRunnerParams, CheckInScenarioRunnerResult, void>(
  'modular2simple/checkInScenarioRunner',
);

/** The editor command that exports a scenario for CARLA's ScenarioRunner (a quick fix of a CARLA finding offers it). */
export const EXPORT_FOR_CARLA_COMMAND = 'modular2simple.exportForCarla';

/** The custom requests; their method names are also advertised in `capabilities.experimental.requests`. */
export const FlattenToTextRequest = new RequestType<FlattenToTextParams, FlattenTextResult, void>('modular2simple/flattenToText');
export const FlattenToFileRequest = new RequestType<FlattenToFileParams, WriteResult, void>('modular2simple/flattenToFile');
export const PackRequest = new RequestType<PackParams, WriteResult, void>('modular2simple/pack');
/** The reference graph for the Show Structure view; null when the URI is no scenario. */
export const StructureRequest = new RequestType<StructureParams, StructureNode | null, void>('modular2simple/structure');

/** Run in esmini: flattens the editor's text, runs it headless and answers with its messages on source lines and the CSV path. */
export const RunEsminiRequest = new RequestType<RunEsminiParams, RunEsminiResult, void>('modular2simple/runEsmini');

/** The live preview: the flattened text of a scenario as the editor has it, and where it shows each line of that scenario. */
export interface PreviewParams {
  /** A `main.xosc`, a package (`.mosc` or unpacked folder) or any scenario file. */
  uri: string;
}

export interface PreviewResult {
  /** The flattened scenario; null when errors prevent it. */
  text: string | null;
  problems: ProblemSummary[];
  /** Where the text shows each line of the file itself (empty when there is no text), from the flattener's insertion records. */
  lines: LineSegment[];
}

export const PreviewRequest = new RequestType<PreviewParams, PreviewResult, void>('modular2simple/preview');

/** *New Modular Scenario…*: the text of a main scenario with an ego on a road network (the client asks the questions and writes the file). */
export interface NewScenarioParams {
  /** Where the new scenario will be written: a `file:` URI or a path, ending in .xosc. */
  scenario: string;
  /** The OpenDRIVE road network: a `file:` URI or a path. */
  roadNetwork: string;
}

export interface NewScenarioResult {
  text: string;
  /** The road network's path as the scenario names it, relative to the scenario's folder. */
  roadFile: string;
  /** Where the ego stands: a lane that exists on the road network. */
  ego: { roadId: string; laneId: number; s: number };
}

export const NewScenarioRequest = new RequestType<NewScenarioParams, NewScenarioResult, void>('modular2simple/newScenario');

/** One attribute of a group that *Extract to a simple scenario* may list in `parameterAttributes`. */
export interface ExtractGroupChoice {
  /** Stable for one text of the document: the element's place in the group and the attribute's name. */
  id: string;
  /** `Element.attribute`. */
  label: string;
  value: string;
  /** Proposed by default (a number, an entity reference or an enumeration value). */
  suggested: boolean;
}

/** *Extract to a simple scenario*: the group at `position` of `uri`, with `attributes` (choice ids) listed; the suggested ones when absent. */
export interface ExtractGroupParams {
  uri: string;
  position: { line: number; character: number };
  attributes?: string[];
}

export interface ExtractGroupResult {
  /** Creates the simple scenario and replaces the group by a ScenarioReference (documentChanges). */
  edit: WorkspaceEdit;
  /** The simple scenario's URI. */
  uri: string;
  /** The attributes listed, as `Element.attribute`. */
  parameters: string[];
}

export const ExtractGroupRequest = new RequestType<ExtractGroupParams, ExtractGroupResult, void>('modular2simple/extractGroup');

/** The client command a code action invokes so the user can choose the attributes first (VS Code). */
export const EXTRACT_GROUP_COMMAND = 'modular2simple.extractToSimpleScenario';

export interface ExtractGroupCommandArguments {
  uri: string;
  position: { line: number; character: number };
  choices: ExtractGroupChoice[];
}

export const CUSTOM_REQUESTS = [
  FlattenToTextRequest.method,
  FlattenToFileRequest.method,
  PackRequest.method,
  StructureRequest.method,
  SceneRequest.method,
  RunTraceRequest.method,
  RunEsminiRequest.method,
  PreviewRequest.method,
  NewScenarioRequest.method,
  ExtractGroupRequest.method,
  ExportForCarlaRequest.method,
  CheckInScenarioRunnerRequest.method,
  LibraryModulesRequest.method,
  LibraryInsertRequest.method,
  LibraryCollisionsRequest.method,
  TemplatesRequest.method,
  NewFromTemplateRequest.method,
];

/** URI scheme of files inside a `.mosc`: `mosc:/abs/path/pkg.mosc/inner.mosc/main.xosc`. */
export const PACKAGE_SCHEME = 'mosc';

export interface ProblemSummary {
  uri: string;
  /** Zero-based, as LSP. */
  line: number;
  character: number;
  severity: 'error' | 'warning' | 'information' | 'hint';
  message: string;
  hint?: string;
  /** The problem's code (server/src/core/problems.ts), what a client tells problems apart by. */
  code?: string;
  /** Where the problem's range ends (zero-based), when the server knows it; else it covers its line from `character`. */
  end?: { line: number; character: number };
}

export interface FlattenTextResult {
  text: string | null;
  problems: ProblemSummary[];
}

export interface WriteResult {
  written: string | null;
  problems: ProblemSummary[];
  /**
   * Set when nothing was written because the user must agree first: `outsideWorkspace` means the
   * output lies outside the workspace folders; send the request again with `outsideWorkspace: true`.
   */
  needsConfirmation?: 'outsideWorkspace';
}

export interface StructureNode {
  kind: 'main' | 'package' | 'scenario' | 'group' | 'reference' | 'missing';
  label: string;
  detail?: string;
  uri?: string;
  line?: number;
  character?: number;
  children: StructureNode[];
}

export interface RunEsminiParams {
  /** The scenario to run: a main.xosc, any plain .xosc, a .mosc or a file inside one (its unsaved text is used). */
  uri: string;
  /** Setting modular2simple.esmini.path: the program or its folder; PATH when empty. Relative to the first workspace folder. */
  esminiPath?: string;
  /** Setting modular2simple.esmini.roadPath: extra folders for road files and catalogs. */
  roadPath?: string[];
  /** Simulated seconds (default 30). */
  duration?: number;
  /** *Run Anyway*: run whatever can be flattened despite the scenario's errors (listed in `flattenProblems`), as `run --force` does. */
  force?: boolean;
}

/** One esmini message on the source line it comes from (zero-based, as LSP). */
export interface EsminiProblemSummary {
  uri: string;
  range: { start: { line: number; character: number }; end: { line: number; character: number } };
  severity: 'error' | 'warning';
  message: string;
  /** How often esmini printed it. */
  count: number;
  /** Simulated time printed with it; absent while loading. */
  time?: number;
  /** False when nothing in the scenario matched, so it sits on the first line of the file run. */
  located: boolean;
  note?: string;
}

export interface RunEsminiResult {
  /** ok: esmini ran without error; errors: it reported some; not-flattened; no-esmini; failed; cancelled. */
  outcome: 'ok' | 'errors' | 'not-flattened' | 'no-esmini' | 'failed' | 'cancelled';
  /** One line for the user (for no-esmini: how to get it). */
  message: string;
  /** The file that was run (the uri asked for, or the main.xosc of a package). */
  uri: string;
  problems: EsminiProblemSummary[];
  flattenProblems: ProblemSummary[];
  /**
   * What esmini runs otherwise than written, by the esmini profile (a condition it never fires), whatever the simulator
   * setting; empty when the flattening already checked for esmini (then they are among `flattenProblems`).
   */
  esminiFindings: ProblemSummary[];
  /** With outcome not-flattened: only the scenario's errors stopped it, so the same request with `force` runs it. */
  forcible?: boolean;
  /** esmini's whole output. */
  log: string;
  /** Every storyboard transition and condition firing esmini's log reports, as `run --trace` records (absolute paths). */
  trace?: TraceRecord[];
  /**
   * esmini's CSV log (`--csv_logger`, on the server's disk): 6 header lines, the column line
   * (`Index [-], TimeStamp [s], #1 Entity_Name [-], ...`, 31 columns per entity), one row per step.
   * Drop rows whose TimeStamp exceeds `duration`. It stays until the next run of the same file.
   */
  csvFile?: string;
  /** Where two entities' bounding boxes began to overlap (s; esmini's collision detection), but for the overlaps the scenario means. */
  collisions?: RunCollision[];
  /** The flattened scenario as handed to esmini (with the added time limit). */
  scenarioFile?: string;
  /** For a distribution file: the ScenarioFile (a .xosc) its concrete scenario was made from, whose roads the run is drawn on. */
  scenarioOf?: string;
  duration: number;
  timeStep: number;
  seed: number;
  simulatedTime?: number;
  wallMs: number;
  esmini?: string;
  args?: string[];
  /** What esmini said about its own road files and 3D models (the esmini source that prints it, and why it is harmless): information only. */
  remarks?: EsminiRemarkSummary[];
  /**
   * The road file: as written, the file given to esmini (the one the bird's-eye view draws) or the package entry whose copy
   * it was given (a road packed with the scenario), and the one esmini's log says it loaded.
   */
  roadFile?: { filepath: string; resolved?: string; packaged?: string; loaded?: string };
}

/** A message esmini prints about its own files, never about the scenario (server/src/esmini/log.ts). */
export interface EsminiRemarkSummary {
  message: string;
  count: number;
  origin: string;
  why: string;
}
