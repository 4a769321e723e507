import * as vscode from 'vscode';
import * as archive from './packageArchive';
import { packageEntryUri } from './packageFileSystem';

export const PACKAGE_VIEW_TYPE = 'modular2simple.packageView';

interface OpenEntryMessage {
  type: 'open';
  entry: string;
}

function isOpenEntryMessage(value: unknown): value is OpenEntryMessage {
  const candidate = value as Partial<OpenEntryMessage> | null;
  return typeof candidate === 'object' && candidate !== null && candidate.type === 'open' && typeof candidate.entry === 'string';
}

function escapeHtml(text: string): string {
  return text.replace(/[&<>"']/g, (character) => `&#${character.charCodeAt(0)};`);
}

function nonce(): string {
  return Array.from({ length: 16 }, () => Math.floor(Math.random() * 36).toString(36)).join('');
}

/** Opening a `.mosc` shows the files inside it; each opens in place through the `mosc:` file system. */
export class PackageViewProvider implements vscode.CustomReadonlyEditorProvider {
  constructor(private readonly log: (message: string) => void) {}

  openCustomDocument(uri: vscode.Uri): vscode.CustomDocument {
    return { uri, dispose: () => undefined };
  }

  async resolveCustomEditor(document: vscode.CustomDocument, panel: vscode.WebviewPanel): Promise<void> {
    const script = nonce();
    panel.webview.options = { enableScripts: true, localResourceRoots: [] };
    const render = async (): Promise<void> => {
      panel.webview.html = await this.html(document.uri, script, panel.webview.cspSource);
    };
    panel.webview.onDidReceiveMessage(async (message: unknown) => {
      if (!isOpenEntryMessage(message)) return;
      await vscode.commands.executeCommand('vscode.open', packageEntryUri(document.uri, message.entry));
    });
    const watcher = vscode.workspace.createFileSystemWatcher(new vscode.RelativePattern(vscode.Uri.joinPath(document.uri, '..'), document.uri.path.split('/').pop() ?? ''));
    watcher.onDidChange(render);
    panel.onDidDispose(() => watcher.dispose());
    await render();
  }

  private async html(uri: vscode.Uri, script: string, cspSource: string): Promise<string> {
    let body: string;
    try {
      const entries = await archive.listAll(await archive.locate(uri.fsPath));
      const items = entries
        .map((entry) => {
          const depth = entry.split('/').length - 1;
          const isMain = entry === 'main.xosc';
          const label = escapeHtml(entry.split('/').pop() ?? entry);
          const link = entry.toLowerCase().endsWith('.mosc')
            ? `<span class="package">${label}</span>`
            : `<a href="#" data-entry="${escapeHtml(entry)}"${isMain ? ' class="main"' : ''}>${label}</a>`;
          return `<li style="padding-left:${depth * 1.2}em">${link}</li>`;
        })
        .join('\n');
      body = `<p>${entries.length} entries. Click a file to open, edit and save it inside the package.</p><ul>${items}</ul>`;
    } catch (error) {
      this.log(`${uri.fsPath}: ${(error as Error).message}`);
      body = `<p class="error">${escapeHtml((error as Error).message)}</p><p>The package was left unchanged. Rebuild it with <b>Pack into .mosc</b> from its unpacked folder.</p>`;
    }
    return `<!DOCTYPE html><html><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; style-src ${cspSource} 'unsafe-inline'; script-src 'nonce-${script}';">
<style>body{font-family:var(--vscode-font-family);color:var(--vscode-foreground)} ul{list-style:none;padding-left:0} li{margin:.2em 0}
a{color:var(--vscode-textLink-foreground)} .main{font-weight:bold} .package::before{content:'📦 '} .error{color:var(--vscode-errorForeground)}</style>
</head><body><h2>${escapeHtml(uri.path.split('/').pop() ?? uri.path)}</h2>${body}
<script nonce="${script}">const vscode = acquireVsCodeApi();
document.querySelectorAll('a[data-entry]').forEach((link) => link.addEventListener('click', (event) => { event.preventDefault(); vscode.postMessage({ type: 'open', entry: link.dataset.entry }); }));</script>
</body></html>`;
  }
}
