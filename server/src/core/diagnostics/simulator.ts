import { ProblemDataByCode } from '../problems';
import { CARLA_FACTS, CARLA_PROFILE, CarlaFactName } from '../profiles/carla';
import type { ProfileFacts } from '../profiles/checks';
import { ESMINI_FACTS, ESMINI_PROFILE, EsminiFactName } from '../profiles/esmini';
import type { ElementFact, FactSeverity, SimulatorFact } from '../profiles/facts';
import { Range } from '../text';
import { EGO_PROPERTY } from '../profiles/scenarioRunner';
import { attribute, elementAt, escapeAttributeValue, XmlDocument } from '../xml';
import {
  childrenInsertion,
  insertionBefore,
  CoreFix,
  defineDiagnostic,
  documentEdit,
  isOptionalString,
  isRecord,
  isString,
  ProblemWording,
  TextLines,
} from './definition';

function describe(fact: ElementFact): string {
  return fact.parent ? `${fact.element} in ${fact.parent}` : fact.element;
}

/** The words of what a simulator profile's check found (core/profiles/checks.ts), each naming its source. */
function profileMessage(facts: ProfileFacts): string {
  switch (facts.kind) {
    case 'version':
      return `${facts.profile} accepts only OpenSCENARIO ${facts.wanted.revMajor}.${facts.wanted.revMinor}; this file states ${facts.stated} (${facts.wanted.source})`;
    case 'oldVersion':
      return `${facts.profile} runs OpenSCENARIO ${facts.oldest.revMajor}.0 or later; this file states ${facts.stated}, which it refuses ("${facts.oldest.refusal.replace('{stated}', facts.stated)}") (${facts.oldest.source})`;
    case 'element': {
      const { fact } = facts;
      const where = fact.in === 'init' ? ' in the Init' : fact.in === 'story' ? ' in a Story' : '';
      const note = fact.note ? `: ${fact.note}` : '';
      const verb = fact.support === 'ignored' ? 'ignores' : 'does not support';
      return `${facts.profile} ${verb} ${describe(fact)}${where}${note} (${fact.source})`;
    }
    case 'attribute': {
      const { fact } = facts;
      const what = fact.supportedValues?.length === 0 ? fact.attribute : `${fact.attribute}="${facts.value}"`;
      return `${facts.profile} does not support ${what} on ${facts.element}: ${fact.note} (${fact.source})`;
    }
    case 'absentAttribute':
      return `${facts.profile} does not support ${facts.element} without ${facts.fact.attribute}: ${facts.fact.note} (${facts.fact.source})`;
    case 'catalogType':
      return `${facts.profile} reads no catalog of ${facts.type} entries; it reads ${facts.rule.types.map((name) => name + 'Catalog').join(', ')} (${facts.rule.source})`;
    case 'catalogFileName':
      return `${facts.profile} reads a catalog of ${facts.type} entries only from a file named ${facts.type}Catalog.xosc in the catalog directory; this file is ${facts.fileName} (${facts.source})`;
  }
}

/** A simulator profile's finding (its severity is the fact's). */
export function simulatorWording(finding: { severity: FactSeverity; facts: ProfileFacts }): ProblemWording<'simulator'> {
  return { severity: finding.severity, code: 'simulator', message: profileMessage(finding.facts) };
}

/**
 * A simulator's finding in a catalog entry, placed on the CatalogReference that uses the entry (`file`, `line`, `column`:
 * where the finding stands in the catalog, one-based, so that two findings of one line stay two): a simulator reads an
 * entry only where a scenario references it.
 */
export function inCatalogEntryWording(
  wording: ProblemWording<'simulator'>,
  entry: { name: string; file: string; line: number; column: number },
): ProblemWording<'simulator'> {
  return { ...wording, message: `in catalog entry '${entry.name}' (${entry.file}:${entry.line}:${entry.column}): ${wording.message}` };
}

/** The note of a finding placed on a CatalogReference, at the place in the catalog the finding stands. */
export const IN_CATALOG_ENTRY_NOTE = 'here in the catalog entry';

/** What a simulator does beyond one element or attribute: the `fact`, then `detail`, the case at hand, then the fact's source. */
function factWording(simulator: string, fact: SimulatorFact, detail: string): ProblemWording<'simulator'> {
  return { severity: fact.severity, code: 'simulator', message: `${simulator} ${fact.does}: ${detail} (${fact.source})` };
}

/** What CARLA's ScenarioRunner does beyond one element or attribute (core/semantics/checks/carla.ts): the fact `name`, then `detail`, the case at hand. */
export function carlaFactWording(name: CarlaFactName, detail: string): ProblemWording<'simulator'> {
  return factWording(CARLA_PROFILE.name, CARLA_FACTS[name], detail);
}

/** What to write so that esmini fires a SimulationTimeCondition it never fires (the quick fix simulationTimeFix makes, for `run` and `check` on the command line). */
const SIMULATION_TIME_HINTS = {
  edge: 'write conditionEdge="none" on this Condition: esmini then fires it when it is first evaluated',
  'after-zero':
    'write rule="greaterThan" here, and conditionEdge="none" on its Condition: esmini then starts the Event when its Act starts',
} as const;

/**
 * What esmini does beyond one element or attribute (core/profiles/esmini.ts ESMINI_FACTS): the fact `name`, then `detail`,
 * the case at hand; with `simulationTimeFix`, what to write so that esmini fires the condition.
 */
export function esminiFactWording(
  name: EsminiFactName,
  detail: string,
  simulationTimeFix?: keyof typeof SIMULATION_TIME_HINTS,
): ProblemWording<'simulator'> {
  const wording = factWording(ESMINI_PROFILE.name, ESMINI_FACTS[name], detail);
  return simulationTimeFix ? { ...wording, hint: SIMULATION_TIME_HINTS[simulationTimeFix] } : wording;
}

function isSimulatorData(value: unknown): value is ProblemDataByCode['simulator'] {
  if (!isRecord(value) || !isOptionalString(value.suggestion)) return false;
  if (value.exportMaps !== undefined && typeof value.exportMaps !== 'boolean') return false;
  if (!isOptionalString(value.actor) || !isOptionalString(value.ego)) return false;
  if (value.orientationFirst !== undefined && typeof value.orientationFirst !== 'boolean') return false;
  if (value.simulationTimeFix !== undefined && value.simulationTimeFix !== 'edge' && value.simulationTimeFix !== 'after-zero') return false;
  return value.rename === undefined || (isRecord(value.rename) && isString(value.rename.from) && isString(value.rename.to));
}

function baseName(file: string): string {
  return file.slice(Math.max(file.lastIndexOf('/'), file.lastIndexOf('\\')) + 1);
}

/**
 * What the selected simulator does not run as written (core/profiles/, core/semantics/checks/carla.ts): an
 * error where it refuses the scenario, a warning where it runs it otherwise. Its fixes: the one edit that
 * answers it where there is one (the value of a `${...}`, revMinor="0", the EntityRef an Actors lacks for esmini),
 * the catalog file's rename, and the export for CARLA where the export maps it.
 */
export const SIMULATOR = defineDiagnostic({
  code: 'simulator',
  rule: { description: 'The selected simulator runs what the file uses.' },
  severity: 'warning',
  isData: isSimulatorData,
  fixes: async ({ data, range, document, parsed }) => [
    ...(data?.suggestion !== undefined
      ? [{ title: `Write '${data.suggestion}'`, edits: [{ place: 'document' as const, range, newText: data.suggestion }], preferred: true }]
      : []),
    ...(data?.rename
      ? [{ title: `Rename ${baseName(data.rename.from)} to ${baseName(data.rename.to)}`, edits: [], rename: data.rename, preferred: true }]
      : []),
    ...(data?.exportMaps ? [{ title: 'Export for CARLA…', edits: [], command: 'export-for-carla' as const }] : []),
    ...(data?.actor !== undefined ? await actorFix(data.actor, document, range, parsed) : []),
    ...(data?.orientationFirst ? await orientationFirstFix(document, range, parsed) : []),
    ...(data?.ego !== undefined ? await egoFix(data.ego, document, parsed) : []),
    ...(data?.simulationTimeFix ? await simulationTimeFix(data.simulationTimeFix, document, range, parsed) : []),
  ],
});

/**
 * A SimulationTimeCondition esmini never fires, made one it fires when its trigger is first evaluated: the Condition's
 * conditionEdge none ('edge'); or, where that is after time 0, its rule greaterThan (0) and the edge none ('after-zero').
 */
async function simulationTimeFix(
  fix: 'edge' | 'after-zero',
  document: TextLines,
  range: Range,
  parsed: () => Promise<XmlDocument>,
): Promise<CoreFix[]> {
  const at = elementAt(await parsed(), document.offsetAt(range.start));
  const time = fix === 'after-zero' ? at : undefined;
  const condition = fix === 'edge' ? at : at?.parent?.parent;
  if (condition?.name !== 'Condition' || (fix === 'after-zero' && time?.name !== 'SimulationTimeCondition')) return [];
  const rule = time && attribute(time, 'rule');
  const edge = attribute(condition, 'conditionEdge');
  const edgeToNone = edge && edge.value !== 'none' ? edge : undefined;
  const edits = [
    ...(rule ? [documentEdit(document, rule.valueStart, rule.valueEnd, 'greaterThan')] : []),
    ...(edgeToNone ? [documentEdit(document, edgeToNone.valueStart, edgeToNone.valueEnd, 'none')] : []),
  ];
  if (edits.length === 0) return [];
  const title = [rule ? 'rule="greaterThan"' : '', edgeToNone ? 'conditionEdge="none"' : ''].filter(Boolean).join(', ');
  return [{ title: `Write ${title}: esmini starts it when first evaluated`, edits, preferred: true }];
}

/**
 * ScenarioRunner's ego Property added to the Properties of the named ScenarioObject's Vehicle: what Export for CARLA
 * writes into its output (export/carla.ts markEgo), written into the scenario instead. Before a File, as the schema
 * orders a Properties' children; a Vehicle without Properties gets them.
 */
async function egoFix(ego: string, document: TextLines, parsed: () => Promise<XmlDocument>): Promise<CoreFix[]> {
  const object = (await parsed()).root?.children
    .find((child) => child.name === 'Entities')
    ?.children.find((child) => child.name === 'ScenarioObject' && attribute(child, 'name')?.value === ego);
  const vehicle = object?.children.find((child) => child.name === 'Vehicle');
  if (!vehicle) return [];
  const text = document.getText();
  const property = `<Property name="${EGO_PROPERTY.name}" value="${EGO_PROPERTY.value}"/>`;
  const properties = vehicle.children.find((child) => child.name === 'Properties');
  const file = properties?.children.find((child) => child.name === 'File');
  const inserted = file
    ? insertionBefore(text, file, property)
    : properties
      ? childrenInsertion(text, properties, () => [property])
      : childrenInsertion(text, vehicle, () => [`<Properties>${property}</Properties>`]);
  if (!inserted) return [];
  const edit = documentEdit(document, inserted.start, inserted.end, inserted.newText);
  return [{ title: `Mark '${ego}' as the ego: ${property}`, edits: [edit], preferred: true }];
}

/** The Orientation the problem stands on, moved (with its line) before its RoutePosition's InRoutePosition. */
async function orientationFirstFix(document: TextLines, range: Range, parsed: () => Promise<XmlDocument>): Promise<CoreFix[]> {
  const orientation = elementAt(await parsed(), document.offsetAt(range.start));
  const position = orientation?.parent?.children.find((child) => child.name === 'InRoutePosition');
  if (orientation?.name !== 'Orientation' || !position || position.start > orientation.start) return [];
  const text = document.getText();
  const lineStart = text.lastIndexOf('\n', orientation.start - 1) + 1;
  // Its whole line goes, line break included, when it stands alone on it.
  const removeFrom = /^[ \t]*$/.test(text.slice(lineStart, orientation.start))
    ? Math.max(0, lineStart - (text[lineStart - 2] === '\r' ? 2 : 1))
    : orientation.start;
  const moved = insertionBefore(text, position, text.slice(orientation.start, orientation.end));
  return [
    {
      title: 'Move <Orientation> before <InRoutePosition>',
      edits: [documentEdit(document, moved.start, moved.end, moved.newText), documentEdit(document, removeFrom, orientation.end, '')],
      preferred: true,
    },
  ];
}

/** `<EntityRef entityRef="actor"/>` added to the Actors the problem stands on. */
async function actorFix(actor: string, document: TextLines, range: Range, parsed: () => Promise<XmlDocument>): Promise<CoreFix[]> {
  const actors = elementAt(await parsed(), document.offsetAt(range.start));
  const text = document.getText();
  const inserted =
    actors?.name === 'Actors'
      ? childrenInsertion(text, actors, () => [`<EntityRef entityRef="${escapeAttributeValue(actor)}"/>`])
      : undefined;
  if (!inserted) return [];
  const edit = documentEdit(document, inserted.start, inserted.end, inserted.newText);
  return [{ title: `Add <EntityRef entityRef="${actor}"/> to the Actors`, edits: [edit], preferred: true }];
}
