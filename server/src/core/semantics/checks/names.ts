import { attribute, XmlElement } from '../../xml';
import { namedSiblings } from '../elementIndex';
import { coreMemo } from '../../memos';
import type { Finding, SemanticCheck } from './types';
import { at, relatedAt } from './support';
import { duplicateCatalogEntryWording } from '../../diagnostics/duplicateCatalogEntry';
import { duplicateNameWording, firstOfNameNote } from '../../diagnostics/duplicateName';

/**
 * Declarations have their own check (duplicateDeclarations) and the first one wins there; a Property is
 * a key-value pair that nothing references by name (esmini's catalogs repeat `source_reference`).
 */
const NAMES_CHECKED_ELSEWHERE: ReadonlySet<string> = new Set(['ParameterDeclaration', 'VariableDeclaration', 'Property']);

/** A modular file's group that imports groups: flattening names what it holds `OUTER.INNER`, so its own name may repeat (SPEC 2). */
function holdsScenarioReference(element: XmlElement): boolean {
  return element.children.some((child) => child.name === 'ScenarioReference');
}

const DOLLAR = 36;

/** Children lists of `namedSiblings` (kept as they are by a value edit elsewhere) whose names are literals, all different. */
const distinctLiteralNames = coreMemo<readonly XmlElement[], true>('distinctLiteralNames');

/**
 * ManeuverGroups of one name are common in plain scenarios, and SPEC's policy reports them only where a
 * reference names them: a StoryboardElementStateCondition of this file here, a ScenarioReference of
 * another file through `duplicate-group` (core/flatten/link.ts).
 */

/**
 * Element names are unique among the children of one element (ASAM QC
 * `reference_control.unique_element_names_on_same_level`): two Events of one Maneuver, two Acts of one
 * Story, two ScenarioObjects of the Entities. The entries of a catalog are unique too
 * (`uniquely_resolvable_entity_references`: a CatalogReference names exactly one). Names are compared
 * as they evaluate (`$Name` included); reported at the second and each later one. esmini runs each
 * element and resolves a reference to the name to the first one, so by SPEC 12 a repeated name is an error
 * only where a storyboard reference of this file names it (or a catalog entry, which a CatalogReference
 * names), and a warning that says what ASAM's checker says otherwise; with simulator esmini always a warning.
 */
export const duplicateNames: SemanticCheck = (context) => {
  const { model, evaluator } = context;
  const esmini = context.simulator === 'esmini';
  if (!model.document.root) return [];
  const findings: Finding[] = [];
  // Read only once a name repeats: most files have no repeated name.
  let referencedNames: Set<string> | undefined;
  const referenced = () =>
    (referencedNames ??= new Set(
      model.storyboardReferences.map((reference) => reference.refAttribute.value.split('::').pop()?.trim() ?? ''),
    ));
  let referencedEntityNames: Set<string> | undefined;
  const referencedEntities = () =>
    (referencedEntityNames ??= new Set(
      model.entityReferences.map((reference) => evaluator.textOf(reference.element, reference.attribute) ?? reference.attribute.value),
    ));
  // The elements with named siblings, not the whole tree: this runs on each edit.
  for (const { parent, children } of namedSiblings(model)) {
    if (distinctLiteralNames.get(children)) continue;
    let first: Map<string, XmlElement> | undefined;
    // Names written without `$` and all different repeat under no parameters, whatever else the file holds.
    let distinctLiterals = true;
    for (const child of children) {
      const nameAttribute = attribute(child, 'name');
      if (nameAttribute && nameAttribute.value.charCodeAt(0) === DOLLAR) distinctLiterals = false;
      if (!nameAttribute || NAMES_CHECKED_ELSEWHERE.has(child.name) || holdsScenarioReference(child)) continue;
      const name = evaluator.textOf(child, nameAttribute);
      if (name === undefined || name === '') continue;
      first ??= new Map<string, XmlElement>();
      const earlier = first.get(name);
      if (!earlier) {
        first.set(name, child);
        continue;
      }
      distinctLiterals = false;
      if (child.name === 'ManeuverGroup' && !referenced().has(name)) continue;
      const inCatalog = parent === model.catalog;
      const ambiguous = inCatalog || (child.name === 'ScenarioObject' ? referencedEntities().has(name) : referenced().has(name));
      const written = nameAttribute.value;
      const earlierName = attribute(earlier, 'name');
      findings.push({
        ...at(child, nameAttribute),
        ...(inCatalog
          ? duplicateCatalogEntryWording(attribute(parent, 'name')?.value ?? '', name, written, esmini)
          : duplicateNameWording({
              parent: parent.name,
              name,
              written,
              earlier: earlier.name,
              child: child.name,
              referenced: ambiguous,
              esmini,
            })),
        related: [
          relatedAt(context, earlierName?.valueStart ?? earlier.start, earlierName?.valueEnd ?? earlier.nameEnd, firstOfNameNote(name)),
        ],
      });
    }
    if (distinctLiterals) distinctLiteralNames.set(children, true);
  }
  return findings;
};
