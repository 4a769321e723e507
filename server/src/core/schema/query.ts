import { XmlDocument, XmlElement } from '../xml';
import { SchemaIndex, schemaIndex } from './index';
import { AttributeDeclaration, ElementParticle } from './model';
import { chooseVersion, SchemaVersionSetting } from './version';
import { coreMemo } from '../memos';

/** The schema index a document is read against, or undefined when schema support is off. */
export function indexFor(document: XmlDocument, setting: SchemaVersionSetting | 'off'): SchemaIndex | undefined {
  return setting === 'off' ? undefined : schemaIndex(chooseVersion(document, setting).version);
}

/** The complex type of an element, found by following its ancestors' content models from the root. */
export function typeOfElement(index: SchemaIndex, element: XmlElement): string | undefined {
  // A parse never changes, so an element's type is computed once per schema (override checks ask on every edit).
  let known = typesByIndex.get(index);
  if (!known) typesByIndex.set(index, (known = new WeakMap()));
  if (known.has(element)) return known.get(element);
  const typeName = typeAlongChain(index, element);
  known.set(element, typeName);
  return typeName;
}

const typesByIndex = coreMemo<SchemaIndex, WeakMap<XmlElement, string | undefined>>('elementTypes');

function typeAlongChain(index: SchemaIndex, element: XmlElement): string | undefined {
  const chain: XmlElement[] = [];
  for (let current: XmlElement | undefined = element; current; current = current.parent) chain.unshift(current);
  if (chain[0].name !== index.schema.rootElement) return undefined;
  let typeName: string | undefined = index.schema.rootType;
  for (const next of chain.slice(1)) {
    typeName = typeName === undefined ? undefined : index.childParticle(typeName, next.name, true)?.type;
    if (typeName === undefined) return undefined;
  }
  return typeName;
}

/** The particle through which an element stands in its parent, when the parent's type is known. */
export function particleOfElement(index: SchemaIndex, element: XmlElement): ElementParticle | undefined {
  const parentType = element.parent ? typeOfElement(index, element.parent) : undefined;
  if (element.parent === undefined && element.name === index.schema.rootElement) {
    return { kind: 'element', name: element.name, type: index.schema.rootType, min: 1, max: 1 };
  }
  return parentType ? index.childParticle(parentType, element.name, true) : undefined;
}

export interface AllowedChild {
  particle: ElementParticle;
  /** The content is incomplete without it at this point. */
  required: boolean;
}

/**
 * The elements that may follow `preceding` (children names already written) in an element of type
 * `typeName`; required: those that must be written before `following` (the next child written), or
 * before the end when nothing follows.
 */
export function allowedChildren(index: SchemaIndex, typeName: string, preceding: string[], following?: string): AllowedChild[] {
  const type = index.complexType(typeName);
  if (!type?.content) return [];
  if (type.content.kind === 'all') {
    return index
      .childParticles(typeName)
      .filter((particle) => particle.max === -1 || preceding.filter((name) => name === particle.name).length < particle.max)
      .map((particle) => ({ particle, required: particle.min > 0 && !preceding.includes(particle.name) }));
  }
  const automaton = index.automaton(typeName);
  let states = automaton.start;
  for (const name of preceding) states = automaton.step(states, index.modelName(typeName, name, true))?.states ?? states;
  const followingName = following === undefined ? undefined : index.modelName(typeName, following, true);
  const path =
    followingName === undefined
      ? automaton.missingToEnd(states)
      : automaton.step(states, followingName)
        ? []
        : (automaton.missingBefore(states, followingName) ?? []);
  const required = new Set(path.map((particle) => particle.name));
  // In the content model's order, whatever order the automaton's states hold them in.
  const order = index.childParticles(typeName);
  const allowed = automaton
    .allowed(states)
    .sort((a, b) => order.indexOf(a) - order.indexOf(b))
    .map((particle) => ({ particle, required: required.has(particle.name) }));
  if (allowed.some((entry) => entry.particle.name === 'Maneuver') && typeName === 'ManeuverGroup') {
    const reference = index.childParticle(typeName, 'ScenarioReference', true);
    if (reference) allowed.push({ particle: reference, required: false });
  }
  return allowed;
}

/** The first type whose content model has a child of this name: a guess for elements the parse cannot place. */
export function typeByElementName(index: SchemaIndex, name: string): string | undefined {
  if (name === index.schema.rootElement) return index.schema.rootType;
  for (const typeName of Object.keys(index.schema.complexTypes)) {
    const particle = index.childParticle(typeName, name, true);
    if (particle) return particle.type;
  }
  return undefined;
}

export function requiredAttributes(index: SchemaIndex, typeName: string): AttributeDeclaration[] {
  return (index.complexType(typeName)?.attributes ?? []).filter((declaration) => declaration.required);
}
