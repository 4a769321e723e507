import { Connection, Diagnostic, DiagnosticRelatedInformation, DiagnosticSeverity, DiagnosticTag } from 'vscode-languageserver/node';
import { FlatSource, LinkedReference } from '../core/flatten';
import { Problem } from '../core/problems';
import { diagnosticOf } from '../core/diagnostics';
import { cycleMessage, cycleStepNote } from '../core/diagnostics/cycle';
import { standsForCycleOnly } from '../core/diagnostics/sourceErrors';
import { ruleOf } from '../core/rules';
import { Range } from '../core/text';
import { resolvedTarget } from '../analysis';
import { baseName, displayRef, refId, SourceRef } from '../core/sources';
import { Workspace } from '../workspace';
import { addReferencingScenarios } from './catalogVariables';
import { DiagnosticData, diagnosticDataOf } from './fixes/data';
import { distributionAnalysis, distributionProblems } from './distributions';

export const DIAGNOSTIC_SOURCE = 'modular2simple';

/** At most this many diagnostics are published per file. */
export const MAX_DIAGNOSTICS = 1000;

/** LSP severity: the core's own, so the editor and the CLI agree (an unknown key blocks a flatten, so it is an error). */
function severityOf(problem: Problem): DiagnosticSeverity {
  if (problem.severity === 'error') return DiagnosticSeverity.Error;
  if (problem.severity === 'warning') return DiagnosticSeverity.Warning;
  if (problem.severity === 'hint') return DiagnosticSeverity.Hint;
  return DiagnosticSeverity.Information;
}

export function toDiagnostic(problem: Problem, workspace: Workspace): Diagnostic {
  const related: DiagnosticRelatedInformation[] = (problem.related ?? []).map((item) => ({
    location: { uri: workspace.uriOf(item.source), range: item.range },
    message: item.message,
  }));
  const rule = ruleOf(problem);
  const diagnostic: Diagnostic = {
    range: problem.range,
    severity: severityOf(problem),
    // The rule the user knows from ASAM's checker where it has one; quick fixes and clients read the project's code in `data`.
    code: rule.qcRule ?? problem.code,
    source: DIAGNOSTIC_SOURCE,
    message: problem.hint ? `${problem.message}\n${problem.hint}` : problem.message,
    data: diagnosticDataOf(problem),
  };
  if (rule.helpUri) diagnostic.codeDescription = { href: rule.helpUri };
  if (related.length > 0) diagnostic.relatedInformation = related;
  if (diagnosticOf(problem.code)?.deprecated) diagnostic.tags = [DiagnosticTag.Deprecated];
  if (diagnosticOf(problem.code)?.unnecessary) diagnostic.tags = [DiagnosticTag.Unnecessary];
  return diagnostic;
}

function referencePlace(source: FlatSource, link: LinkedReference): Range | undefined {
  const attributeNode = link.info.fileAttribute;
  const lines = source.original?.document.lines;
  return lines && attributeNode ? lines.range(attributeNode.valueStart, attributeNode.valueEnd) : undefined;
}

/** Each step of a cycle as a related location: the reference in each member's file (`sourceOf` gives the file's analysis). */
function cycleSteps(
  workspace: Workspace,
  cycle: SourceRef[],
  sourceOf: (member: SourceRef) => FlatSource | undefined,
): DiagnosticRelatedInformation[] {
  const related: DiagnosticRelatedInformation[] = [];
  for (let step = 0; step + 1 < cycle.length; step++) {
    const from = sourceOf(cycle[step]);
    const next = refId(cycle[step + 1]);
    const stepLink = from?.links.find((candidate) => {
      const target = resolvedTarget(candidate.resolution);
      return target !== undefined && refId(target) === next;
    });
    const range = from && stepLink ? referencePlace(from, stepLink) : undefined;
    if (from && range)
      related.push({
        location: { uri: workspace.uriOf(from.ref), range },
        message: cycleStepNote(baseName(cycle[step]), baseName(cycle[step + 1])),
      });
  }
  return related;
}

/**
 * The core reports a cycle in the file that closes it; the file that starts it gets a cycle
 * diagnostic too, on its reference, with each step of the cycle as a related location.
 */
function cycleDiagnostics(workspace: Workspace, root: FlatSource): Diagnostic[] {
  const sources = new Map<string, FlatSource>();
  const pending = [root];
  while (pending.length > 0) {
    const source = pending.pop() as FlatSource;
    if (sources.has(refId(source.ref))) continue;
    sources.set(refId(source.ref), source);
    for (const link of source.links) if (link.source) pending.push(link.source);
  }
  const rootId = refId(root.ref);
  const diagnostics: Diagnostic[] = [];
  for (const source of sources.values()) {
    for (const link of source.links) {
      const cycle = link.cycle;
      if (!cycle || cycle.length < 2 || refId(cycle[0]) !== rootId || source === root) continue;
      const related = cycleSteps(workspace, cycle, (member) => sources.get(refId(member)));
      const first = related[0];
      if (!first) continue;
      diagnostics.push({
        range: first.location.range,
        severity: DiagnosticSeverity.Error,
        code: 'cycle',
        source: DIAGNOSTIC_SOURCE,
        message: cycleMessage(cycle.map((member) => displayRef(member, workspace.folders[0]))),
        relatedInformation: related,
        data: { code: 'cycle' } satisfies DiagnosticData,
      });
    }
  }
  return diagnostics;
}

/** The diagnostics of one file analysed as a main file. */
export async function diagnose(workspace: Workspace, ref: SourceRef): Promise<{ diagnostics: Diagnostic[]; dependencies: string[] }> {
  const result = await workspace.analyze(ref);
  const id = refId(ref);
  const cycles = cycleDiagnostics(workspace, result.source);
  const diagnostics: Diagnostic[] = [...cycles];
  for (const problem of result.problems) {
    if (refId(problem.source) !== id) continue;
    // A reference whose only error (or the only error of a file it leads to) is a cycle already carries the cycle diagnostic.
    const cycleOnly =
      standsForCycleOnly(problem) &&
      cycles.some(
        (cycle) => cycle.range.start.line === problem.range.start.line && cycle.range.start.character === problem.range.start.character,
      );
    if (cycleOnly) continue;
    const diagnostic = toDiagnostic(problem, workspace);
    if (problem.code === 'cycle') {
      const link = result.source.links.find(
        (candidate) => candidate.cycle && referencePlace(result.source, candidate)?.start.line === problem.range.start.line,
      );
      const members = link?.cycle ?? [];
      // Each member's own analysis holds its reference (this file's analysis may reach none of them: the cycle stopped there).
      const analyses = new Map<string, FlatSource>([[id, result.source]]);
      for (const member of members.slice(0, -1))
        if (!analyses.has(refId(member))) analyses.set(refId(member), await workspace.source(member));
      diagnostic.relatedInformation = cycleSteps(workspace, members, (member) => analyses.get(refId(member)));
      if (members.length > 0)
        diagnostic.message = `${cycleMessage(members.map((member) => displayRef(member, workspace.folders[0])))}${problem.hint ? `\n${problem.hint}` : ''}`;
    }
    if (problem.code === 'undeclared-variable') await addReferencingScenarios(workspace, ref, problem, diagnostic);
    diagnostics.push(diagnostic);
  }
  const dependencies = result.source.dependencies.map((dependency) => refId(dependency));
  const distribution = await distributionAnalysis(workspace, ref);
  if (distribution) {
    for (const problem of distributionProblems(distribution)) diagnostics.push(toDiagnostic(problem, workspace));
    // An edit of the ScenarioFile changes what the distribution's names and values mean.
    if (distribution.scenarioPath) dependencies.push(distribution.scenarioPath);
  }
  if (diagnostics.length > MAX_DIAGNOSTICS) {
    // A pathological file (say 100,000 groups of one name) must not flood the editor: errors first.
    diagnostics.sort((a, b) => (a.severity ?? 4) - (b.severity ?? 4));
    diagnostics.length = MAX_DIAGNOSTICS;
  }
  return { diagnostics, dependencies };
}

/**
 * Publishes diagnostics for open documents: after an edit (briefly delayed, latest edit wins) for
 * the edited file and every open file that depends on it. A client that pulls diagnostics
 * (`textDocument/diagnostic`) gets none pushed; it is asked to pull again instead.
 */
export class DiagnosticsScheduler {
  private readonly dependencies = new Map<string, Set<string>>();
  private readonly pending = new Set<string>();
  private timer: NodeJS.Timeout | undefined;
  private running: Promise<void> | undefined;
  /** Called after each pass that published diagnostics. */
  onPassDone: (() => void) | undefined;
  /** `push`: publish; `refresh`: ask the pulling client to pull again; `pull`: the pulling client cannot be asked. */
  mode: 'push' | 'refresh' | 'pull' = 'push';

  constructor(
    private readonly connection: Connection,
    private readonly workspace: Workspace,
  ) {}

  /** Schedules the open documents affected by a change of `changedIds` (file ids or disk paths). */
  changed(changedIds: string[]): void {
    const folders = changedIds.map((changed) => changed + '/');
    const touched = (dependency: string) => changedIds.includes(dependency) || folders.some((folder) => dependency.startsWith(folder));
    for (const [id] of this.workspace.documents) {
      if (changedIds.includes(id)) {
        this.pending.add(id);
        continue;
      }
      // Walked in place: a main file with 400 references has 400 dependencies, on every keystroke.
      const dependencies = this.dependencies.get(id);
      if (dependencies)
        for (const dependency of dependencies)
          if (touched(dependency)) {
            this.pending.add(id);
            break;
          }
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
    if (this.mode === 'push') void this.connection.sendDiagnostics({ uri, diagnostics: [] });
  }

  private arm(): void {
    if (this.mode === 'pull') return this.pending.clear();
    if (this.timer) clearTimeout(this.timer);
    this.timer = setTimeout(() => void (this.mode === 'refresh' ? this.refresh() : this.flush()), this.workspace.settings.diagnosticsDelay);
  }

  private async refresh(): Promise<void> {
    this.timer = undefined;
    this.pending.clear();
    try {
      await this.connection.languages.diagnostics.refresh();
    } catch (error) {
      this.connection.console.error(`workspace/diagnostic/refresh failed: ${(error as Error).stack ?? error}`);
    }
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
    this.onPassDone?.();
    if (this.pending.size > 0 && !this.timer) this.arm();
  }
}
