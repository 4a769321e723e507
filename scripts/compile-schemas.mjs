// Compiles the bundled ASAM OpenSCENARIO XSDs (schemas/) into one compact JSON model, at build time,
// so that the language server and the CLI never interpret XSD: elements, attributes, simple types
// (enumerations, patterns, built-in bases), cardinalities and sequence/choice/all structure, with the
// version that introduced or deprecated each element, attribute and enumeration value.
import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import * as path from 'node:path';
import { fileURLToPath } from 'node:url';
import { XMLParser } from 'fast-xml-parser';

/**
 * What this writes is what the server reads: its types are the reader's.
 * @typedef {import('../server/src/core/schema/model').CompiledSchema} CompiledSchema
 * @typedef {import('../server/src/core/schema/model').SchemaVersion} SchemaVersion
 * @typedef {import('../server/src/core/schema/model').SimpleType} SimpleType
 * @typedef {import('../server/src/core/schema/model').ComplexType} ComplexType
 * @typedef {import('../server/src/core/schema/model').AttributeDeclaration} AttributeDeclaration
 * @typedef {import('../server/src/core/schema/model').ValueAlternative} ValueAlternative
 * @typedef {import('../server/src/core/schema/model').Particle} Particle
 * @typedef {import('../server/src/core/schema/model').ElementParticle} ElementParticle
 * @typedef {{ tag: string, attributes: Record<string, string>, children: unknown[] }} XsdNode
 */

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

/** The schema files, oldest first, with the version a FileHeader states for them. */
/** @type {{ version: SchemaVersion, file: string }[]} */
export const SCHEMA_FILES = [
  { version: '1.0', file: 'OpenSCENARIOv1.0.xsd' },
  { version: '1.1', file: 'OpenSCENARIOv1.1.1.xsd' },
  { version: '1.2', file: 'OpenSCENARIOv1.2.xsd' },
  { version: '1.3', file: 'OpenSCENARIOv1.3.xsd' },
];

const parser = new XMLParser({ preserveOrder: true, ignoreAttributes: false, attributeNamePrefix: '', commentPropName: '#comment' });

/**
 * The nodes of fast-xml-parser's ordered output: their tag names, attributes and children.
 * @param {unknown[] | undefined} list
 * @returns {XsdNode[]}
 */
function nodes(list) {
  const result = [];
  for (const item of /** @type {Record<string, any>[]} */ (list ?? [])) {
    const tag = Object.keys(item).find((key) => key !== ':@');
    if (!tag || tag === '#text') continue;
    result.push({ tag: tag.replace(/^xsd:/, ''), attributes: item[':@'] ?? {}, children: item[tag] });
  }
  return result;
}

/**
 * @param {XsdNode} node
 * @param {string} tag
 */
function child(node, tag) {
  return nodes(node.children).find((candidate) => candidate.tag === tag);
}

/** True when an annotation of the node says `deprecated` (how 1.1 and later mark deprecation). */
/** @param {XsdNode} node */
function isDeprecated(node) {
  const annotation = child(node, 'annotation');
  if (!annotation) return false;
  return nodes(annotation.children).some((info) => info.tag === 'appinfo' && JSON.stringify(info.children).includes('deprecated'));
}

/** @param {XsdNode} node */
function occurs(node) {
  const min = node.attributes.minOccurs === undefined ? 1 : Number(node.attributes.minOccurs);
  const maxText = node.attributes.maxOccurs;
  const max = maxText === undefined ? 1 : maxText === 'unbounded' ? -1 : Number(maxText);
  return { min, max };
}

/**
 * @param {string} text
 * @param {SchemaVersion} version
 * @returns {Omit<CompiledSchema, 'file'>}
 */
function compileSchema(text, version) {
  const header = (/<!--([\s\S]*?)-->/.exec(text)?.[1] ?? '').trim();
  const document = nodes(parser.parse(text));
  const schema = document.find((node) => node.tag === 'schema');
  if (!schema) throw new Error(`the OpenSCENARIO ${version} schema has no xsd:schema element`);
  const top = nodes(schema.children);
  const groups = new Map(top.filter((node) => node.tag === 'group').map((node) => [node.attributes.name, node]));
  /** @type {Record<string, SimpleType>} */
  const simpleTypes = {};
  /** @type {Record<string, ComplexType>} */
  const complexTypes = {};
  let anonymous = 0;

  /** A simple type as the alternatives a value may match: a built-in base, an enumeration or patterns. */
  /**
   * @param {XsdNode} node
   * @param {string | undefined} name
   * @returns {SimpleType}
   */
  function compileSimple(node, name) {
    /** @type {SimpleType} */
    const compiled = { alternatives: [], parameter: false, expression: false };
    if (isDeprecated(node)) compiled.deprecated = true;
    /** @param {string} memberName */
    const addMember = (memberName) => {
      if (memberName.startsWith('xsd:'))
        compiled.alternatives.push({ builtin: /** @type {ValueAlternative['builtin']} */ (memberName.slice(4)) });
      else {
        if (memberName === 'parameter') compiled.parameter = true;
        else if (memberName === 'expression') compiled.expression = true;
        // A member type by name: none in the bundled schemas, and the reader's ValueAlternative has no field for it.
        else compiled.alternatives.push(/** @type {ValueAlternative} */ ({ ref: memberName }));
      }
    };
    const restriction = child(node, 'restriction');
    const union = child(node, 'union');
    if (restriction) {
      const facets = nodes(restriction.children);
      const values = facets.filter((facet) => facet.tag === 'enumeration');
      const patterns = facets.filter((facet) => facet.tag === 'pattern').map((facet) => facet.attributes.value);
      if (values.length > 0) {
        /** @type {ValueAlternative} */
        const enumeration = { enumeration: values.map((value) => value.attributes.value) };
        const deprecatedValues = values.filter(isDeprecated).map((value) => value.attributes.value);
        if (deprecatedValues.length > 0) enumeration.deprecatedValues = deprecatedValues;
        compiled.alternatives.push(enumeration);
      } else if (patterns.length > 0) {
        compiled.alternatives.push({ patterns });
      } else {
        addMember(restriction.attributes.base);
      }
    } else if (union) {
      for (const member of (union.attributes.memberTypes ?? '').split(/\s+/).filter(Boolean)) addMember(member);
      for (const inner of nodes(union.children).filter((candidate) => candidate.tag === 'simpleType')) {
        const innerCompiled = compileSimple(inner, undefined);
        compiled.parameter ||= innerCompiled.parameter;
        compiled.expression ||= innerCompiled.expression;
        compiled.alternatives.push(...innerCompiled.alternatives);
      }
    }
    if (name !== undefined) simpleTypes[name] = compiled;
    return compiled;
  }

  /** @param {XsdNode} node */
  function attributeType(node) {
    if (node.attributes.type) return node.attributes.type;
    const inline = child(node, 'simpleType');
    const name = `#anonymous${++anonymous}`;
    if (inline) compileSimple(inline, name);
    else simpleTypes[name] = { alternatives: [{ builtin: 'string' }], parameter: false, expression: false };
    return name;
  }

  /**
   * @param {XsdNode[]} list
   * @returns {AttributeDeclaration[]}
   */
  function compileAttributes(list) {
    return list
      .filter((node) => node.tag === 'attribute')
      .map((node) => {
        /** @type {AttributeDeclaration} */
        const attribute = { name: node.attributes.name, type: attributeType(node), required: node.attributes.use === 'required' };
        if (isDeprecated(node)) attribute.deprecated = true;
        return attribute;
      });
  }

  /** A particle: an element, or a sequence/choice/all of particles; groups are inlined where referenced. */
  /**
   * @param {XsdNode} node
   * @returns {Particle}
   */
  function compileParticle(node) {
    const { min, max } = occurs(node);
    if (node.tag === 'element') {
      /** @type {ElementParticle} */
      const element = { kind: 'element', name: node.attributes.name, type: node.attributes.type, min, max };
      if (isDeprecated(node)) element.deprecated = true;
      return element;
    }
    if (node.tag === 'group') {
      const group = groups.get(node.attributes.ref);
      const inner = nodes(group?.children).find((candidate) => ['sequence', 'choice', 'all'].includes(candidate.tag));
      if (!inner) throw new Error(`the OpenSCENARIO ${version} schema has no group ${node.attributes.ref} with a sequence, choice or all`);
      const compiled = compileParticle(inner);
      if (min === 1 && max === 1) return compiled;
      // The reference's occurrence applies to the whole group: wrap it.
      return { kind: 'sequence', min, max, items: [compiled] };
    }
    const items = nodes(node.children)
      .filter((candidate) => ['element', 'group', 'sequence', 'choice', 'all', 'any'].includes(candidate.tag))
      .map(compileParticle);
    return { kind: /** @type {'sequence' | 'choice' | 'all'} */ (node.tag), min, max, items };
  }

  for (const node of top) {
    if (node.tag === 'simpleType') compileSimple(node, node.attributes.name);
  }
  for (const node of top) {
    if (node.tag !== 'complexType') continue;
    /** @type {ComplexType} */
    const compiled = { attributes: [] };
    if (isDeprecated(node)) compiled.deprecated = true;
    const body = nodes(node.children);
    const simpleContent = body.find((candidate) => candidate.tag === 'simpleContent');
    if (simpleContent) {
      const extension = child(simpleContent, 'extension');
      compiled.text = true;
      compiled.attributes = compileAttributes(nodes(extension?.children));
    } else {
      compiled.attributes = compileAttributes(body);
      const content = body.find((candidate) => ['sequence', 'choice', 'all', 'group'].includes(candidate.tag));
      if (content) compiled.content = compileParticle(content);
    }
    complexTypes[node.attributes.name] = compiled;
  }
  const rootElement = top.find((node) => node.tag === 'element' && node.attributes.name === 'OpenSCENARIO');
  if (!rootElement) throw new Error(`the OpenSCENARIO ${version} schema declares no OpenSCENARIO element`);
  return { version, header, rootElement: 'OpenSCENARIO', rootType: rootElement.attributes.type, complexTypes, simpleTypes };
}

/**
 * @param {Particle | undefined} particle
 * @returns {Generator<ElementParticle>}
 */
function* elementParticles(particle) {
  if (!particle) return;
  if (particle.kind === 'element') yield particle;
  else for (const item of particle.items) yield* elementParticles(item);
}

/**
 * Marks each element, attribute and enumeration value with the first version that has it (`since`,
 * left out for 1.0) and the first version that annotates it deprecated (`deprecatedSince`). An
 * element or attribute is matched by its parent type's name; when that type is new, by its own name
 * anywhere, so that a renamed parent does not make old children look new.
 */
/** @param {CompiledSchema[]} schemas */
function addHistory(schemas) {
  /** @type {() => Map<string, string>} */
  const versions = () => new Map();
  const seen = { elementIn: versions(), element: versions(), attributeIn: versions(), attribute: versions(), value: versions() };
  const deprecatedFirst = versions();
  /**
   * @param {Map<string, string>} map
   * @param {string} key
   * @param {string} version
   */
  const note = (map, key, version) => {
    if (!map.has(key)) map.set(key, version);
  };
  for (const schema of schemas) {
    for (const [typeName, type] of Object.entries(schema.complexTypes)) {
      for (const element of elementParticles(type.content)) {
        note(seen.elementIn, `${typeName}/${element.name}`, schema.version);
        note(seen.element, element.name, schema.version);
        const elementType = schema.complexTypes[element.type];
        if (element.deprecated || elementType?.deprecated) note(deprecatedFirst, `e:${typeName}/${element.name}`, schema.version);
      }
      for (const attribute of type.attributes) {
        note(seen.attributeIn, `${typeName}@${attribute.name}`, schema.version);
        note(seen.attribute, attribute.name, schema.version);
        if (attribute.deprecated || schema.simpleTypes[attribute.type]?.deprecated)
          note(deprecatedFirst, `a:${typeName}@${attribute.name}`, schema.version);
      }
    }
    for (const [typeName, type] of Object.entries(schema.simpleTypes)) {
      for (const alternative of type.alternatives) {
        for (const value of alternative.enumeration ?? []) note(seen.value, `${typeName}=${value}`, schema.version);
        for (const value of alternative.deprecatedValues ?? []) note(deprecatedFirst, `v:${typeName}=${value}`, schema.version);
      }
    }
  }
  const firstVersion = schemas[0].version;
  /**
   * @param {string | undefined} specific
   * @param {string} [general]
   */
  const since = (specific, general) => {
    const version = specific ?? general;
    return version && version !== firstVersion ? version : undefined;
  };
  for (const schema of schemas) {
    const older = schemas.slice(0, schemas.indexOf(schema));
    for (const [typeName, type] of Object.entries(schema.complexTypes)) {
      const typeIsNew = !older.some((previous) => previous.complexTypes[typeName]);
      for (const element of elementParticles(type.content)) {
        const version = since(typeIsNew ? seen.element.get(element.name) : seen.elementIn.get(`${typeName}/${element.name}`));
        if (version) element.since = version;
        const deprecatedSince = deprecatedFirst.get(`e:${typeName}/${element.name}`);
        if (deprecatedSince && schema.version >= deprecatedSince) element.deprecatedSince = deprecatedSince;
      }
      for (const attribute of type.attributes) {
        const version = since(typeIsNew ? seen.attribute.get(attribute.name) : seen.attributeIn.get(`${typeName}@${attribute.name}`));
        if (version) attribute.since = version;
        const deprecatedSince = deprecatedFirst.get(`a:${typeName}@${attribute.name}`);
        if (deprecatedSince && schema.version >= deprecatedSince) attribute.deprecatedSince = deprecatedSince;
      }
    }
    for (const [typeName, type] of Object.entries(schema.simpleTypes)) {
      for (const alternative of type.alternatives) {
        if (!alternative.enumeration) continue;
        /** @type {Record<string, string>} */
        const valuesSince = {};
        for (const value of alternative.enumeration) {
          const version = since(seen.value.get(`${typeName}=${value}`));
          if (version) valuesSince[value] = version;
        }
        if (Object.keys(valuesSince).length > 0) alternative.valuesSince = valuesSince;
      }
    }
  }
}

/** @param {string} [directory] */
export function compileSchemas(directory = path.join(root, 'schemas')) {
  const schemas = SCHEMA_FILES.map(({ version, file }) => ({
    ...compileSchema(readFileSync(path.join(directory, file), 'utf8'), version),
    file,
  }));
  addHistory(schemas);
  return { source: 'ASAM OpenSCENARIO XML schemas (schemas/*.xsd), distributable under the ASAM license terms', schemas };
}

/**
 * dist/openscenario-schemas.json: one JSON object whose first line gives the byte range of each version's
 * model in the file, so that a run reads and parses only the version it checks (server/src/core/schema/model.ts):
 *   {"ranges":{"1.0":[  start,    end],...},
 *   "source":"...","schemas":{"1.0":{...},...}}
 * The offsets are padded with spaces to a fixed width, so that the first line's length does not depend on them.
 * @param {{ source: string, schemas: CompiledSchema[] }} [compiled]
 */
export function schemaModelFile(compiled = compileSchemas()) {
  const width = 10;
  /** @param {number} offset */
  const pad = (offset) => String(offset).padStart(width, ' ');
  /** @typedef {[version: string, start: number, end: number]} VersionRange */
  /** @param {VersionRange[]} ranges */
  const rangesLine = (ranges) =>
    `{"ranges":{${ranges.map(([version, start, end]) => `"${version}":[${pad(start)},${pad(end)}]`).join(',')}},\n`;
  const placeholder = rangesLine(compiled.schemas.map((schema) => [schema.version, 0, 0]));
  let rest = `"source":${JSON.stringify(compiled.source)},"schemas":{`;
  /** @type {VersionRange[]} */
  const ranges = [];
  compiled.schemas.forEach((schema, i) => {
    rest += `${i > 0 ? ',' : ''}"${schema.version}":`;
    const text = JSON.stringify(schema);
    const start = Buffer.byteLength(placeholder) + Buffer.byteLength(rest);
    rest += text;
    ranges.push([schema.version, start, start + Buffer.byteLength(text)]);
  });
  return rangesLine(ranges) + rest + '}}';
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const out = process.argv[2] ?? path.join(root, 'dist', 'openscenario-schemas.json');
  mkdirSync(path.dirname(out), { recursive: true });
  writeFileSync(out, schemaModelFile());
}
