import * as vscode from 'vscode';
import type { StructureNode } from '../../common/src/protocol';

export const STRUCTURE_VIEW_ID = 'modular2simple.structure';

const ICONS: Record<StructureNode['kind'], vscode.ThemeIcon> = {
  main: new vscode.ThemeIcon('file-code'),
  package: new vscode.ThemeIcon('package'),
  scenario: new vscode.ThemeIcon('file'),
  group: new vscode.ThemeIcon('symbol-class'),
  reference: new vscode.ThemeIcon('references'),
  missing: new vscode.ThemeIcon('warning', new vscode.ThemeColor('problemsWarningIcon.foreground')),
};

/** The reference graph of a main file (main file, nested packages, simple scenarios, groups), as the paper's Fig. 2. */
export class StructureTree implements vscode.TreeDataProvider<StructureNode> {
  private readonly changes = new vscode.EventEmitter<StructureNode | undefined>();
  readonly onDidChangeTreeData = this.changes.event;
  private root: StructureNode | undefined;

  get current(): StructureNode | undefined {
    return this.root;
  }

  show(root: StructureNode | undefined): void {
    this.root = root;
    this.changes.fire(undefined);
  }

  getTreeItem(node: StructureNode): vscode.TreeItem {
    const collapsible =
      node.children.length === 0
        ? vscode.TreeItemCollapsibleState.None
        : node.kind === 'group'
          ? vscode.TreeItemCollapsibleState.Collapsed
          : vscode.TreeItemCollapsibleState.Expanded;
    const item = new vscode.TreeItem(node.label, collapsible);
    item.description = node.detail;
    item.iconPath = ICONS[node.kind];
    item.contextValue = node.kind;
    item.tooltip = node.detail ? `${node.label}\n${node.detail}` : node.label;
    if (node.uri) {
      const position = new vscode.Position(node.line ?? 0, node.character ?? 0);
      const options: vscode.TextDocumentShowOptions = { selection: new vscode.Range(position, position), preview: true };
      item.resourceUri = vscode.Uri.parse(node.uri);
      item.command = { title: 'Open', command: 'vscode.open', arguments: [vscode.Uri.parse(node.uri), options] };
    }
    return item;
  }

  getChildren(node?: StructureNode): StructureNode[] {
    if (!node) return this.root ? [this.root] : [];
    return node.children;
  }

  dispose(): void {
    this.changes.dispose();
  }
}
