/*
 * What the schema check found, as facts by code: names, values, versions. Each code's module
 * (core/diagnostics/<code>.ts, above this folder) words them, as the message and hint of its problem.
 */

/** The version a file is read as, and the one its FileHeader states (when it states one). */
export interface VersionRead {
  version: string;
  stated: string | undefined;
}

/** The versions of the schema that know a name (or accept a value) the version read does not. */
export interface OtherVersions extends VersionRead {
  versions: string[];
}

export interface SchemaFactsByCode {
  'schema-version':
    | { kind: 'fallback'; fallback: string; version: string }
    | { kind: 'expression'; value: string; version: string; suggestion: string | undefined };
  'schema-unknown-element':
    | { kind: 'root'; expected: string; found: string }
    | {
        kind: 'child';
        parent: string;
        child: string;
        version: string;
        /** The parent holds text, or no element at all. */
        holdsNoElements: boolean;
        introducedIn: OtherVersions | undefined;
        suggestion: string | undefined;
        /** The children the parent may hold. */
        children: string[];
      };
  'schema-unknown-attribute': {
    element: string;
    attribute: string;
    version: string;
    introducedIn: OtherVersions | undefined;
    suggestion: string | undefined;
    /** The attributes of the element not written yet. */
    candidates: string[];
  };
  'schema-value': {
    element: string;
    attribute: string;
    value: string;
    type: string;
    /** The values the type allows, described. */
    expected: string;
    validIn: OtherVersions | undefined;
    suggestion: string | undefined;
  };
  'schema-deprecated':
    | { kind: 'value'; element: string; attribute: string; value: string; version: string; instead: string | undefined }
    | {
        kind: 'attribute';
        element: string;
        attribute: string;
        since: string | undefined;
        /** The replacements written beside it (attributes by name, elements as `<Name>`). */
        together: string[];
        instead: string | undefined;
        /** A simulator that needs the deprecated attribute, with its fact: it stays (deprecations.ts keptFor). */
        keptFor?: { simulator: string; note: string; source: string };
      }
    | { kind: 'element'; element: string; since: string | undefined; version: string; instead: string | undefined };
  'schema-missing-attribute': { element: string; missing: string[] };
  'schema-missing-element': { parent: string; missing: string[]; before: string | undefined };
  'schema-order':
    | { kind: 'before'; element: string; parent: string; before: string[] }
    | { kind: 'expected'; element: string; parent: string; expected: string[] };
  'schema-cardinality': { element: string; parent: string; max: number };
}

export type SchemaFactCode = keyof SchemaFactsByCode;

/** A code with its facts. */
export type SchemaFacts = { [C in SchemaFactCode]: { code: C; facts: SchemaFactsByCode[C] } }[SchemaFactCode];
