import { Connection, Diagnostic, DiagnosticRelatedInformation, DiagnosticSeverity, DiagnosticTag } from 'vscode-languageserver/node';
import { Problem } from '../core/problems';
import { refId, SourceRef } from '../core/sources';
import { Workspace } from '../workspace';

export const DIAGNOSTIC_SOURCE = 'modular2simple';

/** What a quick fix needs from a diagnostic: the problem code and the core's data. */
export interface DiagnosticData {
  code: string;
  suggestion?: string;
  replacement?: string;
  entity?: string;
}

/** LSP severity: an unknown key is an error for the CLI but a warning while editing (SPEC 7). */
function severityOf(problem: Problem): DiagnosticSeverity {
  if (problem.code === 'unknown-key') return DiagnosticSeverity.Warning;
  if (problem.severity === 'error') return DiagnosticSeverity.Error;
  if (problem.severity === 'warning') return DiagnosticSeverity.Warning;
  return DiagnosticSeverity.Information;
}

export function toDiagnostic(problem: Problem, workspace: Workspace): Diagnostic {
  const related: DiagnosticRelatedInformation[] = (problem.related ?? []).map((item) => ({
    location: { uri: workspace.uriOf(item.source), range: item.range },
    message: item.message,
  }));
  const data: DiagnosticData = { code: problem.code, ...problem.data };
  const diagnostic: Diagnostic = {
    range: problem.range,
    severity: severityOf(problem),
    code: problem.code,
    source: DIAGNOSTIC_SOURCE,
    message: problem.hint ? `${problem.message}\n${problem.hint}` : problem.message,
    data,
  };
  if (related.length > 0) diagnostic.relatedInformation = related;
  if (problem.code === 'xosc-fallback') diagnostic.tags = [DiagnosticTag.Deprecated];
  return diagnostic;
}

/** The diagnostics of one file analysed as a main file, with the cycle spelled out in related locations. */
export async function diagnose(workspace: Workspace, ref: SourceRef): Promise<{ diagnostics: Diagnostic[]; dependencies: string[] }> {
  const result = await workspace.flatten(ref);
  const id = refId(ref);
  const diagnostics: Diagnostic[] = [];
  for (const problem of result.problems) {
    if (refId(problem.source) !== id) continue;
    const diagnostic = toDiagnostic(problem, workspace);
    if (problem.code === 'cycle') {
      const link = result.source.links.find((candidate) => candidate.cycle && candidate.info.fileAttribute && problem.range.start.line === result.source.original?.document.lines.positionAt(candidate.info.fileAttribute.valueStart).line);
      diagnostic.relatedInformation = (link?.cycle ?? []).map((member, index) => ({
        location: { uri: workspace.uriOf(member), range: { start: { line: 0, character: 0 }, end: { line: 0, character: 0 } } },
        message: `cycle step ${index + 1}`,
      }));
    }
    diagnostics.push(diagnostic);
  }
  return { diagnostics, dependencies: result.source.dependencies.map((dependency) => refId(dependency)) };
}

/**
 * Publishes diagnostics for open documents: after an edit (briefly delayed, latest edit wins) for
 * the edited file and every open file that depends on it.
 */
export class DiagnosticsScheduler {
  private readonly dependencies = new Map<string, Set<string>>();
  private readonly pending = new Set<string>();
  private timer: NodeJS.Timeout | undefined;
  private running: Promise<void> | undefined;

  constructor(
    private readonly connection: Connection,
    private readonly workspace: Workspace,
  ) {}

  /** Schedules the open documents affected by a change of `changedIds` (file ids or disk paths). */
  changed(changedIds: string[]): void {
    for (const [id] of this.workspace.documents) {
      const dependencies = this.dependencies.get(id);
      const affected = changedIds.some(
        (changed) => changed === id || (dependencies && [...dependencies].some((dependency) => dependency === changed || dependency.startsWith(changed + '/'))),
      );
      if (affected) this.pending.add(id);
    }
    this.arm();
  }

  all(): void {
    for (const id of this.workspace.documents.keys()) this.pending.add(id);
    this.arm();
  }

  closed(ref: SourceRef, uri: string): void {
    this.dependencies.delete(refId(ref));
    this.pending.delete(refId(ref));
    void this.connection.sendDiagnostics({ uri, diagnostics: [] });
  }

  private arm(): void {
    if (this.timer) clearTimeout(this.timer);
    this.timer = setTimeout(() => void this.flush(), this.workspace.settings.diagnosticsDelay);
  }

  /** Runs one pass at a time; edits arriving meanwhile are taken by the next pass. */
  private async flush(): Promise<void> {
    this.timer = undefined;
    if (this.running) {
      await this.running;
      if (this.pending.size > 0 && !this.timer) this.arm();
      return;
    }
    const ids = [...this.pending];
    this.pending.clear();
    this.running = (async () => {
      for (const id of ids) {
        const open = this.workspace.documents.get(id);
        if (!open) continue;
        const version = open.document.version;
        try {
          const { diagnostics, dependencies } = await diagnose(this.workspace, open.ref);
          this.dependencies.set(id, new Set(dependencies));
          const current = this.workspace.documents.get(id);
          if (!current || current.document.version !== version) continue;
          await this.connection.sendDiagnostics({ uri: open.uri, version, diagnostics });
        } catch (error) {
          this.connection.console.error(`diagnostics of ${open.uri} failed: ${(error as Error).stack ?? error}`);
        }
      }
    })();
    await this.running;
    this.running = undefined;
    if (this.pending.size > 0 && !this.timer) this.arm();
  }
}
