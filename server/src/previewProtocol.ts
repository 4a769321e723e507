import { RequestType } from 'vscode-languageserver-protocol';
import type { LineSegment } from './core/lineSegments';
import type { ProblemSummary } from './protocol';

/** The live preview's request: the flattened text of a scenario as the editor has it, and where it shows each line of that scenario. */
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
