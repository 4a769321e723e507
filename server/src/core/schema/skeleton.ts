import { SchemaIndex } from './index';
import { AttributeDeclaration, ElementParticle, Particle } from './model';
import { requiredAttributes } from './query';
import { builtinOf, enumerationValues } from './values';

/** A minimal valid element: its required attributes and, recursively, its required children in schema order. */
export interface SkeletonElement {
  name: string;
  /** The complex type's name in the schema. */
  type: string;
  attributes: AttributeDeclaration[];
  children: SkeletonElement[];
}

/** How deep a skeleton goes: deeper required content is left for the user (and for the validator to point at). */
export const SKELETON_DEPTH = 6;

/** A value that the type accepts: its first enumeration value, false, 0, a date, or empty text. */
export function placeholderValue(index: SchemaIndex, typeName: string): string {
  const simple = index.simpleType(typeName);
  if (!simple) return '';
  const values = enumerationValues(simple);
  if (values.length > 0) return values[0];
  const builtin = builtinOf(simple);
  if (builtin === 'boolean') return 'false';
  if (builtin === 'double' || builtin === 'int' || builtin === 'unsignedInt' || builtin === 'unsignedShort') return '0';
  if (builtin === 'dateTime') return '2020-01-01T00:00:00';
  return '';
}

/** Whether the required content of this particle leads back to a type being expanded (a recursive type). */
function reachesAny(index: SchemaIndex, particle: Particle, open: ReadonlySet<string>, seen: Set<string>): boolean {
  if (particle.min === 0) return false;
  if (particle.kind === 'element') {
    if (open.has(particle.type)) return true;
    if (seen.has(particle.type)) return false;
    seen.add(particle.type);
    const content = index.complexType(particle.type)?.content;
    return content !== undefined && reachesAny(index, content, open, seen);
  }
  // A choice recurses only when every alternative does (the skeleton takes one that does not).
  if (particle.kind === 'choice') return particle.items.length > 0 && particle.items.every((item) => reachesAny(index, item, open, seen));
  return particle.items.some((item) => reachesAny(index, item, open, seen));
}

/** The element particles a content model needs at the least, in order: a required choice takes its first alternative that does not recurse. */
function requiredParticles(index: SchemaIndex, particle: Particle, open: ReadonlySet<string>): ElementParticle[] {
  if (particle.min === 0) return [];
  const once = (): ElementParticle[] => {
    if (particle.kind === 'element') return [particle];
    if (particle.kind === 'choice') {
      if (particle.items.length === 0) return [];
      const chosen = particle.items.find((item) => !reachesAny(index, item, open, new Set())) ?? particle.items[0];
      return requiredParticles(index, chosen, open);
    }
    return particle.items.flatMap((item) => requiredParticles(index, item, open));
  };
  const result: ElementParticle[] = [];
  for (let i = 0; i < particle.min; i++) result.push(...once());
  return result;
}

/** The smallest valid element for a particle; bounded by `depth` and never expanding a type inside itself. */
export function elementSkeleton(index: SchemaIndex, particle: ElementParticle, depth = SKELETON_DEPTH): SkeletonElement {
  const build = (current: ElementParticle, level: number, open: ReadonlySet<string>): SkeletonElement => {
    const type = index.complexType(current.type);
    const attributes = requiredAttributes(index, current.type);
    if (!type?.content || level >= depth || open.has(current.type))
      return { name: current.name, type: current.type, attributes, children: [] };
    const inside = new Set(open).add(current.type);
    const children = requiredParticles(index, type.content, inside).map((child) => build(child, level + 1, inside));
    return { name: current.name, type: current.type, attributes, children };
  };
  return build(particle, 1, new Set());
}

export interface SkeletonLayout {
  /** The indentation of the lines after the first (the first line starts wherever it is inserted). */
  indent: string;
  /** One level of indentation. */
  unit: string;
  /** The line break; empty writes the skeleton on one line. */
  eol: string;
}

/** The skeleton as XML text; `value` writes an attribute's value (a placeholder, or a snippet's tab stop). */
export function skeletonText(
  skeleton: SkeletonElement,
  layout: SkeletonLayout,
  value: (declaration: AttributeDeclaration) => string,
): string {
  const write = (element: SkeletonElement, indent: string): string => {
    const open = `<${element.name}${element.attributes.map((declaration) => ` ${declaration.name}="${value(declaration)}"`).join('')}`;
    if (element.children.length === 0) return `${open}/>`;
    // On one line (no line break), no indentation either.
    const inner = layout.eol ? indent + layout.unit : '';
    const children = element.children.map((child) => `${layout.eol}${inner}${write(child, inner)}`).join('');
    return `${open}>${children}${layout.eol}${layout.eol ? indent : ''}</${element.name}>`;
  };
  return write(skeleton, layout.eol ? layout.indent : '');
}

/**
 * The skeleton with an optional child added (as its own skeleton) where the content model accepts it, for
 * an element the schema does not require but a new file wants (ParameterDeclarations, a StopTrigger);
 * unchanged when the child is there already or fits nowhere.
 */
export function withOptionalChild(index: SchemaIndex, element: SkeletonElement, childName: string): SkeletonElement {
  if (element.children.some((child) => child.name === childName)) return element;
  const particle = index.childParticle(element.type, childName, false);
  if (!particle) return element;
  const automaton = index.automaton(element.type);
  const accepts = (names: string[]): boolean => {
    let states = automaton.start;
    for (const name of names) {
      const next = automaton.step(states, name);
      if (!next) return false;
      states = next.states;
    }
    return automaton.accepts(states);
  };
  const names = element.children.map((child) => child.name);
  for (let at = 0; at <= names.length; at++) {
    if (!accepts([...names.slice(0, at), childName, ...names.slice(at)])) continue;
    const children = [...element.children];
    children.splice(at, 0, elementSkeleton(index, particle));
    return { ...element, children };
  }
  return element;
}
