import { SKIPPED_BY_FORCE } from '../diagnostics';
import { OverridableAttribute, OverridePlan } from '../keys';
import { ManeuverGroupInfo, ManeuverGroupReferenceInfo, ScenarioModel, ScenarioReferenceInfo } from '../model';
import { Problem, ProblemCode } from '../problems';
import { SchemaVersionSetting } from '../schema/version';
import { Declaration, DocumentSemantics } from '../semantics';
import { refId, Resolution, SourceRef } from '../sources';
import { XmlElement } from '../xml';

/** Problems that the original tool ignored silently: what `--force` skips (reported as skipped, not as errors). */
export const OVERRIDE_PROBLEM_CODES: ReadonlySet<ProblemCode> = SKIPPED_BY_FORCE;

/**
 * Problems of a referenced file that concern that file alone and not a scenario importing its groups: its own road file
 * (`road-file`), since an imported group never carries its source's RoadNetwork and the output runs on the main file's.
 * Reported when that file is checked itself; they neither stop a flattening nor count among the main's problems.
 */
export const SOURCE_ONLY_PROBLEM_CODES: ReadonlySet<ProblemCode> = new Set<ProblemCode>(['road-file']);

/**
 * Whether a problem of a referenced file (`source`) concerns a scenario importing the groups `groupNames` from it. Not
 * a SOURCE_ONLY_PROBLEM_CODES one, nor a simulator's finding in that file itself outside the imported groups: the
 * simulator runs the importing scenario's FileHeader, road, entities and storyboard, never the source's (a library
 * module's `revMinor="1"` is no CARLA error in a 1.0 main). Findings in its catalogs and the files it imports are
 * judged where they are imported.
 */
export function concernsImporter(problem: Problem, source: FlatSource, groupNames: readonly string[]): boolean {
  if (SOURCE_ONLY_PROBLEM_CODES.has(problem.code)) return false;
  const original = source.original;
  if (problem.code !== 'simulator' || !original || refId(problem.source) !== refId(source.ref)) return true;
  const offset = original.document.lines.offsetAt(problem.range.start);
  return original.groups.some((group) => groupNames.includes(group.name) && group.element.start <= offset && offset < group.element.end);
}

export interface LinkedGroupReference {
  info: ManeuverGroupReferenceInfo;
  /** The group in the source (the flattened package for a `.mosc`) that the name selects. */
  target: ManeuverGroupInfo | undefined;
  overridable: OverridableAttribute[];
  plan: OverridePlan | undefined;
}

export interface LinkedReference {
  info: ScenarioReferenceInfo;
  resolution: Resolution;
  /** The referenced file, flattened when it is a package or itself holds references. */
  source: FlatSource | undefined;
  groups: LinkedGroupReference[];
  /** The files from this reference back to itself, when it closes a cycle. */
  cycle: SourceRef[] | undefined;
}

/** A group that flattening put into the output, and where it came from. */
export interface Insertion {
  reference: ManeuverGroupReferenceInfo;
  outerGroup: ManeuverGroupInfo;
  link: LinkedReference;
  group: LinkedGroupReference;
  /** Offsets of the copy in the flattened text. */
  start: number;
  end: number;
  /** Offsets of the outer group it replaced (with its siblings) in the original text. */
  replacedStart: number;
  replacedEnd: number;
}

/** One file read and, when it holds references, flattened (with `parameterAttributes` kept). */
export interface FlatSource {
  ref: SourceRef;
  /** The file as read; undefined when it could not be read. */
  original: ScenarioModel | undefined;
  links: LinkedReference[];
  /** The flattened text; undefined when an error here or below prevents flattening. */
  text: string | undefined;
  model: ScenarioModel | undefined;
  insertions: Insertion[];
  /** Problems found in this file itself. */
  problems: Problem[];
  /** Problems of this file and of every file it depends on. */
  allProblems: Problem[];
  /** Every file this one depends on, itself included. */
  dependencies: SourceRef[];
  /** True while the flattened text can be, but has not yet been, rendered (see Flattener.rendered). */
  renderable: boolean;
  /** The OpenSCENARIO semantics of the file as read (parameters, expressions, catalogs, names). */
  semantics: DocumentSemantics | undefined;
  /**
   * Where each catalog this file or the files it imports from reach lives: catalog name to the
   * catalog kind and the directory on disk (the first found wins), for carrying locations.
   */
  catalogIndex: Map<string, { kind: string; directory: string }>;
  /** What rendering carried from the sources into the root (SPEC 11), once rendered. */
  carried: CarryPlan | undefined;
  /** Text the carrying added to the main file's text, with the declarations it copied (offsets of the flattened text). */
  additions: Addition[];
}

/** A region of the flattened text that carrying added or replaced outside the imported groups. */
export interface Addition {
  start: number;
  end: number;
  replacedStart: number;
  replacedEnd: number;
  parts: { start: number; end: number; source: FlatSource; element: XmlElement }[];
}

export interface CarriedDeclaration {
  name: string;
  /** The declaration in the source's (flattened) model. */
  declaration: Declaration;
  source: FlatSource;
  /** The declaration's text as written in the source. */
  text: string;
}

export interface CarriedLocation {
  /** `VehicleCatalog`, ... */
  kind: string;
  /** The absolute directory on disk. */
  directory: string;
  source: FlatSource;
}

export interface CarryPlan {
  declarations: CarriedDeclaration[];
  locations: CarriedLocation[];
  problems: Problem[];
}

/** A text edit of the main file with, for each carried declaration, where it lands inside the inserted text. */
export interface CarryEdit {
  start: number;
  end: number;
  text: string;
  /** Carried declarations: offsets inside `text`, and what they were copied from. */
  parts: { start: number; end: number; source: FlatSource; element: XmlElement }[];
}

/** How files are checked against the OpenSCENARIO schemas: by their FileHeader, pinned, or not at all. */
export interface SchemaOptions {
  version: SchemaVersionSetting | 'off';
}

export interface FlattenOptions {
  /**
   * Produce the output whatever errors were found (`--force`, *Write Anyway*, *Run Anyway*): overrides
   * that cannot apply are skipped, as the original did; only what cannot be rendered at all (a missing file
   * or group, malformed XML, a cycle, a too large output) leaves no text.
   */
  force?: boolean;
  /** Where the output will be written (its file paths are rebased onto its folder, SPEC 11.6); beside the main file by default. */
  outputPath?: string;
  /** The output goes to standard output: its file paths are written absolute. */
  standardOutput?: boolean;
  /**
   * The road file is handed to the simulator by its absolute path (a run: esmini/run.ts withRoadFile), so a LogicFile path
   * through a parameter, left as written, is no warning that the output may reach another road.
   */
  roadHanded?: boolean;
  /**
   * A controller's `Properties/File` through a parameter that names a file from the main file's folder is handed to the
   * simulator as that absolute file (a run: esmini/controllerFiles.ts), so leaving it as written is no warning either.
   */
  controllerFilesHanded?: boolean;
}

export interface AnalysisResult {
  problems: Problem[];
  source: FlatSource;
  /** Files outside its dependencies whose existence decided a problem (an imported group's controller File): an editor watches them. */
  lookedUp: string[];
}

/** A file stored in a package that an output names: written beside the output (in `<name>.files/`) so that the output runs. */
export interface PackagedFile {
  /** Where it is written, absolute. */
  path: string;
  bytes: Uint8Array;
  /**
   * The `$parameter` path (as written) whose value names this file from the output: its copy lies beside the output, not in
   * the flattener's own `NAME.files/`, so another file already there is never replaced (`besideOutputWritable`).
   */
  namedBy?: string;
}

export interface FlattenResult {
  /** The flattened scenario; undefined when errors prevent it. */
  text: string | undefined;
  problems: Problem[];
  source: FlatSource;
  /** Files of a package the output names (a self-contained package's roads and catalogs): written beside it, in `<name>.files/`. */
  files: PackagedFile[];
}
