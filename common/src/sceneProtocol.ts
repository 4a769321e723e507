/**
 * The bird's-eye view's request `modular2simple/scene` (SceneParams → SceneResult), typed for both
 * sides (both bundles import this file).
 */
import { RequestType } from 'vscode-languageserver-protocol';
import type { SectionPolylines } from './sectionPolylines';
import type { TraceRecord } from './trace';

export interface SceneParams {
  /** A scenario: file: or mosc: URI (a main.xosc is shown flattened, unsaved edits included). */
  uri: string;
  /** Extra folders to find the road file in (the `modular2simple.esmini.roadPath` setting). */
  roadPath?: string[];
}

/** A place in a source file, zero-based as LSP. */
export interface SourceLocation {
  uri: string;
  line: number;
  character: number;
}

export interface SceneEntity {
  name: string;
  kind: string;
  length: number;
  width: number;
  /** How far the bounding box's center is ahead of the position (esmini positions the rear axle). */
  centerX: number;
  /** Absent when the start position could not be evaluated (see `problem`). */
  x?: number;
  y?: number;
  hdg?: number;
  described: string;
  problem?: string;
  /** The TeleportAction's Position in Init, or else the ScenarioObject. */
  source?: SourceLocation;
}

export interface SceneEvent {
  name: string;
  maneuver: string;
  /** The ManeuverGroup as the scenario shown names it (flattened: `CutInLead.CutIn` for a copy of an imported group). */
  group: string;
  act: string;
  trigger: string;
  /** When a plain SimulationTimeCondition starts it. */
  plannedTime?: number;
  source?: SourceLocation;
  /**
   * esmini's path of the event (`Story::Act::ManeuverGroup::Maneuver::Event`, flattened names): the key of its
   * start in a storyboard trace (common/src/trace.ts), one per copy of a reused group.
   */
  path?: string;
  /** The entities of its ManeuverGroup's Actors. */
  actors: string[];
  /** For a copy of an imported group: the group as written in its simple scenario, and that file's name. */
  sourceGroup?: { name: string; file: string };
}

export interface SceneRoadFile {
  /** As written in RoadNetwork/LogicFile. */
  filepath: string;
  /** The file found, or undefined with the folders searched in `problems`. */
  resolved?: string;
  roadCount: number;
  source?: SourceLocation;
}

export interface SceneResult {
  uri: string;
  title: string;
  roadFile?: SceneRoadFile;
  /** Lane borders per lane section, coordinates rounded to centimetres. */
  sections: SectionPolylines[];
  entities: SceneEntity[];
  events: SceneEvent[];
  /** What could not be shown, in words (road file not found, a position not evaluated, ...). */
  problems: string[];
}

export const SceneRequest = new RequestType<SceneParams, SceneResult, void>('modular2simple/scene');

export interface RunTraceParams {
  /** The scenario the run was made from (file: or mosc: URI), flattened as the scene is. */
  uri: string;
  /** esmini's log of the run (its stdout or log.txt). */
  log: string;
}

/**
 * The storyboard trace of a run of esmini's program read from its log (as Run in esmini reads it), each record on
 * the flattened element it belongs to: the bird's-eye view's event times for a run loaded from a CSV and its log.
 */
export const RunTraceRequest = new RequestType<RunTraceParams, TraceRecord[], void>('modular2simple/runTrace');
