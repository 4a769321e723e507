import { attribute, descendants, XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { CARLA_PROFILE } from './carla';
import { ESMINI_PROFILE } from './esmini';
import { AttributeFact, ElementFact, SimulatorProfile } from './facts';
import { Simulator } from './simulators';

export const PROFILES: Record<Exclude<Simulator, 'asam'>, SimulatorProfile> = { carla: CARLA_PROFILE, esmini: ESMINI_PROFILE };

/** Something a simulator will not run as written: on an element, or on one of its attributes. */
export interface SimulatorFinding {
  element: XmlElement;
  attribute?: XmlAttribute;
  message: string;
}

export interface ProfileCheckContext {
  profile: SimulatorProfile;
  document: XmlDocument;
  /** The name of the file the document was read from (catalogs are found by name). */
  fileName: string;
  /** Every element of the document, in document order. */
  elements: XmlElement[];
}

/** One check of a simulator profile over a document. */
export type ProfileCheck = (context: ProfileCheckContext) => SimulatorFinding[];

/** Whether the values of `$name` or `${...}` are known only when the scenario runs. */
const isParameterized = (value: string) => value.startsWith('$');

function isCatalogFile(document: XmlDocument): boolean {
  return document.root?.children.some((child) => child.name === 'Catalog') ?? false;
}

/** Where an action runs: in the Init, in a Story (or a catalog's Maneuver), or not known. */
function placeOf(element: XmlElement): 'init' | 'story' | undefined {
  for (let current = element.parent; current; current = current.parent) {
    if (current.name === 'Init') return 'init';
    if (current.name === 'Story' || current.name === 'Maneuver') return 'story';
  }
  return undefined;
}

function describe(fact: ElementFact): string {
  return fact.parent ? `${fact.element} in ${fact.parent}` : fact.element;
}

const versionCheck: ProfileCheck = ({ profile, document }) => {
  const wanted = profile.versions;
  const header = document.root?.children.find((child) => child.name === 'FileHeader');
  // The simulator checks the version of the scenario it runs, not of the catalogs it reads.
  if (!wanted || !header || isCatalogFile(document)) return [];
  const major = attribute(header, 'revMajor');
  const minor = attribute(header, 'revMinor');
  if (!major || !minor || (major.value === wanted.revMajor && minor.value === wanted.revMinor)) return [];
  return [
    {
      element: header,
      attribute: major.value === wanted.revMajor ? minor : major,
      message: `${profile.name} accepts only OpenSCENARIO ${wanted.revMajor}.${wanted.revMinor}; this file states ${major.value}.${minor.value} (${wanted.source})`,
    },
  ];
};

const elementCheck: ProfileCheck = ({ profile, elements }) => {
  const facts = new Map<string, ElementFact[]>();
  for (const fact of profile.elements) facts.set(fact.element, [...(facts.get(fact.element) ?? []), fact]);
  const findings: SimulatorFinding[] = [];
  for (const element of elements) {
    const candidates = facts.get(element.name);
    if (!candidates) continue;
    for (const fact of candidates) {
      if (fact.parent && element.parent?.name !== fact.parent) continue;
      const note = fact.note ? `: ${fact.note}` : '';
      if (fact.places) {
        const place = placeOf(element);
        if (!place || fact.places[place]) continue;
        const elsewhere = place === 'init' ? 'only in a Story' : 'only in the Init';
        findings.push({
          element,
          message: `${profile.name} does not support ${describe(fact)} in ${place === 'init' ? 'the Init' : 'a Story'}, ${elsewhere}${note} (${fact.source})`,
        });
      } else if (fact.support === 'ignored') {
        findings.push({ element, message: `${profile.name} ignores ${describe(fact)}${note} (${fact.source})` });
      } else {
        findings.push({ element, message: `${profile.name} does not support ${describe(fact)}${note} (${fact.source})` });
      }
    }
  }
  return findings;
};

function breaks(fact: AttributeFact, value: string): boolean {
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
      const found = attribute(element, fact.attribute);
      if (!found || !breaks(fact, found.value)) continue;
      const what = fact.supportedValues?.length === 0 ? fact.attribute : `${fact.attribute}="${found.value}"`;
      findings.push({
        element,
        attribute: found,
        message: `${profile.name} does not support ${what} on ${element.name}: ${fact.note} (${fact.source})`,
      });
    }
  }
  return findings;
};

const expressionCheck: ProfileCheck = ({ profile, elements }) => {
  const source = profile.expressionsNotEvaluated?.source;
  if (!source) return [];
  const findings: SimulatorFinding[] = [];
  for (const element of elements) {
    for (const candidate of element.attributes) {
      if (!candidate.value.includes('${')) continue;
      findings.push({
        element,
        attribute: candidate,
        message: `${profile.name} does not evaluate \${...} expressions: ${candidate.name}="${candidate.value}" is read as text (${source})`,
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
        message: `${profile.name} reads no catalog of ${type} entries; it reads ${rule.types.map((name) => name + 'Catalog').join(', ')} (${rule.source})`,
      },
    ];
  const expected = `${type}Catalog.xosc`;
  if (fileName === expected) return [];
  return [
    {
      element: catalog,
      attribute: attribute(catalog, 'name'),
      message: `${profile.name} reads a catalog of ${type} entries only from a file named ${expected} in the catalog directory; this file is ${fileName} (${rule.source})`,
    },
  ];
};

/** The checks of every simulator profile, in the order their findings are listed. */
export const PROFILE_CHECKS: readonly ProfileCheck[] = [versionCheck, elementCheck, attributeCheck, expressionCheck, catalogNameCheck];

/** What `simulator` will not run in a document (none for `asam`, the standard alone). */
export function simulatorFindings(simulator: Simulator, document: XmlDocument, fileName: string): SimulatorFinding[] {
  if (simulator === 'asam' || !document.root) return [];
  const context: ProfileCheckContext = {
    profile: PROFILES[simulator],
    document,
    fileName,
    elements: [document.root, ...descendants(document.root)],
  };
  return PROFILE_CHECKS.flatMap((check) => check(context));
}
