import { CancellationToken, Diagnostic } from 'vscode-languageserver/node';
import { Problem, problemKey, uniqueProblems } from '../core/problems';
import { refId, SourceRef } from '../core/sources';
import { mainOf, Workspace } from '../workspace';
import { diagnose, toDiagnostic } from './diagnostics';

/** Problems by the id of the file they are in. */
export type ProblemsByFile = Map<string, { ref: SourceRef; problems: Problem[] }>;

/**
 * The problems that analysing `mains` finds, by the file each is in: what `modular2simple check`
 * reports, where a problem of a simple scenario shows in that scenario however it was reached.
 */
export async function problemsByFile(workspace: Workspace, mains: SourceRef[], token?: CancellationToken): Promise<ProblemsByFile> {
  let problems: Problem[] = [];
  for (const main of mains) {
    if (token?.isCancellationRequested) break;
    problems = problems.concat((await workspace.analyze(main)).problems);
  }
  const byFile: ProblemsByFile = new Map();
  for (const problem of uniqueProblems(problems)) {
    const id = refId(problem.source);
    const entry = byFile.get(id) ?? { ref: problem.source, problems: [] };
    entry.problems.push(problem);
    byFile.set(id, entry);
  }
  return byFile;
}

/** The main files of every scenario file of the workspace folders, as `check FOLDER` takes them. */
export async function workspaceMains(workspace: Workspace): Promise<SourceRef[]> {
  return (await workspace.indexedFiles()).map((entry) => mainOf(entry.path, entry.kind));
}

/**
 * The diagnostics of one file: its own analysis as a main file, and the problems that analyses of
 * other files place in it (a duplicate group a reference makes ambiguous, a listed name no key reaches).
 */
export async function fileDiagnostics(workspace: Workspace, ref: SourceRef, placedElsewhere: Problem[]): Promise<Diagnostic[]> {
  const { diagnostics } = await diagnose(workspace, ref);
  const own = new Set((await workspace.analyze(ref)).problems.map((problem) => problemKey(problem)));
  for (const problem of placedElsewhere) if (!own.has(problemKey(problem))) diagnostics.push(toDiagnostic(problem, workspace));
  return diagnostics;
}
