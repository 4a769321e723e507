/**
 * The contract between the VS Code client and the language server: custom command names and
 * their payloads. Plain data only, so both bundles can import it.
 */
export const ServerCommands = {
  /** args: [uri: string, options?: { force?: boolean }] -> FlattenTextResult. For the live preview. */
  flattenToText: 'modular2simple.server.flattenToText',
  /** args: [inputUri: string, outputPath: string (a .xosc), options?: { force?: boolean; outsideWorkspace?: boolean }] -> WriteResult. */
  flattenToFile: 'modular2simple.server.flattenToFile',
  /** args: [inputs: string[] (file URIs of a folder, a main.xosc or files), outputPath: string] -> WriteResult. */
  pack: 'modular2simple.server.pack',
  /** args: [uri: string] -> StructureNode | null. The reference graph for the Show Structure view. */
  structure: 'modular2simple.server.structure',
} as const;

/** URI scheme of files inside a `.mosc`: `mosc:/abs/path/pkg.mosc/inner.mosc/main.xosc`. */
export const PACKAGE_SCHEME = 'mosc';

export interface ProblemSummary {
  uri: string;
  /** Zero-based, as LSP. */
  line: number;
  character: number;
  severity: 'error' | 'warning' | 'information';
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
   * output lies outside the workspace folders; send the command again with `{ outsideWorkspace: true }`.
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
