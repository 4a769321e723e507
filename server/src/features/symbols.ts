import { CodeLens, DocumentSymbol, SymbolInformation, SymbolKind } from 'vscode-languageserver/node';
import { attribute, XmlDocument, XmlElement } from '../core/xml';
import { displayRef, SourceRef } from '../core/sources';
import { Workspace } from '../workspace';

const OUTLINE: Record<string, { kind: SymbolKind; nameAttribute: string }> = {
  Storyboard: { kind: SymbolKind.Namespace, nameAttribute: 'name' },
  Init: { kind: SymbolKind.Constructor, nameAttribute: 'name' },
  Story: { kind: SymbolKind.Module, nameAttribute: 'name' },
  Act: { kind: SymbolKind.Package, nameAttribute: 'name' },
  ManeuverGroup: { kind: SymbolKind.Class, nameAttribute: 'name' },
  Maneuver: { kind: SymbolKind.Method, nameAttribute: 'name' },
  Event: { kind: SymbolKind.Event, nameAttribute: 'name' },
  ScenarioReference: { kind: SymbolKind.File, nameAttribute: 'scenarioFileName' },
  ManeuverGroupReference: { kind: SymbolKind.Interface, nameAttribute: 'maneuverGroupName' },
  ScenarioObject: { kind: SymbolKind.Variable, nameAttribute: 'name' },
};

/** The outline: Storyboard, Story, Act, ManeuverGroup (with maneuvers and events), references and entities. */
export function documentSymbols(document: XmlDocument): DocumentSymbol[] {
  const lines = document.lines;
  const collect = (element: XmlElement, into: DocumentSymbol[]) => {
    // An explicit stack bounds recursion on deeply nested input.
    const stack: { element: XmlElement; into: DocumentSymbol[] }[] = [{ element, into }];
    while (stack.length > 0) {
      const { element: current, into: target } = stack.pop() as { element: XmlElement; into: DocumentSymbol[] };
      const outline = OUTLINE[current.name];
      let childTarget = target;
      if (outline) {
        const named = attribute(current, outline.nameAttribute);
        const symbol: DocumentSymbol = {
          name: named?.value || current.name,
          detail: named?.value ? current.name : undefined,
          kind: outline.kind,
          range: lines.range(current.start, Math.max(current.end, current.startTagEnd)),
          selectionRange: named ? lines.range(named.valueStart, named.valueEnd) : lines.range(current.start, current.nameEnd),
          children: [],
        };
        target.push(symbol);
        childTarget = symbol.children as DocumentSymbol[];
      }
      for (let index = current.children.length - 1; index >= 0; index--)
        stack.push({ element: current.children[index], into: childTarget });
    }
  };
  const symbols: DocumentSymbol[] = [];
  if (document.root) collect(document.root, symbols);
  return symbols;
}

/** ManeuverGroups of every scenario file of the workspace whose name holds the query's characters in order. */
export async function workspaceSymbols(workspace: Workspace, query: string, limit = 1000): Promise<SymbolInformation[]> {
  const wanted = query.toLowerCase();
  const matches = (name: string) => {
    let position = 0;
    const lowered = name.toLowerCase();
    for (const char of wanted) {
      position = lowered.indexOf(char, position) + 1;
      if (position === 0) return false;
    }
    return true;
  };
  const symbols: SymbolInformation[] = [];
  for (const file of await workspace.indexedFiles()) {
    for (const group of file.groups) {
      if (!group.name || !matches(group.name)) continue;
      symbols.push({
        name: group.name,
        kind: SymbolKind.Class,
        location: { uri: workspace.uriOf(group.ref), range: group.range },
        containerName: displayRef(group.ref, workspace.folders[0]),
      });
      if (symbols.length >= limit) return symbols;
    }
  }
  return symbols;
}

export const OPEN_PREVIEW_COMMAND = 'modular2simple.openPreview';

function counted(count: number, noun: string): string {
  return `${count} ${noun}${count === 1 ? '' : 's'}`;
}

/** "1 attribute overridden", "21 attributes overridden". */
export function attributesOverridden(applied: number): string {
  return `${counted(applied, 'attribute')} overridden`;
}

/** What a reference's keys do, in words: "15 keys override 21 attributes", "1 key overrides 1 attribute". */
export function overrideSummary(keys: number, applied: number): string {
  if (keys === 0) return 'no keys: defaults only';
  return `${counted(keys, 'key')} override${keys === 1 ? 's' : ''} ${counted(applied, 'attribute')}`;
}

/** Lenses on each ScenarioReference: how many overrides take effect, and the flatten preview. */
export async function codeLenses(workspace: Workspace, uri: string, ref: SourceRef): Promise<CodeLens[]> {
  const source = await workspace.source(ref);
  const model = source.original;
  if (!model) return [];
  const lenses: CodeLens[] = [];
  for (const link of source.links) {
    const range = model.document.lines.range(link.info.element.start, link.info.element.nameEnd);
    const applied = link.groups.reduce((count, group) => count + (group.plan?.applied.size ?? 0), 0);
    const written = link.groups.reduce((count, group) => count + group.info.parameters.length, 0);
    const title = link.source ? overrideSummary(written, applied) : 'unresolved reference';
    lenses.push({ range, command: { title, command: '' } });
    // The line lets the preview open at the groups this reference imports.
    lenses.push({
      range,
      command: { title: 'flatten preview', command: OPEN_PREVIEW_COMMAND, arguments: [uri, { line: range.start.line }] },
    });
  }
  return lenses;
}
