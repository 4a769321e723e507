/**
 * The contract between the VS Code client and the language server: the custom requests with their
 * parameters and results, typed for both sides (both bundles import this file).
 */
import { RequestType } from 'vscode-languageserver-protocol';
import { SceneRequest } from './sceneProtocol';

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
}

export interface StructureParams {
  uri: string;
}

/** The custom requests; their method names are also advertised in `capabilities.experimental.requests`. */
export const FlattenToTextRequest = new RequestType<FlattenToTextParams, FlattenTextResult, void>('modular2simple/flattenToText');
export const FlattenToFileRequest = new RequestType<FlattenToFileParams, WriteResult, void>('modular2simple/flattenToFile');
export const PackRequest = new RequestType<PackParams, WriteResult, void>('modular2simple/pack');
/** The reference graph for the Show Structure view; null when the URI is no scenario. */
export const StructureRequest = new RequestType<StructureParams, StructureNode | null, void>('modular2simple/structure');

export const CUSTOM_REQUESTS = [FlattenToTextRequest.method, FlattenToFileRequest.method, PackRequest.method, StructureRequest.method, SceneRequest.method];

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
