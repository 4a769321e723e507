import { IN_CATALOG_ENTRY_NOTE, inCatalogEntryWording } from '../../diagnostics/simulator';
import type { RelatedProblemLocation } from '../../problems';
import { baseName } from '../../sources';
import { attribute, XmlAttribute, XmlElement } from '../../xml';
import type { CatalogEntry, CatalogReferenceResolution } from '../catalogs';
import type { Finding, SemanticContext } from './types';

/** A finding's place: an attribute's value, or the element's start tag name. */
export function at(element: XmlElement, attr: XmlAttribute | undefined): Pick<Finding, 'element' | 'attribute' | 'start' | 'end'> {
  return attr
    ? { element, attribute: attr, start: attr.valueStart, end: attr.valueEnd }
    : { element, attribute: undefined, start: element.start, end: element.nameEnd };
}

/** An attribute's value as a number after `$parameter`/`${...}` evaluation; undefined when it is absent or no number (other rules report that). */
export function numberOf(context: SemanticContext, element: XmlElement, name: string): { attr: XmlAttribute; value: number } | undefined {
  const attr = attribute(element, name);
  const text = context.evaluator.textOf(element, attr);
  if (!attr || text === undefined || text.trim() === '') return undefined;
  const value = Number(text);
  return Number.isNaN(value) ? undefined : { attr, value };
}

export function relatedAt(context: SemanticContext, start: number, end: number, message: string): RelatedProblemLocation {
  return { source: context.ref, range: context.model.document.lines.range(start, end), message };
}

/** Whether an element lies in an entry of the document's own catalog (below a child of its `Catalog`). */
export function inCatalogEntry(context: SemanticContext, element: XmlElement): boolean {
  const catalog = context.model.catalog;
  if (!catalog) return false;
  for (let current = element.parent; current; current = current.parent) if (current === catalog) return true;
  return false;
}

/**
 * A simulator's findings (`code` 'simulator') in each catalog entry the document references, placed on the
 * CatalogReference, the entry's file and line in the message: a simulator reads an entry only where a scenario
 * uses it, so an entry no scenario references is no problem. A suggested edit would be in the catalog, not here.
 */
export function onCatalogReferences(
  context: SemanticContext,
  check: (entry: CatalogEntry, resolution: CatalogReferenceResolution) => Finding[],
): Finding[] {
  // Each entry is checked once, however many references use it.
  const checked = new Map<XmlElement, Finding[]>();
  return context.catalogs.references.flatMap((resolution) => {
    const entry = resolution.entry;
    if (!entry) return [];
    const { reference } = resolution;
    const lines = entry.file.model.document.lines;
    let findings = checked.get(entry.element);
    if (!findings) checked.set(entry.element, (findings = check(entry, resolution)));
    return findings.flatMap((finding): Finding[] => {
      if (finding.code !== 'simulator') return [];
      const exportMaps = finding.data !== undefined && 'exportMaps' in finding.data && finding.data.exportMaps === true;
      const wording = { severity: finding.severity, code: finding.code, message: finding.message, hint: finding.hint };
      const place = lines.positionAt(finding.start);
      return [
        {
          ...at(reference.element, reference.entryNameAttribute),
          ...inCatalogEntryWording(wording, {
            name: entry.name,
            file: baseName(entry.file.ref),
            line: place.line + 1,
            column: place.character + 1,
          }),
          // Its own place in the catalog, which the command line prints on a line of its own and the editor links to.
          related: [
            { source: entry.file.ref, range: lines.range(finding.start, finding.end), message: IN_CATALOG_ENTRY_NOTE },
            ...(finding.related ?? []),
          ],
          ...(exportMaps ? { data: { exportMaps: true } } : {}),
        },
      ];
    });
  });
}
