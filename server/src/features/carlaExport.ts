import * as path from 'node:path';
import { isSameFile } from '../../../common/src/atomic';
import { insideFolders } from '../../../common/src/paths';
import { ProblemSummary, WriteResult } from '../../../common/src/protocol';
import { CarlaExportOptionError, CarlaExportOptions, CarlaLoss, exportForCarla } from '../core/export/carla';
import { roadFolders } from '../core/semantics/roadFiles';
import { refId, type SourceRef } from '../core/sources';
import { filePathOf } from '../uris';
import { Workspace } from '../workspace';
import { invalidParams, outsideConfirmed, refOf, summarize, writeOutput, writePackagedFiles } from './commands';

/** The editor's export options: the output, the release of `modular2simple.carla.release`, the road folders of `modular2simple.esmini.roadPath` (as Run in esmini and `export --road-path`). */
export function carlaExportOptions(workspace: Workspace, ref: SourceRef, outputPath: string): CarlaExportOptions {
  return {
    outputPath,
    release: workspace.settings.carlaRelease,
    roadFolders: roadFolders(workspace.settings.roadPath, workspace.folders[0] ?? path.dirname(ref.disk)),
  };
}

/** A loss of the export as the editor lists it: a refusal is an error, what is dropped or approximated a warning. */
export function lossSummary(workspace: Workspace, loss: CarlaLoss): ProblemSummary {
  return {
    uri: workspace.uriOf(loss.source),
    line: loss.range.start.line,
    character: loss.range.start.character,
    end: { line: loss.range.end.line, character: loss.range.end.character },
    severity: loss.kind === 'refused' ? 'error' : 'warning',
    message: `${loss.element}: ${loss.what} (${loss.kind}); ${loss.carla}`,
    code: `carla-export-${loss.kind}`,
  };
}

/**
 * *Export for CARLA…*: the scenario as OpenSCENARIO 1.0 that ScenarioRunner builds (core/export/carla.ts,
 * with the editor's unsaved text and the release of `modular2simple.carla.release`), written atomically,
 * never over its input; the loss report comes back as problems at their source lines.
 */
export async function exportForCarlaToFile(
  workspace: Workspace,
  uri: unknown,
  outputPath: unknown,
  options: unknown,
): Promise<WriteResult> {
  const ref = await refOf(workspace, uri);
  if (typeof outputPath !== 'string' || !outputPath) throw invalidParams('expected an output path');
  const output = path.resolve(filePathOf(outputPath) ?? outputPath);
  const refusal = (message: string, extra: Partial<WriteResult> = {}): WriteResult => ({
    written: null,
    problems: [{ uri: workspace.uriOf(ref), line: 0, character: 0, severity: 'error', message }],
    ...extra,
  });
  if (!output.toLowerCase().endsWith('.xosc')) return refusal(`the output '${output}' must end in .xosc`);
  if (output === ref.disk || isSameFile(ref.disk, output)) return refusal(`refusing to overwrite ${output}, the scenario being exported`);
  if (workspace.folders.length > 0 && !insideFolders(output, workspace.folders) && !outsideConfirmed(options))
    return refusal(`${output} lies outside the workspace; confirm to write it there`, { needsConfirmation: 'outsideWorkspace' });
  let result;
  try {
    result = await exportForCarla(workspace.store, ref, carlaExportOptions(workspace, ref, output));
  } catch (error) {
    if (error instanceof CarlaExportOptionError) return refusal(error.message);
    throw error;
  }
  const problems = [
    ...result.problems.map((problem) => summarize(workspace, problem)),
    ...result.losses.map((loss) => lossSummary(workspace, loss)),
  ];
  if (result.text === undefined) {
    // A refusal placed in this file is its own error already; the sentence at its first line is for one placed elsewhere
    // (in an imported simple scenario) or not placed at all, not a second error for the same cause.
    const placedHere = result.losses.some((loss) => loss.kind === 'refused' && refId(loss.source) === refId(ref));
    const sentence = placedHere ? [] : refusal(`not exported: ${result.refused ?? 'refused'}`).problems;
    return { written: null, problems: [...problems, ...sentence] };
  }
  // A road packed with the scenario goes beside the export that names it, as flatten writes it.
  return (
    (await writePackagedFiles(workspace, result.files ?? [], problems, ref)) ?? writeOutput(workspace, output, result.text, problems, ref)
  );
}
