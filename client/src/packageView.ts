import * as vscode from 'vscode';
import { webviewNonce } from './webviewNonce';
import * as archive from './packageArchive';
import { packageEntryUri } from './packageFileSystem';

export const PACKAGE_VIEW_TYPE = 'modular2simple.packageView';

/** What the package's page may ask for: open one of its files, or run one of the package commands on it. */
type PackageViewMessage = { type: 'open'; entry: string } | { type: 'run'; command: PackageAction };

const PACKAGE_ACTIONS = {
  'modular2simple.openPreview': 'Open Flattened Preview',
  'modular2simple.showStructure': 'Show Structure',
  'modular2simple.flatten': 'Flatten to .xosc',
} as const;
type PackageAction = keyof typeof PACKAGE_ACTIONS;

function parseMessage(value: unknown): PackageViewMessage | undefined {
  if (typeof value !== 'object' || value === null) return undefined;
  const candidate = value as Record<string, unknown>;
  if (candidate.type === 'open' && typeof candidate.entry === 'string') return { type: 'open', entry: candidate.entry };
  if (candidate.type === 'run' && typeof candidate.command === 'string' && candidate.command in PACKAGE_ACTIONS) {
    return { type: 'run', command: candidate.command as PackageAction };
  }
  return undefined;
}

function escapeHtml(text: string): string {
  return text.replace(/[&<>"']/g, (character) => `&#${character.charCodeAt(0)};`);
}

/** Opening a `.mosc` shows the files inside it; each opens in place through the `mosc:` file system. */
export class PackageViewProvider implements vscode.CustomReadonlyEditorProvider {
  constructor(private readonly log: (message: string) => void) {}

  openCustomDocument(uri: vscode.Uri): vscode.CustomDocument {
    return { uri, dispose: () => undefined };
  }

  async resolveCustomEditor(document: vscode.CustomDocument, panel: vscode.WebviewPanel): Promise<void> {
    const script = webviewNonce();
    panel.webview.options = { enableScripts: true, localResourceRoots: [] };
    const render = async (): Promise<void> => {
      panel.webview.html = await this.html(document.uri, script, panel.webview.cspSource);
    };
    panel.webview.onDidReceiveMessage(async (received: unknown) => {
      const message = parseMessage(received);
      if (message?.type === 'open') await vscode.commands.executeCommand('vscode.open', packageEntryUri(document.uri, message.entry));
      if (message?.type === 'run') await vscode.commands.executeCommand(message.command, document.uri);
    });
    const watcher = vscode.workspace.createFileSystemWatcher(
      new vscode.RelativePattern(vscode.Uri.joinPath(document.uri, '..'), document.uri.path.split('/').pop() ?? ''),
    );
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
      const actions = Object.entries(PACKAGE_ACTIONS)
        .map(([command, title]) => `<button data-command="${command}">${escapeHtml(title)}</button>`)
        .join(' ');
      body = `<p>${actions}</p><p>${entries.length} entries. Click a file to open, edit and save it inside the package.</p><ul>${items}</ul>`;
    } catch (error) {
      this.log(`${uri.fsPath}: ${(error as Error).message}`);
      body = `<p class="error">${escapeHtml((error as Error).message)}</p><p>The package was left unchanged. Rebuild it with <b>Pack into .mosc</b> from its unpacked folder.</p>`;
    }
    return `<!DOCTYPE html><html><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; style-src ${cspSource} 'unsafe-inline'; script-src 'nonce-${script}';">
<style>body{font-family:var(--vscode-font-family);color:var(--vscode-foreground)} ul{list-style:none;padding-left:0} li{margin:.2em 0}
a{color:var(--vscode-textLink-foreground)} button{color:var(--vscode-button-foreground);background:var(--vscode-button-background);border:none;padding:4px 10px;margin-right:6px;cursor:pointer} .main{font-weight:bold} .package::before{content:'📦 '} .error{color:var(--vscode-errorForeground)}</style>
</head><body><h2>${escapeHtml(uri.path.split('/').pop() ?? uri.path)}</h2>${body}
<script nonce="${script}">const vscode = acquireVsCodeApi();
document.querySelectorAll('a[data-entry]').forEach((link) => link.addEventListener('click', (event) => { event.preventDefault(); vscode.postMessage({ type: 'open', entry: link.dataset.entry }); }));
document.querySelectorAll('button[data-command]').forEach((button) => button.addEventListener('click', () => vscode.postMessage({ type: 'run', command: button.dataset.command })));</script>
</body></html>`;
  }
}
