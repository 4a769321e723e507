import { previewLineMap } from '../core/previewLines';
import { PreviewParams, PreviewResult } from '../../../common/src/protocol';
import { Workspace } from '../workspace';
import { refOf, summarize } from './commands';

/** The flattened text as the editor has it, from the current generation's flattener (what did not change is not read again). */
export async function preview(workspace: Workspace, params: PreviewParams): Promise<PreviewResult> {
  const ref = await refOf(workspace, params?.uri);
  const result = await workspace.flattener().flatten(ref);
  return {
    text: result.text ?? null,
    problems: result.problems.map((problem) => summarize(workspace, problem)),
    lines: result.text === undefined ? [] : previewLineMap(result.source),
  };
}
