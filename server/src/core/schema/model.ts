import * as fs from 'node:fs';
import * as path from 'node:path';

/** The versions of OpenSCENARIO whose schemas are bundled, oldest first. */
export const SCHEMA_VERSIONS = ['1.0', '1.1', '1.2', '1.3'] as const;
export type SchemaVersion = (typeof SCHEMA_VERSIONS)[number];

/** One way a value may be valid: a built-in XSD type, an enumeration or patterns. */
export interface ValueAlternative {
  builtin?: 'boolean' | 'dateTime' | 'double' | 'int' | 'string' | 'unsignedInt' | 'unsignedShort';
  enumeration?: string[];
  deprecatedValues?: string[];
  /** The version that introduced a value, for values newer than 1.0. */
  valuesSince?: Record<string, string>;
  /** XSD patterns (anchored as XSD anchors them). */
  patterns?: string[];
}

export interface SimpleType {
  alternatives: ValueAlternative[];
  /** The type admits `$name` (a member of the schema's `parameter` type). */
  parameter: boolean;
  /** The type admits `${expression}` (a member of the schema's `expression` type, 1.1 and later). */
  expression: boolean;
  deprecated?: boolean;
}

export interface AttributeDeclaration {
  name: string;
  /** The name of a simple type of the same schema. */
  type: string;
  required: boolean;
  deprecated?: boolean;
  since?: string;
  deprecatedSince?: string;
}

export interface ElementParticle {
  kind: 'element';
  name: string;
  /** The name of a complex type of the same schema. */
  type: string;
  min: number;
  /** -1: unbounded. */
  max: number;
  deprecated?: boolean;
  since?: string;
  deprecatedSince?: string;
}

export interface GroupParticle {
  kind: 'sequence' | 'choice' | 'all';
  min: number;
  max: number;
  items: Particle[];
}

export type Particle = ElementParticle | GroupParticle;

export interface ComplexType {
  attributes: AttributeDeclaration[];
  content?: Particle;
  /** Simple content: the element holds text (CustomCommandAction). */
  text?: boolean;
  deprecated?: boolean;
}

export interface CompiledSchema {
  version: SchemaVersion;
  /** The licence header of the XSD the model was compiled from. */
  header: string;
  file: string;
  rootElement: string;
  rootType: string;
  complexTypes: Record<string, ComplexType>;
  simpleTypes: Record<string, SimpleType>;
}

/**
 * The first line of the file `npm run build` writes (scripts/compile-schemas.mjs): the byte range of each
 * version's model, so that a run decodes and parses only the versions it checks against (a CLI flatten
 * one of four; decoding and parsing the whole file was most of loading).
 */
interface CompiledSchemaRanges {
  ranges: Partial<Record<SchemaVersion, [number, number]>>;
}

/** The compiled model's file name; `npm run build` writes it next to the bundles in dist/. */
export const SCHEMA_MODEL_FILE = 'openscenario-schemas.json';

let file: { bytes: Buffer; ranges: CompiledSchemaRanges['ranges'] } | undefined;
const loaded = new Map<SchemaVersion, CompiledSchema>();

function readModelFile(): { bytes: Buffer; ranges: CompiledSchemaRanges['ranges'] } {
  const bytes = fs.readFileSync(modelPath());
  const lineEnd = bytes.indexOf(10);
  // The first line is `{"ranges":{...},`: closed, it is a JSON object of its own.
  const header = lineEnd < 0 ? undefined : (JSON.parse(bytes.toString('latin1', 0, lineEnd).replace(/,\s*$/, '}')) as CompiledSchemaRanges);
  if (!header?.ranges)
    throw new Error(`the compiled OpenSCENARIO schema model (${SCHEMA_MODEL_FILE}) is from an older build: run \`npm run build\``);
  return { bytes, ranges: header.ranges };
}

function modelPath(): string {
  // Bundled: beside dist/server.js and dist/cli.js. From source (tests): the repository's dist/.
  const candidates = [path.join(__dirname, SCHEMA_MODEL_FILE), path.resolve(__dirname, '..', '..', '..', '..', 'dist', SCHEMA_MODEL_FILE)];
  const found = candidates.find((candidate) => fs.existsSync(candidate));
  if (!found) throw new Error(`the compiled OpenSCENARIO schema model (${SCHEMA_MODEL_FILE}) is missing: run \`npm run build\``);
  return found;
}

/** The compiled schema of a version, read once when first asked for. */
export function schemaFor(version: SchemaVersion): CompiledSchema {
  let schema = loaded.get(version);
  if (!schema) {
    file ??= readModelFile();
    const range = file.ranges[version];
    if (range === undefined) throw new Error(`no compiled schema for OpenSCENARIO ${version}`);
    schema = JSON.parse(file.bytes.toString('utf8', range[0], range[1])) as CompiledSchema;
    loaded.set(version, schema);
    delete file.ranges[version];
    // Every version read: the file's bytes are no longer needed.
    if (Object.keys(file.ranges).length === 0) file = { bytes: Buffer.alloc(0), ranges: {} };
  }
  return schema;
}

export function isSchemaVersion(value: unknown): value is SchemaVersion {
  return typeof value === 'string' && (SCHEMA_VERSIONS as readonly string[]).includes(value);
}

/** Every element particle of a content model, in document order. */
export function elementParticles(particle: Particle | undefined): ElementParticle[] {
  const result: ElementParticle[] = [];
  const visit = (current: Particle) => {
    if (current.kind === 'element') result.push(current);
    else for (const item of current.items) visit(item);
  };
  if (particle) visit(particle);
  return result;
}
