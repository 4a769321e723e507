import { attribute, descendants, XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { CARLA_PROFILE } from './carla';
import { ESMINI_PROFILE } from './esmini';
import { AttributeFact, ElementFact, FactSeverity, SimulatorProfile } from './facts';
import { CarlaRelease, DEFAULT_CARLA_RELEASE, Simulator } from './simulators';

export const PROFILES: Record<Exclude<Simulator, 'asam'>, SimulatorProfile> = { carla: CARLA_PROFILE, esmini: ESMINI_PROFILE };

/** What a profile's check found, as facts: core/diagnostics/simulator.ts words them (`profile`: the simulator's name). */
export type ProfileFacts =
  /** The file states a version the simulator does not accept. */
  | { kind: 'version'; profile: string; wanted: { revMajor: string; revMinor: string; source: string }; stated: string }
  /** The file states a version older than the oldest the simulator runs. */
  | { kind: 'oldVersion'; profile: string; oldest: { revMajor: number; source: string; refusal: string }; stated: string }
  /** An element the simulator ignores or does not support (where `fact` says). */
  | { kind: 'element'; profile: string; fact: ElementFact }
  /** An attribute the simulator reads as if required, absent from `element`. */
  | { kind: 'absentAttribute'; profile: string; fact: AttributeFact; element: string }
  /** An attribute, or its `value`, the simulator does not support on `element`. */
  | { kind: 'attribute'; profile: string; fact: AttributeFact; element: string; value: string }
  /** A catalog of entries of `type`, which the simulator reads from no catalog. */
  | { kind: 'catalogType'; profile: string; type: string; rule: { types: readonly string[]; source: string } }
  /** A catalog of `type` entries in a file the simulator does not find by its name. */
  | { kind: 'catalogFileName'; profile: string; type: string; fileName: string; source: string };

/** Something a simulator will not run as written: on an element, or on one of its attributes. */
export interface SimulatorFinding {
  element: XmlElement;
  attribute?: XmlAttribute;
  facts: ProfileFacts;
  severity: FactSeverity;
  /** The text to write over the attribute's value, where that one edit answers the finding. */
  suggestion?: string;
  /** The project's export for this simulator writes what the finding asks for. */
  exportMaps?: boolean;
}

export interface ProfileCheckContext {
  profile: SimulatorProfile;
  document: XmlDocument;
  /** The name of the file the document was read from (catalogs are found by name). */
  fileName: string;
  /** Every element of the document, in document order. */
  elements: XmlElement[];
  /** The CARLA release whose facts apply (a fact may hold for some releases only). */
  release: CarlaRelease;
}

/** One check of a simulator profile over a document. */
export type ProfileCheck = (context: ProfileCheckContext) => SimulatorFinding[];

/** Whether the values of `$name` or `${...}` are known only when the scenario runs. */
const isParameterized = (value: string) => value.startsWith('$');

function isCatalogFile(document: XmlDocument): boolean {
  return document.root?.children.some((child) => child.name === 'Catalog') ?? false;
}

/** Whether an element lies in an entry of a catalog file (a child of its `Catalog`, or below one). */
function inCatalogEntry(element: XmlElement): boolean {
  for (let current = element.parent; current; current = current.parent)
    if (current.name === 'Catalog' && current.parent?.parent === undefined) return true;
  return false;
}

/** Where an action runs: in the Init, in a Story (or a catalog's Maneuver), or not known. */
function placeOf(element: XmlElement): 'init' | 'story' | undefined {
  for (let current = element.parent; current; current = current.parent) {
    if (current.name === 'Init') return 'init';
    if (current.name === 'Story' || current.name === 'Maneuver') return 'story';
  }
  return undefined;
}

/** A scenario's FileHeader and its version attributes; undefined for a catalog: the simulator checks the version of the scenario it runs, not of the catalogs it reads. */
function scenarioVersion(document: XmlDocument): { header: XmlElement; major?: XmlAttribute; minor?: XmlAttribute } | undefined {
  const header = document.root?.children.find((child) => child.name === 'FileHeader');
  if (!header || isCatalogFile(document)) return undefined;
  return { header, major: attribute(header, 'revMajor'), minor: attribute(header, 'revMinor') };
}

const versionCheck: ProfileCheck = ({ profile, document }) => {
  const wanted = profile.versions;
  const version = scenarioVersion(document);
  if (!wanted || !version) return [];
  const { header, major, minor } = version;
  if (!major || !minor || (major.value === wanted.revMajor && minor.value === wanted.revMinor)) return [];
  const onMinor = major.value === wanted.revMajor;
  return [
    {
      element: header,
      attribute: onMinor ? minor : major,
      severity: wanted.severity ?? 'warning',
      facts: { kind: 'version', profile: profile.name, wanted, stated: `${major.value}.${minor.value}` },
      suggestion: onMinor ? wanted.revMinor : wanted.revMajor,
      ...(wanted.exportWrites ? { exportMaps: true } : {}),
    },
  ];
};

const oldVersionCheck: ProfileCheck = ({ profile, document }) => {
  const oldest = profile.oldestRevMajor;
  const version = scenarioVersion(document);
  if (!oldest || !version) return [];
  const { header, major, minor } = version;
  // A revMajor that is no number is the schema's to report.
  if (!major || !/^\s*\d+\s*$/.test(major.value) || Number(major.value) >= oldest.revMajor) return [];
  const stated = `${major.value.trim()}.${minor?.value.trim() ?? ''}`;
  return [{ element: header, attribute: major, severity: 'error', facts: { kind: 'oldVersion', profile: profile.name, oldest, stated } }];
};

function holds(fact: { releases?: readonly CarlaRelease[] }, release: CarlaRelease): boolean {
  return !fact.releases || fact.releases.includes(release);
}

const elementCheck: ProfileCheck = ({ profile, elements, release }) => {
  const facts = new Map<string, ElementFact[]>();
  for (const fact of profile.elements) if (holds(fact, release)) facts.set(fact.element, [...(facts.get(fact.element) ?? []), fact]);
  const findings: SimulatorFinding[] = [];
  for (const element of elements) {
    const candidates = facts.get(element.name);
    if (!candidates) continue;
    for (const fact of candidates) {
      if (fact.parent && element.parent?.name !== fact.parent) continue;
      const place = placeOf(element);
      if (fact.in && place !== fact.in) continue;
      findings.push({
        element,
        severity: fact.severity ?? 'warning',
        facts: { kind: 'element', profile: profile.name, fact },
        ...(place !== undefined && fact.exportWritesIn?.includes(place) ? { exportMaps: true } : {}),
      });
    }
  }
  return findings;
};

/** Whether `value` of the fact's attribute is one the simulator does not run as written (a $parameter is judged where it is resolved). */
export function breaks(fact: AttributeFact, value: string): boolean {
  if (fact.supportedValues?.length === 0) return true;
  if (isParameterized(value)) return false;
  if (fact.supportedValues) return !fact.supportedValues.includes(value);
  return fact.unsupportedValues?.includes(value) ?? false;
}

const attributeCheck: ProfileCheck = ({ profile, elements }) => {
  const findings: SimulatorFinding[] = [];
  for (const element of elements) {
    for (const fact of profile.attributes) {
      if (fact.element !== '*' && fact.element !== element.name) continue;
      if (fact.parent && element.parent?.name !== fact.parent) continue;
      if (fact.notOn?.includes(element.name)) continue;
      const other = fact.unlessAttribute && attribute(element, fact.unlessAttribute.attribute)?.value;
      if (other !== undefined && fact.unlessAttribute?.values.includes(other)) continue;
      const found = attribute(element, fact.attribute);
      if (fact.whenAbsent) {
        if (!found)
          findings.push({
            element,
            severity: fact.severity ?? 'warning',
            facts: { kind: 'absentAttribute', profile: profile.name, fact, element: element.name },
          });
        continue;
      }
      if (!found || !breaks(fact, found.value)) continue;
      findings.push({
        element,
        attribute: found,
        severity: fact.severity ?? 'warning',
        facts: { kind: 'attribute', profile: profile.name, fact, element: element.name, value: found.value },
        ...(fact.exportWrites?.includes(found.value) ? { exportMaps: true } : {}),
      });
    }
  }
  return findings;
};

const catalogNameCheck: ProfileCheck = ({ profile, document, fileName }) => {
  const rule = profile.catalogFileNames;
  const catalog = document.root?.children.find((child) => child.name === 'Catalog');
  const type = catalog?.children[0]?.name;
  if (!rule || !catalog || !type) return [];
  if (!rule.types.includes(type))
    return [
      {
        element: catalog,
        severity: 'warning',
        facts: { kind: 'catalogType', profile: profile.name, type, rule },
      },
    ];
  const expected = `${type}Catalog.xosc`;
  if (fileName === expected) return [];
  return [
    {
      element: catalog,
      attribute: attribute(catalog, 'name'),
      severity: 'warning',
      facts: { kind: 'catalogFileName', profile: profile.name, type, fileName, source: rule.source },
    },
  ];
};

/** The checks of every simulator profile, in the order their findings are listed. */
export const PROFILE_CHECKS: readonly ProfileCheck[] = [versionCheck, oldVersionCheck, elementCheck, attributeCheck, catalogNameCheck];

/** The checks of what a catalog entry holds, which a simulator reads only where a scenario references the entry. */
const ENTRY_CHECKS: readonly ProfileCheck[] = [elementCheck, attributeCheck];

/**
 * What `simulator` will not run in a document (none for `asam`, the standard alone). In a catalog file the
 * entries are left out: a simulator reads an entry only where a scenario references it, and `entryFindings`
 * checks it there (an entry no scenario uses is no problem).
 */
export function simulatorFindings(
  simulator: Simulator,
  document: XmlDocument,
  fileName: string,
  release: CarlaRelease = DEFAULT_CARLA_RELEASE,
): SimulatorFinding[] {
  if (simulator === 'asam' || !document.root) return [];
  const all = [document.root, ...descendants(document.root)];
  const context: ProfileCheckContext = {
    profile: PROFILES[simulator],
    document,
    fileName,
    elements: isCatalogFile(document) ? all.filter((element) => !inCatalogEntry(element)) : all,
    release,
  };
  return PROFILE_CHECKS.flatMap((check) => check(context));
}

/** What `simulator` will not run in a catalog entry (`entry`, a child of the `Catalog` of `document`), for the scenario that references it. */
export function entryFindings(
  simulator: Simulator,
  document: XmlDocument,
  fileName: string,
  entry: XmlElement,
  release: CarlaRelease = DEFAULT_CARLA_RELEASE,
): SimulatorFinding[] {
  if (simulator === 'asam') return [];
  const context: ProfileCheckContext = {
    profile: PROFILES[simulator],
    document,
    fileName,
    elements: [entry, ...descendants(entry)],
    release,
  };
  return ENTRY_CHECKS.flatMap((check) => check(context));
}
