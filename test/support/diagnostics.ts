import { Diagnostic } from 'vscode-languageserver/node';

/** A diagnostic's project code (`data.code`): its `code` names the ASAM Quality Checker rule where that checker has one. */
export function problemCodeOf(diagnostic: Diagnostic): string | undefined {
  const data: unknown = diagnostic.data;
  return typeof data === 'object' && data !== null && 'code' in data && typeof data.code === 'string' ? data.code : undefined;
}
