/**
 * The "Run in esmini" request between the VS Code client and the language server, typed. Plain data
 * and the request type only, so both bundles can import it.
 */
import { RequestType } from 'vscode-languageserver-protocol';
import type { ProblemSummary } from './protocol';

export interface RunEsminiParams {
  /** The scenario to run: a main.xosc, any plain .xosc, a .mosc or a file inside one (its unsaved text is used). */
  uri: string;
  /** Setting modular2simple.esmini.path: the program or its folder; PATH when empty. Relative to the first workspace folder. */
  esminiPath?: string;
  /** Setting modular2simple.esmini.roadPath: extra folders for road files and catalogs. */
  roadPath?: string[];
  /** Simulated seconds (default 30). */
  duration?: number;
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
  /** esmini's whole output. */
  log: string;
  /**
   * esmini's CSV log (`--csv_logger`, on the server's disk): 6 header lines, the column line
   * (`Index [-], TimeStamp [s], #1 Entity_Name [-], ...`, 31 columns per entity), one row per step.
   * Drop rows whose TimeStamp exceeds `duration`. It stays until the next run of the same file.
   */
  csvFile?: string;
  /** The flattened scenario as handed to esmini (with the added time limit). */
  scenarioFile?: string;
  duration: number;
  timeStep: number;
  seed: number;
  simulatedTime?: number;
  wallMs: number;
  esmini?: string;
  args?: string[];
}

export const RunEsminiRequest = new RequestType<RunEsminiParams, RunEsminiResult, void>('modular2simple/runEsmini');
