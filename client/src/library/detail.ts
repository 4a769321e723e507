import * as vscode from 'vscode';
import { webviewNonce } from '../webviewNonce';
import type { LibraryModuleSummary } from '../../../common/src/libraryProtocol';
import { pictureDataUri } from './view';

type DetailMessage = { type: 'insert' } | { type: 'open'; what: 'module' | 'example' };

function parseMessage(value: unknown): DetailMessage | undefined {
  if (typeof value !== 'object' || value === null) return undefined;
  const candidate = value as Record<string, unknown>;
  if (candidate.type === 'insert') return { type: 'insert' };
  if (candidate.type === 'open' && (candidate.what === 'module' || candidate.what === 'example'))
    return { type: 'open', what: candidate.what };
  return undefined;
}

function escapeHtml(text: string): string {
  return text.replace(/[&<>"']/g, (character) => `&#${character.charCodeAt(0)};`);
}

/** The detail page of a module: its doc, its keys with units, ranges and defaults, and its picture. */
export function detailHtml(module: LibraryModuleSummary, cspSource: string, script: string): string {
  const rows = module.parameters
    .map(
      (parameter) =>
        `<tr><td><code>${escapeHtml(parameter.key)}</code></td><td>${escapeHtml(parameter.name)}</td><td>${escapeHtml(parameter.defaultValue ?? '')}</td><td>${escapeHtml(parameter.unit ?? '')}</td><td>${escapeHtml(parameter.range ?? '')}</td><td>${escapeHtml(parameter.about)}</td></tr>`,
    )
    .join('\n');
  const picture = pictureDataUri(module.picture);
  const pictureHtml = picture
    ? `<img alt="${escapeHtml(`${module.title}: the example main run in esmini`)}" src="${picture}">`
    : `<p>No picture${module.picture ? ` (${escapeHtml(module.picture)} could not be read)` : ''}.</p>`;
  const hides = module.hides
    .map((file) => `<p class="note">Hides ${escapeHtml(file)} (a later library's module of the same name).</p>`)
    .join('');
  return `<!DOCTYPE html>
<html lang="en"><head><meta charset="UTF-8">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src data: ${cspSource}; style-src 'unsafe-inline' ${cspSource}; script-src 'nonce-${script}';">
<style>
body { font-family: var(--vscode-font-family); color: var(--vscode-foreground); padding: 0 1em; }
table { border-collapse: collapse; margin: 0.5em 0; } td, th { border: 1px solid var(--vscode-panel-border); padding: 2px 6px; text-align: left; vertical-align: top; }
img { max-width: 100%; background: #f6f8fa; } .note { opacity: 0.8; } button { margin-right: 0.5em; }
</style></head><body>
<h2>${escapeHtml(module.title)} <code>library:${escapeHtml(module.name)}</code></h2>
<p><button id="insert">Insert into Main</button><button data-open="module">Open Module</button>${module.example ? '<button data-open="example">Open Example Main</button>' : ''}</p>
<p>${escapeHtml(module.summary)}</p>
<p><b>Actor</b> <code>${escapeHtml(module.actor.name)}</code>: ${escapeHtml(module.actor.about)}. <b>Group</b> <code>${escapeHtml(module.maneuverGroup)}</code> (${escapeHtml(module.group)}).</p>
<table><tr><th>key</th><th>name</th><th>default</th><th>unit</th><th>range</th><th>what it is</th></tr>
${rows}
</table>
${pictureHtml}
<p class="note">${escapeHtml(module.libraryLabel)} library: ${escapeHtml(module.file)}</p>${hides}
<script nonce="${script}">
const vscode = acquireVsCodeApi();
document.getElementById('insert').addEventListener('click', () => vscode.postMessage({ type: 'insert' }));
for (const button of document.querySelectorAll('[data-open]'))
  button.addEventListener('click', () => vscode.postMessage({ type: 'open', what: button.dataset.open }));
</script>
</body></html>`;
}

/** One panel beside the editor that shows the module last chosen in the Scenario Library view. */
export class LibraryDetail implements vscode.Disposable {
  private panel: vscode.WebviewPanel | undefined;
  private module: LibraryModuleSummary | undefined;

  constructor(private readonly insert: (module: LibraryModuleSummary) => Promise<unknown>) {}

  get shown(): LibraryModuleSummary | undefined {
    return this.panel ? this.module : undefined;
  }

  get html(): string | undefined {
    return this.panel?.webview.html;
  }

  show(module: LibraryModuleSummary): void {
    this.module = module;
    if (!this.panel) {
      this.panel = vscode.window.createWebviewPanel(
        'modular2simple.libraryModule',
        module.title,
        { viewColumn: vscode.ViewColumn.Beside, preserveFocus: true },
        { enableScripts: true, localResourceRoots: [] },
      );
      this.panel.onDidDispose(() => (this.panel = undefined));
      this.panel.webview.onDidReceiveMessage(async (received: unknown) => {
        const message = parseMessage(received);
        const shown = this.module;
        if (!message || !shown) return;
        if (message.type === 'insert') await this.insert(shown);
        else {
          const file = message.what === 'module' ? shown.file : shown.example;
          if (file) await vscode.window.showTextDocument(vscode.Uri.file(file), { viewColumn: vscode.ViewColumn.One });
        }
      });
    }
    this.panel.title = `Library: ${module.title}`;
    this.panel.webview.html = detailHtml(module, this.panel.webview.cspSource, webviewNonce());
    this.panel.reveal(undefined, true);
  }

  dispose(): void {
    this.panel?.dispose();
  }
}
