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
 * The file `npm run build` writes: each version's model as JSON text of its own, so that a run parses
 * only the versions it checks against (a CLI flatten one of four; parsing is most of loading).
 */
interface CompiledSchemaFile {
  source: string;
  schemas: Partial<Record<SchemaVersion, string>>;
}

/** The compiled model's file name; `npm run build` writes it next to the bundles in dist/. */
export const SCHEMA_MODEL_FILE = 'openscenario-schemas.json';

let file: CompiledSchemaFile | undefined;
const loaded = new Map<SchemaVersion, CompiledSchema>();

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
    file ??= JSON.parse(fs.readFileSync(modelPath(), 'utf8')) as CompiledSchemaFile;
    const text = file.schemas[version];
    if (text === undefined) throw new Error(`no compiled schema for OpenSCENARIO ${version}`);
    schema = JSON.parse(text) as CompiledSchema;
    loaded.set(version, schema);
    delete file.schemas[version];
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
