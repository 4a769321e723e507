import { CatalogLoader } from '../semantics/catalogs';
import { entryFreeParameters } from '../semantics/checks';
import { Evaluator } from '../semantics/evaluator';
import { semanticModelOf } from '../semantics/model';
import { ScenarioStore, SourceRef } from '../sources';
import { XmlDocument } from '../xml';

/** A stretch of a file's text, by offsets. */
export interface TextRange {
  start: number;
  end: number;
}

/**
 * What the catalog entries referenced within `ranges` of a scenario read from it without declaring it (esmini's
 * synchronize.xosc: HWManeuvers' Synchronize_NPC reads $AccRate), by CatalogReference start offset
 * (ModularizeInput.catalogParameters): a simple scenario holding such a reference declares them too, or it would not
 * load on its own. Serves both *Extract to a simple scenario…* and `modularize`; only a scenario with a
 * CatalogReference inside a range pays for resolving its catalogs.
 */
export async function catalogParametersOf(
  store: ScenarioStore,
  ref: SourceRef,
  document: XmlDocument,
  ranges: readonly TextRange[],
): Promise<Map<number, string[]>> {
  const found = new Map<number, string[]>();
  const within = (start: number, end: number) => ranges.some((range) => start >= range.start && end <= range.end);
  if (!ranges.some((range) => /<CatalogReference\b/.test(document.text.slice(range.start, range.end)))) return found;
  const model = semanticModelOf(document);
  const resolution = await new CatalogLoader(store).resolve(ref, model, new Evaluator(model));
  for (const reference of resolution.references) {
    const element = reference.reference.element;
    if (!within(element.start, element.end)) continue;
    const names = [...entryFreeParameters(reference)];
    if (names.length > 0) found.set(element.start, names);
  }
  return found;
}
