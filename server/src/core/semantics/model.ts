import { forgetValueEdit, valueEditOf, XmlDocument, XmlElement } from '../xml';
import { CatalogElementCollector } from './catalogElements';
import { EntityCollector } from './entities';
import { carrySemanticModel } from './incremental';
import { ParameterUseCollector } from './parameterUses';
import { ScopeCollector } from './scopes';
import { StoryboardCollector } from './storyboard';
import { Scope, SemanticModel } from './types';
import { VariableCollector } from './variables';
import { coreMemo } from '../memos';

export * from './types';
export { resolveName, visibleDeclarations } from './scopes';
export { referencedName } from './parameterUses';
export { ENTITY_REFERENCE_ATTRIBUTES } from './entities';
export { STORYBOARD_ELEMENT_NAMES, STORYBOARD_ELEMENT_TYPES } from './storyboard';
export { Evaluator } from './evaluator';
export type { Assignments, Provenance, Reading, ValueDifference, ValueResult } from './evaluator';

/** Builds the model of a document in one walk, each element shown to the collector of each kind; linear in its size. */
export function buildSemanticModel(document: XmlDocument): SemanticModel {
  const rootElement = document.root;
  let scopes: ScopeCollector | undefined;
  const model: SemanticModel = {
    document,
    root: undefined,
    scopes: [],
    declarations: [],
    variables: new Map(),
    uses: [],
    sites: [],
    siteOf: new Map(),
    usesOf: new Map(),
    catalogLocations: [],
    catalogReferences: [],
    catalog: undefined,
    entities: [],
    hasEntities: false,
    storyboardElements: [],
    storyboardByName: new Map(),
    storyboardReferences: [],
    variableReferences: [],
    entityReferences: [],
    scopeOf: (element) => scopes?.scopeOf(element),
  };
  if (!rootElement) return model;
  scopes = new ScopeCollector(model, rootElement);
  const uses = new ParameterUseCollector(model);
  const variables = new VariableCollector(model, scopes);
  const catalogElements = new CatalogElementCollector(model, rootElement);
  const entities = new EntityCollector(model);
  const storyboard = new StoryboardCollector(model);

  // One walk in document order with an explicit stack (files nest deeply); two parallel stacks allocate nothing per element.
  const elementStack: XmlElement[] = [rootElement];
  const scopeStack: (Scope | undefined)[] = [undefined];
  while (elementStack.length > 0) {
    const element = elementStack.pop() as XmlElement;
    const scope = scopes.enter(element, scopeStack.pop()) as Scope;
    if (element === rootElement) model.root = scope;
    for (let i = element.children.length - 1; i >= 0; i--) {
      elementStack.push(element.children[i]);
      scopeStack.push(scope);
    }
    // Variables are declared before the uses of the same element are read, as parameters are on entering a scope.
    variables.visit(element, scope);
    uses.visit(element, scope, scopes.declarationByElement.get(element));
    catalogElements.visit(element);
    entities.visit(element);
    storyboard.visit(element);
  }
  variables.finish();
  return model;
}

// Models are pure functions of a parse, which never changes once built.
const models = coreMemo<XmlDocument, SemanticModel>('semanticModels');

/** The model of a parse: carried over from the previous parse's after an edit inside one value, else built. */
export function semanticModelOf(document: XmlDocument): SemanticModel {
  let model = models.get(document);
  if (!model) {
    const edit = valueEditOf(document);
    const previous = edit && models.get(edit.previous);
    model = (edit && previous && carrySemanticModel(previous, edit, document)) ?? buildSemanticModel(document);
    models.set(document, model);
    // The previous parse is no longer needed for this one.
    if (edit) forgetValueEdit(document);
  }
  return model;
}
