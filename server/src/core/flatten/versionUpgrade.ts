import { attribute, selfAndDescendants, XmlAttribute, XmlDocument, XmlElement } from '../xml';
import { statedRevision } from '../schema/version';

/*
 * A group copied from a scenario of an earlier OpenSCENARIO version into a later one (a 1.1 library module into a
 * 1.3 main) is written in the later version's words where the standard deprecated the earlier ones and says what
 * replaces them: the output then carries no deprecated attribute that its author could not edit (the module's
 * file), and esmini reads it without its "deprecated ... Accepting it anyway" warnings (ScenarioReader.cpp:5611, 5657).
 */

/** The cloud states of 1.0/1.1 as the fractional cloud cover 1.2 replaced them with: esmini's own reading of them (OSCEnvironment.cpp:64-69). */
export const CLOUD_STATE_OKTAS: Readonly<Record<string, string>> = {
  free: 'zeroOktas',
  cloudy: 'fourOktas',
  rainy: 'sixOktas',
  overcast: 'eightOktas',
  skyOff: 'nineOktas',
};

/** One attribute a later version renames: the element, the old and new names, the version that deprecated it, and the value as the new attribute holds it. */
interface Upgrade {
  element: string;
  from: string;
  to: string;
  since: number;
  value: (written: string) => string | undefined;
}

const UPGRADES: readonly Upgrade[] = [
  // OpenSCENARIO 1.3 model documentation: Sun.intensity deprecated, illuminance in lx (the same quantity, renamed).
  { element: 'Sun', from: 'intensity', to: 'illuminance', since: 1.3, value: (written) => written },
  // 1.2: Weather.cloudState deprecated, fractionalCloudCover instead; a parameter or expression is left as written.
  {
    element: 'Weather',
    from: 'cloudState',
    to: 'fractionalCloudCover',
    since: 1.2,
    value: (written) => (Object.hasOwn(CLOUD_STATE_OKTAS, written.trim()) ? CLOUD_STATE_OKTAS[written.trim()] : undefined),
  },
];

/** The version a FileHeader states as a number (1.3), undefined when it states none. */
export function statedVersion(document: XmlDocument): number | undefined {
  const stated = statedRevision(document);
  const major = Number(stated.major);
  const minor = Number(stated.minor);
  return Number.isInteger(major) && Number.isInteger(minor) && minor < 10 ? major + minor / 10 : undefined;
}

/** A renamed attribute of a copied element: where its name is and what it becomes. */
export interface AttributeUpgrade {
  element: XmlElement;
  attribute: XmlAttribute;
  name: string;
  value: string;
}

/**
 * The deprecated attributes below `group` that the copy into a scenario of version `to` writes under their
 * replacement's name, read from a scenario of version `from`; `valueOf` gives each attribute's value as the copy
 * holds it (an override's, else the written one). Nothing where either version is unknown or `to` is not later.
 */
export function versionUpgrades(
  group: XmlElement,
  from: number | undefined,
  to: number | undefined,
  valueOf: (element: XmlElement, written: XmlAttribute) => string,
): AttributeUpgrade[] {
  if (from === undefined || to === undefined || to <= from) return [];
  const found: AttributeUpgrade[] = [];
  for (const element of selfAndDescendants(group)) {
    for (const upgrade of UPGRADES) {
      if (element.name !== upgrade.element || from >= upgrade.since || to < upgrade.since) continue;
      const written = attribute(element, upgrade.from);
      if (!written || attribute(element, upgrade.to)) continue;
      const value = upgrade.value(valueOf(element, written));
      if (value !== undefined) found.push({ element, attribute: written, name: upgrade.to, value });
    }
  }
  return found;
}
