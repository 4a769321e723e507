import { applyEdits } from '../flatten/edits';
import { rebasePaths } from '../flatten/rebase';
import { nodeFileSystem } from '../sources';
import { parseXml } from '../xml';

/**
 * A scenario written in `fromDirectory` with its file paths rebased (flatten's own rebasing, SPEC 11.6)
 * so that, written in `toDirectory`, it reaches the same roads and catalogs.
 */
export async function rebasedText(text: string, fromDirectory: string, toDirectory: string): Promise<string> {
  if (fromDirectory === toDirectory) return text;
  const document = parseXml(text);
  const rebase = await rebasePaths({ document, baseOf: () => fromDirectory, outputDirectory: toDirectory, kindOf: (diskPath) => nodeFileSystem.kind(diskPath) });
  return rebase.edits.length === 0 ? text : applyEdits(text, rebase.edits);
}
