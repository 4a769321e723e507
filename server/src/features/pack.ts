import * as fs from 'node:fs';
import * as path from 'node:path';
import { isSameFile } from '../../../common/src/atomic';
import { diskRef } from '../core/sources';
import { packFiles, packFolder, PackResult } from '../core/pack';
import { WriteResult } from '../../../common/src/protocol';
import { filePathOf } from '../uris';
import { Workspace } from '../workspace';
import { invalidParams, summarize, writeOutput } from './commands';

function isFolder(filePath: string): boolean {
  try {
    return fs.statSync(filePath).isDirectory();
  } catch {
    return false;
  }
}

/**
 * Packs a folder (or the folder of a lone main.xosc) with everything it references, or a list of
 * files at the root of a new package; writes the archive atomically, never over an input.
 */
export async function packCommand(
  workspace: Workspace,
  inputs: unknown,
  outputPath: unknown,
  selfContained?: unknown,
): Promise<WriteResult> {
  if (!Array.isArray(inputs) || inputs.length === 0 || !inputs.every((input) => typeof input === 'string'))
    throw invalidParams('expected a list of input URIs');
  if (typeof outputPath !== 'string' || !outputPath) throw invalidParams('expected an output path');
  const output = path.resolve(filePathOf(outputPath) ?? outputPath);
  const refuse = (message: string): WriteResult => ({
    written: null,
    problems: [{ uri: outputPath, line: 0, character: 0, severity: 'error', message }],
  });
  if (!output.toLowerCase().endsWith('.mosc')) return refuse(`the output '${output}' must end in .mosc`);
  const paths = (inputs as string[]).map((input) => path.resolve(filePathOf(input) ?? input));
  const folder =
    paths.length === 1
      ? isFolder(paths[0])
        ? paths[0]
        : path.basename(paths[0]) === 'main.xosc'
          ? path.dirname(paths[0])
          : undefined
      : undefined;
  if (paths.some((input) => input === output || isSameFile(input, output)))
    return refuse(`refusing to overwrite ${output}, one of the inputs`);
  // Paths are rebased onto the package's folder, or (self-contained) the files they name are stored inside it.
  const packOptions = { outputPath: output, selfContained: selfContained === true, workingDirectory: workspace.folders[0] };
  const result: PackResult = folder ? await packFolder(folder, workspace.store, packOptions) : await packFiles(paths, {}, packOptions);
  const problems = result.problems.map((problem) => summarize(workspace, problem));
  // Every file read or resolved to while packing counts: a referenced package must never be overwritten.
  const input = result.inputs.find((candidate) => candidate.disk === output || isSameFile(candidate.disk, output));
  if (input) return refuse(`refusing to overwrite ${output}: the package references it`);
  if (!result.bytes) return { written: null, problems };
  return writeOutput(workspace, output, result.bytes, problems, diskRef(paths[0]));
}
