import { WriteResult } from '../protocol';
import { Workspace } from '../workspace';

/** Packing needs the core's pack module, which is not on this branch yet. */
export async function packCommand(workspace: Workspace, inputs: unknown, outputPath: unknown): Promise<WriteResult> {
  void inputs;
  return { written: null, problems: [{ uri: typeof outputPath === 'string' ? outputPath : '', line: 0, character: 0, severity: 'error', message: 'pack is not available in this build of the language server' }] };
}
