import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import type { LibraryListingResult, LibraryModuleSummary, LibraryProblemSummary } from '../../../common/src/libraryProtocol';

export const LIBRARY_VIEW_ID = 'modular2simple.library';

/** What the Scenario Library view shows: groups of modules, each module, and what could not be read. */
export type LibraryNode =
  | { kind: 'group'; label: string; description?: string; modules: LibraryModuleSummary[] }
  | { kind: 'module'; module: LibraryModuleSummary }
  | { kind: 'problems'; problems: LibraryProblemSummary[] }
  | { kind: 'problem'; problem: LibraryProblemSummary };

/** Pictures larger than this are left out of tooltips (the detail view still names the file). */
const MAX_PICTURE_BYTES = 512 * 1024;

/** Whether a module matches every word of the filter, in its name, title, group, doc, actor or parameters. */
export function matchesFilter(module: LibraryModuleSummary, filter: string): boolean {
  const words = filter.toLowerCase().split(/\s+/).filter(Boolean);
  if (words.length === 0) return true;
  const haystack = [
    module.name,
    module.title,
    module.group,
    module.summary,
    module.actor.name,
    module.actor.about,
    ...module.parameters.flatMap((parameter) => [parameter.key, parameter.name, parameter.about, parameter.unit ?? '']),
  ]
    .join('\n')
    .toLowerCase();
  return words.every((word) => haystack.includes(word));
}

/**
 * The view's top level: the built-in library's modules by their doc's `group` (Vehicles ahead, Vulnerable road
 * users, ...), each user library folder as a group of its own, then the files that could not be read.
 */
export function libraryGroups(listing: LibraryListingResult, filter = ''): LibraryNode[] {
  const nodes: LibraryNode[] = [];
  const shown = listing.modules.filter((module) => matchesFilter(module, filter));
  for (const library of listing.libraries) {
    const modules = shown.filter((module) => module.library === library.folder);
    if (library.label === 'built-in') {
      const groups = [...new Set(modules.map((module) => module.group))].sort((a, b) => a.localeCompare(b));
      for (const group of groups)
        nodes.push({
          kind: 'group',
          label: group,
          modules: modules.filter((module) => module.group === group).sort((a, b) => a.title.localeCompare(b.title)),
        });
    } else if (modules.length > 0 || !filter) {
      nodes.push({
        kind: 'group',
        label: path.basename(library.folder),
        description: `your library: ${library.folder}`,
        modules: modules.sort((a, b) => a.group.localeCompare(b.group) || a.title.localeCompare(b.title)),
      });
    }
  }
  if (listing.problems.length > 0) nodes.push({ kind: 'problems', problems: listing.problems });
  return nodes;
}

/** The picture as a data: URI, for a tooltip or the detail page, or undefined when it cannot be read. */
export function pictureDataUri(picture: string | undefined): string | undefined {
  if (!picture) return undefined;
  try {
    const bytes = fs.readFileSync(picture);
    if (bytes.length > MAX_PICTURE_BYTES) return undefined;
    return `data:image/svg+xml;base64,${bytes.toString('base64')}`;
  } catch {
    return undefined;
  }
}

function parameterLine(parameter: LibraryModuleSummary['parameters'][number]): string {
  const unit = parameter.unit ? ` ${parameter.unit}` : '';
  const range = parameter.range ? `, ${parameter.range}${unit}` : '';
  const value = parameter.defaultValue === undefined ? '(no default)' : `${parameter.defaultValue}${parameter.entity ? '' : unit}`;
  return `- \`${parameter.key}\` **${parameter.name}** = ${value}${range}: ${parameter.about}`;
}

/** The module's doc, keys and picture as Markdown, for its tooltip. */
export function moduleMarkdown(module: LibraryModuleSummary): vscode.MarkdownString {
  const markdown = new vscode.MarkdownString(undefined, true);
  markdown.appendMarkdown(`**${module.title}** \`library:${module.name}\` (${module.group})\n\n${module.summary}\n\n`);
  markdown.appendMarkdown(`Actor \`${module.actor.name}\`: ${module.actor.about}\n\n`);
  markdown.appendMarkdown(`${module.parameters.map(parameterLine).join('\n')}\n\n`);
  const picture = pictureDataUri(module.picture);
  if (picture) markdown.appendMarkdown(`![${module.title}](${picture}|width=420)\n\n`);
  markdown.appendMarkdown(`*${module.libraryLabel} library* ${module.file}`);
  return markdown;
}

const PROBLEM_ICON = new vscode.ThemeIcon('error', new vscode.ThemeColor('problemsErrorIcon.foreground'));

/** The Scenario Library view: modules grouped and filtered; a module opens its detail page, its menu inserts it into a main. */
export class LibraryTree implements vscode.TreeDataProvider<LibraryNode> {
  private readonly changes = new vscode.EventEmitter<LibraryNode | undefined>();
  readonly onDidChangeTreeData = this.changes.event;
  private listing: LibraryListingResult | undefined;
  private filterText = '';

  get current(): LibraryListingResult | undefined {
    return this.listing;
  }

  get filter(): string {
    return this.filterText;
  }

  show(listing: LibraryListingResult): void {
    this.listing = listing;
    this.changes.fire(undefined);
  }

  setFilter(filter: string): void {
    this.filterText = filter.trim();
    this.changes.fire(undefined);
  }

  /** The modules the view shows now (after the filter). */
  visibleModules(): LibraryModuleSummary[] {
    return (this.listing?.modules ?? []).filter((module) => matchesFilter(module, this.filterText));
  }

  getChildren(node?: LibraryNode): LibraryNode[] {
    if (!this.listing) return [];
    if (!node) return libraryGroups(this.listing, this.filterText);
    if (node.kind === 'group') return node.modules.map((module) => ({ kind: 'module', module }));
    if (node.kind === 'problems') return node.problems.map((problem) => ({ kind: 'problem', problem }));
    return [];
  }

  getTreeItem(node: LibraryNode): vscode.TreeItem {
    switch (node.kind) {
      case 'group': {
        const item = new vscode.TreeItem(node.label, vscode.TreeItemCollapsibleState.Expanded);
        item.description = node.description ?? `${node.modules.length}`;
        item.iconPath = new vscode.ThemeIcon('library');
        item.contextValue = 'libraryGroup';
        return item;
      }
      case 'module': {
        const { module } = node;
        const item = new vscode.TreeItem(module.title, vscode.TreeItemCollapsibleState.None);
        item.id = `module:${module.file}`;
        item.description = `library:${module.name}`;
        item.tooltip = moduleMarkdown(module);
        item.iconPath = new vscode.ThemeIcon(module.group.toLowerCase().includes('vulnerable') ? 'person' : 'symbol-class');
        item.contextValue = 'libraryModule';
        item.command = { command: 'modular2simple.library.showModule', title: 'Show Module', arguments: [node] };
        return item;
      }
      case 'problems': {
        const item = new vscode.TreeItem(`Could not be read (${node.problems.length})`, vscode.TreeItemCollapsibleState.Expanded);
        item.iconPath = PROBLEM_ICON;
        item.tooltip = 'Library folders or files that are no usable module; the rest of the library is listed.';
        return item;
      }
      case 'problem': {
        const { problem } = node;
        const item = new vscode.TreeItem(
          `${path.basename(problem.file)}${problem.line ? `:${problem.line}` : ''}`,
          vscode.TreeItemCollapsibleState.None,
        );
        item.description = problem.message;
        item.tooltip = `${problem.file}${problem.line ? `:${problem.line}` : ''}\n${problem.message}`;
        item.iconPath = PROBLEM_ICON;
        item.contextValue = 'libraryProblem';
        if (fs.existsSync(problem.file) && !fs.statSync(problem.file).isDirectory()) {
          const line = Math.max(0, (problem.line ?? 1) - 1);
          item.command = {
            command: 'vscode.open',
            title: 'Open',
            arguments: [vscode.Uri.file(problem.file), { selection: new vscode.Range(line, 0, line, 0) }],
          };
        }
        return item;
      }
    }
  }

  dispose(): void {
    this.changes.dispose();
  }
}
