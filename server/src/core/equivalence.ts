import { XMLParser } from 'fast-xml-parser';

/** An element tree reduced to what SPEC 8 compares: names, attributes as a set, element children, text. */
export interface CanonicalElement {
  name: string;
  attributes: Record<string, string>;
  children: (CanonicalElement | string)[];
}

type OrderedNode = Record<string, unknown>;

// An independent parser (not our own) so that equivalence checks do not share our parser's mistakes.
const parser = new XMLParser({
  preserveOrder: true,
  ignoreAttributes: false,
  attributeNamePrefix: '',
  parseAttributeValue: false,
  parseTagValue: false,
  trimValues: false,
  ignoreDeclaration: true,
  ignorePiTags: true,
  processEntities: true,
  htmlEntities: false,
});

function canonical(nodes: OrderedNode[]): (CanonicalElement | string)[] {
  const result: (CanonicalElement | string)[] = [];
  for (const node of nodes) {
    for (const key of Object.keys(node)) {
      if (key === ':@') continue;
      if (key === '#text') {
        const value = String(node[key]).trim();
        if (value) result.push(value);
        continue;
      }
      if (key.startsWith('?') || key.startsWith('!') || key === '#comment') continue;
      const attributes: Record<string, string> = {};
      const raw = (node[':@'] ?? {}) as Record<string, unknown>;
      for (const name of Object.keys(raw).sort()) attributes[name] = String(raw[name]);
      result.push({ name: key, attributes, children: canonical((node[key] ?? []) as OrderedNode[]) });
    }
  }
  return result;
}

export function canonicalTree(xml: string): CanonicalElement | undefined {
  const parsed = parser.parse(xml.replace(/^\uFEFF/, '')) as OrderedNode[];
  return canonical(parsed).find((node): node is CanonicalElement => typeof node !== 'string');
}

/** The first difference between two XML documents (SPEC 8), or undefined when they are equivalent. */
export function firstDifference(a: string, b: string): string | undefined {
  const left = canonicalTree(a);
  const right = canonicalTree(b);
  if (!left || !right) return left === right ? undefined : 'one document has no root element';
  const compare = (x: CanonicalElement | string, y: CanonicalElement | string, where: string): string | undefined => {
    if (typeof x === 'string' || typeof y === 'string') {
      return x === y ? undefined : `${where}: text ${JSON.stringify(x)} differs from ${JSON.stringify(y)}`;
    }
    const here = `${where}/${x.name}`;
    if (x.name !== y.name) return `${where}: <${x.name}> differs from <${y.name}>`;
    const names = new Set([...Object.keys(x.attributes), ...Object.keys(y.attributes)]);
    for (const name of names) {
      if (x.attributes[name] !== y.attributes[name]) {
        return `${here}${x.attributes.name ? `[@name='${x.attributes.name}']` : ''}: attribute ${name}=${JSON.stringify(x.attributes[name])} differs from ${JSON.stringify(y.attributes[name])}`;
      }
    }
    const count = Math.max(x.children.length, y.children.length);
    for (let i = 0; i < count; i++) {
      if (x.children[i] === undefined || y.children[i] === undefined) {
        return `${here}: ${x.children.length} children differ from ${y.children.length}`;
      }
      const difference = compare(x.children[i], y.children[i], `${here}[${i}]`);
      if (difference) return difference;
    }
    return undefined;
  };
  return compare(left, right, '');
}
