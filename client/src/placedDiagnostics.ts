import * as vscode from 'vscode';
import type { ProblemSummary } from '../../common/src/protocol';
import { placedByUri, type PlacedMessage } from './placed';

const SEVERITY: Record<PlacedMessage['severity'], vscode.DiagnosticSeverity> = {
  error: vscode.DiagnosticSeverity.Error,
  warning: vscode.DiagnosticSeverity.Warning,
  information: vscode.DiagnosticSeverity.Information,
  hint: vscode.DiagnosticSeverity.Hint,
};

/** A diagnostic collection that one command's last run fills: each run replaces what the previous one showed. */
export class PlacedDiagnostics implements vscode.Disposable {
  readonly collection: vscode.DiagnosticCollection;

  /** `source` is the diagnostics' source as the Problems view shows it. */
  constructor(
    name: string,
    private readonly source: string,
  ) {
    this.collection = vscode.languages.createDiagnosticCollection(name);
  }

  replace(problems: readonly ProblemSummary[]): void {
    this.collection.clear();
    for (const [uri, placed] of placedByUri(problems)) {
      this.collection.set(
        vscode.Uri.parse(uri),
        placed.map((message) => {
          const end = message.end ?? { line: message.start.line, character: Number.MAX_SAFE_INTEGER };
          const diagnostic = new vscode.Diagnostic(
            new vscode.Range(message.start.line, message.start.character, end.line, end.character),
            message.message,
            SEVERITY[message.severity],
          );
          diagnostic.source = this.source;
          if (message.code) diagnostic.code = message.code;
          return diagnostic;
        }),
      );
    }
  }

  clear(): void {
    this.collection.clear();
  }

  dispose(): void {
    this.collection.dispose();
  }
}
