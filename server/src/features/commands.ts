import * as fs from 'node:fs';
import * as path from 'node:path';
import { ErrorCodes, ResponseError } from 'vscode-languageserver/node';
import { besideOutputWritable, Flattener, FlatSource, PackagedFile } from '../core/flatten';
import { isSameFile, OutputError, writeFileAtomicMakingFolders } from '../../../common/src/atomic';
import { insideFolders } from '../../../common/src/paths';
import { Problem } from '../core/problems';
import { baseName, childRef, diskRef, displayRef, nodeFileSystem, refId, SourceRef } from '../core/sources';
import { FlattenTextResult, ProblemSummary, StructureNode, WriteResult } from '../../../common/src/protocol';
import { elementPlace, resolvedTarget } from '../analysis';
import { filePathOf } from '../uris';
import { Workspace } from '../workspace';
import { attributesOverridden } from './symbols';

export function summarize(workspace: Workspace, problem: Problem): ProblemSummary {
  const summary: ProblemSummary = {
    uri: workspace.uriOf(problem.source),
    line: problem.range.start.line,
    character: problem.range.start.character,
    severity: problem.severity,
    message: problem.message,
  };
  if (problem.hint) summary.hint = problem.hint;
  summary.code = problem.code;
  return summary;
}

/** A request the client got wrong: answered as such, not logged as a failure of the server. */
export function invalidParams(message: string): ResponseError<void> {
  return new ResponseError(ErrorCodes.InvalidParams, message);
}

function forceOf(options: unknown): boolean {
  return Boolean(options && typeof options === 'object' && (options as { force?: unknown }).force === true);
}

/** Whether the client asked the user and was told to write outside the workspace. */
export function outsideConfirmed(options: unknown): boolean {
  return Boolean(options && typeof options === 'object' && (options as { outsideWorkspace?: unknown }).outsideWorkspace === true);
}

export async function refOf(workspace: Workspace, uri: unknown): Promise<SourceRef> {
  if (typeof uri !== 'string') throw invalidParams('expected a document URI');
  const ref = await workspace.uris.toRef(uri);
  if (!ref) throw invalidParams(`not a scenario URI: ${uri}`);
  // A package (a .mosc, or an unpacked folder) stands for its main.xosc.
  const last = ref.entries.length > 0 ? ref.entries[ref.entries.length - 1] : ref.disk;
  if (last.toLowerCase().endsWith('.mosc')) return childRef(ref, 'main.xosc');
  if (ref.entries.length === 0 && (await workspace.store.host.kind(ref.disk)) === 'directory')
    return diskRef(path.join(ref.disk, 'main.xosc'));
  return ref;
}

/** Flattens with the editor's unsaved text; a fresh Flattener, since `force` changes the outcome. */
export async function flattenToText(workspace: Workspace, uri: unknown, options: unknown): Promise<FlattenTextResult> {
  const ref = await refOf(workspace, uri);
  // The preview shows the flattened text even when it breaks the schema: the editor's diagnostics say where.
  const result = await new Flattener(
    workspace.store,
    workspace.settings.simulator,
    { version: 'off' },
    undefined,
    workspace.settings.carlaRelease,
  ).flatten(ref, {
    force: forceOf(options),
  });
  return { text: result.text ?? null, problems: result.problems.map((problem) => summarize(workspace, problem)) };
}

function outputProblem(workspace: Workspace, ref: SourceRef, message: string): ProblemSummary {
  return { uri: workspace.uriOf(ref), line: 0, character: 0, severity: 'error', message };
}

/** Writes the flattened scenario atomically; refuses to write over any file it was made from. */
export async function flattenToFile(workspace: Workspace, uri: unknown, outputPath: unknown, options: unknown): Promise<WriteResult> {
  const ref = await refOf(workspace, uri);
  if (typeof outputPath !== 'string' || !outputPath) throw invalidParams('expected an output path');
  const output = path.resolve(filePathOf(outputPath) ?? outputPath);
  if (!output.toLowerCase().endsWith('.xosc'))
    return { written: null, problems: [outputProblem(workspace, ref, `the output '${output}' must end in .xosc`)] };
  if (workspace.folders.length > 0 && !insideFolders(output, workspace.folders) && !outsideConfirmed(options)) {
    return {
      written: null,
      problems: [outputProblem(workspace, ref, `${output} lies outside the workspace; confirm to write it there`)],
      needsConfirmation: 'outsideWorkspace',
    };
  }
  const result = await new Flattener(
    workspace.store,
    workspace.settings.simulator,
    { version: workspace.settings.schemaVersion },
    undefined,
    workspace.settings.carlaRelease,
  ).flatten(ref, { force: forceOf(options), outputPath: output });
  const problems = result.problems.map((problem) => summarize(workspace, problem));
  const input = result.source.dependencies.find((dependency) => dependency.disk === output || isSameFile(dependency.disk, output));
  if (input)
    return {
      written: null,
      problems: [
        ...problems,
        outputProblem(workspace, ref, `refusing to overwrite ${displayRef(input, workspace.folders[0])}, an input of this flattening`),
      ],
    };
  if (result.text === undefined) return { written: null, problems };
  // A self-contained package's roads and catalogs go beside the output that names them.
  return (await writePackagedFiles(workspace, result.files, problems, ref)) ?? writeOutput(workspace, output, result.text, problems, ref);
}

/** Writes the package files an output names beside it (each atomically, its folder made); the first refusal of the writer, else undefined. */
export async function writePackagedFiles(
  workspace: Workspace,
  files: readonly PackagedFile[],
  problems: ProblemSummary[],
  ref: SourceRef,
): Promise<WriteResult | undefined> {
  const writable = await besideOutputWritable(files, nodeFileSystem);
  for (const message of writable.warnings) problems.push({ ...outputProblem(workspace, ref, message), severity: 'warning' });
  for (const file of writable.files) {
    await fs.promises.mkdir(path.dirname(file.path), { recursive: true });
    const written = await writeOutput(workspace, file.path, file.bytes, problems, ref);
    if (written.written === null) return written;
  }
  return undefined;
}

/** Writes an output atomically; a refusal of the writer (read-only, a folder) is a problem, not an exception. */
export async function writeOutput(
  workspace: Workspace,
  output: string,
  data: string | Uint8Array,
  problems: ProblemSummary[],
  ref: SourceRef,
): Promise<WriteResult> {
  try {
    // The output was chosen in a save dialog, which offers to create a missing folder: made here, as VS Code's Save As does.
    await writeFileAtomicMakingFolders(output, data);
  } catch (error) {
    if (!(error instanceof OutputError)) throw error;
    return { written: null, problems: [...problems, outputProblem(workspace, ref, error.message)] };
  }
  workspace.fileChanged(output);
  return { written: output, problems };
}

/** The reference graph: each reference with the file it resolves to, its groups and, for packages, their own references. */
export async function structure(workspace: Workspace, uri: unknown): Promise<StructureNode | null> {
  const ref = await refOf(workspace, uri);
  const source = await workspace.source(ref);
  if (!source.original) return null;
  const visiting = new Set<string>();
  const build = (flat: FlatSource, kind: StructureNode['kind'], label: string): StructureNode => {
    const node: StructureNode = {
      kind,
      label,
      detail: displayRef(flat.ref, workspace.folders[0]),
      uri: workspace.uriOf(flat.ref),
      line: 0,
      character: 0,
      children: [],
    };
    if (visiting.has(refId(flat.ref))) return node;
    visiting.add(refId(flat.ref));
    for (const link of flat.links) {
      const position = flat.original?.document.lines.positionAt(link.info.element.start);
      const target = resolvedTarget(link.resolution);
      if (!target || !link.source) {
        node.children.push({
          kind: 'missing',
          label: link.info.fileName || '(no scenarioFileName)',
          detail:
            link.resolution.kind === 'missing'
              ? 'not found'
              : link.resolution.kind === 'invalid' || link.resolution.kind === 'unreadable'
                ? link.resolution.message
                : 'cycle',
          uri: workspace.uriOf(flat.ref),
          line: position?.line,
          character: position?.character,
          children: [],
        });
        continue;
      }
      const child = build(link.source, link.resolution.kind === 'package' ? 'package' : 'scenario', link.info.fileName);
      const reference: StructureNode = {
        kind: 'reference',
        label: `${link.info.outerGroup?.name ?? '?'} → ${link.info.fileName}`,
        uri: workspace.uriOf(flat.ref),
        line: position?.line,
        character: position?.character,
        children: [child],
      };
      for (const group of link.groups) {
        const place = group.target ? elementPlace(link.source, group.target.element) : undefined;
        reference.children.push({
          kind: group.target ? 'group' : 'missing',
          label: group.info.name,
          detail: group.target ? attributesOverridden(group.plan?.applied.size ?? 0) : 'no such group',
          uri: place ? workspace.uriOf(place.ref) : undefined,
          line: place?.range.start.line,
          character: place?.range.start.character,
          children: [],
        });
      }
      node.children.push(reference);
    }
    visiting.delete(refId(flat.ref));
    return node;
  };
  return build(source, 'main', baseName(ref));
}
