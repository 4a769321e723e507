import { attribute, XmlDocument, XmlElement } from '../xml';
import { isSchemaVersion, SchemaVersion } from './model';

/** How a file chooses its schema: by its FileHeader (`auto`) or pinned to one version. */
export type SchemaVersionSetting = 'auto' | SchemaVersion;

export interface ChosenVersion {
  version: SchemaVersion;
  /** What the FileHeader states (`1.0`), when it states revMajor and revMinor. */
  stated: string | undefined;
  /** Set when the stated version has no schema of its own and the nearest one is used. */
  fallback?: string;
  header: XmlElement | undefined;
}

const LATEST: SchemaVersion = '1.3';

export function fileHeaderOf(document: XmlDocument): XmlElement | undefined {
  return document.root?.children.find((child) => child.name === 'FileHeader');
}

/** A file's FileHeader and the revMajor/revMinor it writes, trimmed; each undefined when absent. */
export function statedRevision(document: XmlDocument): {
  header: XmlElement | undefined;
  major: string | undefined;
  minor: string | undefined;
} {
  const header = fileHeaderOf(document);
  return {
    header,
    major: header ? attribute(header, 'revMajor')?.value.trim() : undefined,
    minor: header ? attribute(header, 'revMinor')?.value.trim() : undefined,
  };
}

/** The schema a file is read against: the pinned one, or the one its FileHeader's revMajor/revMinor state. */
export function chooseVersion(document: XmlDocument, setting: SchemaVersionSetting = 'auto'): ChosenVersion {
  const { header, major, minor } = statedRevision(document);
  const stated = major !== undefined && minor !== undefined ? `${major}.${minor}` : undefined;
  if (setting !== 'auto') return { version: setting, stated, header };
  if (stated === undefined) return { version: LATEST, stated, header, fallback: 'the FileHeader states no revMajor/revMinor' };
  if (isSchemaVersion(stated)) return { version: stated, stated, header };
  const majorNumber = Number(major);
  const minorNumber = Number(minor);
  if (!Number.isInteger(majorNumber) || !Number.isInteger(minorNumber))
    return { version: LATEST, stated, header, fallback: `the FileHeader states ${stated}` };
  const version: SchemaVersion = majorNumber < 1 ? '1.0' : LATEST;
  return { version, stated, header, fallback: `no schema for OpenSCENARIO ${stated}` };
}
