/*
 * Modularize (issue 19): turns a library of plain scenarios into simple scenarios and mains.
 *   shape.ts          what makes two ManeuverGroups one behaviour: their structure; their values
 *   naming.ts         a file name that says what a group does
 *   behaviour.ts      one recurring group: defaults, overridable attributes, keys, each use's overrides
 *   simpleScenario.ts the valid scenario around an extracted group
 *   parameterCopies.ts where a group's parameter values differ between its scenarios: a copy of its own to override
 *   mainText.ts       a main: the input with its recurring groups replaced by references
 *   memoryHost.ts     the outputs as files, for flattening them before anything is written
 */
import * as path from 'node:path';
import { firstDifference } from '../equivalence';
import { Flattener } from '../flatten';
import { CATALOG_CODES } from '../flatten/checks';
import { applyEdits } from '../flatten/edits';
import { buildModel } from '../model';
import { diskRef, Limits, ScenarioStore } from '../sources';
import { Problem } from '../problems';
import { countEditorLines } from '../text';
import { attributeValue, parseXml, XmlDocument } from '../xml';
import { indentUnit, planBehaviour } from './behaviour';
import { catalogParametersOf } from './catalogParameters';
import { parameterConflicts } from './parameterCopies';
import { simpleScenarioText } from './simpleScenario';
import { mainText, referenceGroup } from './mainText';
import { memoryHost } from './memoryHost';
import { behaviourName, uniqueName } from './naming';
import { GroupOccurrence, GroupShape, readOccurrence } from './shape';
import { pathRebaser } from './rebase';
import { Behaviour, MainResult, ModularizeInput, ModularizeOptions, ModularizeResult, ParsedInput, RebasePaths } from './types';

export type { Behaviour, MainResult, ModularizeInput, ModularizeOptions, ModularizeResult, RebasePaths } from './types';
export { memoryHost } from './memoryHost';

/** Why an input is not a scenario to modularize (a catalog, a parameter distribution, a modular main), or undefined for a plain scenario. */
export function notAPlainScenario(textOrDocument: string | XmlDocument): string | undefined {
  const document = typeof textOrDocument === 'string' ? parseXml(textOrDocument) : textOrDocument;
  const root = document.root;
  if (!root || root.name !== 'OpenSCENARIO') return 'not an OpenSCENARIO file';
  const kinds = root.children.map((child) => child.name);
  if (kinds.includes('Catalog')) return 'a catalog';
  if (kinds.includes('ParameterValueDistribution')) return 'a parameter value distribution';
  if (!kinds.includes('Storyboard')) return 'not a scenario (no Storyboard)';
  if (buildModel(document).references.length > 0) return 'already modular (it holds ScenarioReferences)';
  return undefined;
}

/** Groups of the inputs by shape, in the order first met; only shapes that recur and are not excluded. */
function recurringGroups(inputs: ParsedInput[], excluded: Set<string>): Map<string, { shape: GroupShape; occurrences: GroupOccurrence[] }> {
  const byShape = new Map<string, { shape: GroupShape; occurrences: GroupOccurrence[] }>();
  inputs.forEach((input, index) => {
    for (const group of buildModel(input.document).groups) {
      const read = readOccurrence(index, input.document, group);
      if (!read || excluded.has(read.shape.key)) continue;
      const known = byShape.get(read.shape.key);
      if (known) known.occurrences.push(read.occurrence);
      else byShape.set(read.shape.key, { shape: read.shape, occurrences: [read.occurrence] });
    }
  });
  for (const [key, entry] of byShape) if (entry.occurrences.length < 2) byShape.delete(key);
  return byShape;
}

/** The lines a behaviour's uses take in the inputs less those of the groups that import it (SPEC 9 lines). */
function linesReplaced(behaviour: Behaviour, inputs: ParsedInput[]): number {
  let replaced = 0;
  for (const use of behaviour.uses) {
    const input = inputs[use.occurrence.input];
    const group = use.occurrence.group.element;
    const reference = referenceGroup(input, behaviour, use, '', '  ', '\n');
    replaced += input.text.slice(group.start, group.end).split('\n').length - reference.split('\n').length;
  }
  return replaced;
}

/** A simple scenario's OpenSCENARIO version and its catalog locations (as rebased there), each kind of catalog by its text. */
interface FileSettings {
  version: string;
  catalogs: Map<string, string>;
}

function fileSettings(behaviour: Behaviour): FileSettings {
  const root = parseXml(behaviour.text).root;
  const header = root?.children.find((child) => child.name === 'FileHeader');
  const catalogs = new Map<string, string>();
  for (const catalog of root?.children.find((child) => child.name === 'CatalogLocations')?.children ?? [])
    catalogs.set(catalog.name, behaviour.text.slice(catalog.start, catalog.end));
  return { version: header ? `${attributeValue(header, 'revMajor')}.${attributeValue(header, 'revMinor')}` : '', catalogs };
}

/**
 * Whether two simple scenarios can share a file: one version, every kind of catalog both use in the same
 * place (and no `$` path). A parameter both declare with different values is no obstacle: the group that
 * reads it gets a copy of its own (see paying).
 */
function compatible(a: FileSettings, b: FileSettings): boolean {
  if (a.version !== b.version) return false;
  for (const [kind, text] of a.catalogs) {
    const other = b.catalogs.get(kind);
    if (text.includes('$') || (other !== undefined && other.replace(/\s+/g, ' ') !== text.replace(/\s+/g, ' '))) return false;
  }
  return ![...b.catalogs.values()].some((text) => text.includes('$'));
}

/** `text` (a shared simple scenario) with the catalog locations of all its members: each kind once. */
function withCatalogsOf(text: string, members: Behaviour[], unit: string, eol: string): string {
  const catalogs = new Map<string, string>();
  for (const member of members)
    for (const [kind, catalog] of fileSettings(member).catalogs) if (!catalogs.has(kind)) catalogs.set(kind, catalog);
  const element = parseXml(text).root?.children.find((child) => child.name === 'CatalogLocations');
  if (!element || catalogs.size === 0) return text;
  const written = [
    `<CatalogLocations>`,
    ...[...catalogs.values()].map((catalog) => `${unit}${unit}${catalog}`),
    `${unit}</CatalogLocations>`,
  ];
  return text.slice(0, element.start) + written.join(eol) + text.slice(element.end);
}

/** A shared file as `build` makes it: its text, the lines it saves in all, the members whose parameters it could not copy. */
interface PooledFile {
  text: string;
  net: number;
  /** The members as the text holds them (with the copies it needs). */
  members: Behaviour[];
  stuck: Behaviour[];
}

/**
 * The behaviours worth extracting, each with its simple scenario: behaviours that can share a file (see
 * compatible; a same-named group of another shape is renamed there) are written into one, which pays its
 * declarations, catalogs, roads and storyboard once. A group there that reads a parameter whose value differs
 * in some use's scenario reads a copy of its own, which each use overrides with its own reading; one that
 * cannot moves to a file of its own. A file is kept only when its uses save more lines than it takes, dropping its
 * least paying behaviours until it does; what is dropped is kept inline with the figures (never larger).
 */
async function paying(
  candidates: Behaviour[],
  inputs: ParsedInput[],
  rebase: RebasePaths,
  simpleFolder: string,
  taken: Set<string>,
  pooling: boolean,
  keptInline: ModularizeResult['keptInline'],
): Promise<Behaviour[]> {
  const pools: { settings: FileSettings; members: Behaviour[] }[] = [];
  for (const candidate of candidates) {
    const settings = fileSettings(candidate);
    const pool = pooling ? pools.find((other) => compatible(other.settings, settings)) : undefined;
    if (!pool) {
      pools.push({ settings, members: [candidate] });
      continue;
    }
    let behaviour = candidate;
    // Groups of one name that differ in shape (Euro NCAP's Synchronization_CollisionDetection) share the file under distinct names.
    if (pool.members.some((other) => other.groupName === candidate.groupName)) {
      const names = new Set(pool.members.map((other) => other.groupName.toLowerCase()));
      const wanted = uniqueName(candidate.groupName, names);
      const renamed = await planBehaviour(
        candidate.shapeKey,
        candidate.slots,
        candidate.part.occurrences,
        inputs,
        candidate.file,
        rebase,
        new Set(),
        wanted,
        new Set(candidate.part.copies?.values()),
      );
      if (!renamed.behaviour) {
        pools.push({ settings, members: [candidate] });
        continue;
      }
      behaviour = renamed.behaviour;
    }
    pool.members.push(behaviour);
    for (const [kind, catalog] of settings.catalogs) if (!pool.settings.catalogs.has(kind)) pool.settings.catalogs.set(kind, catalog);
  }
  const leaveInline = (behaviour: Behaviour, reason: string) => {
    for (const use of behaviour.uses)
      keptInline.push({ input: inputs[use.occurrence.input].path, group: use.occurrence.group.name, reason });
  };
  const result: Behaviour[] = [];
  // Pools grow while this runs: a member that cannot share a file's parameters moves to a pool of its own.
  for (let index = 0; index < pools.length; index++) {
    const { settings, members } = pools[index];
    // Each member as the shared file needs it: with copies of the parameters it reads whose values differ there.
    const variants = new Map<Behaviour, Behaviour>();
    const variant = (member: Behaviour) => variants.get(member) ?? member;
    const replacedLines = new Map<Behaviour, number>();
    const replaced = (member: Behaviour): number => {
      const planned = variant(member);
      const known = replacedLines.get(planned) ?? linesReplaced(planned, inputs);
      replacedLines.set(planned, known);
      return known;
    };
    // What a member adds to a shared file: its group's lines; one that cannot pay even that stays inline.
    const own = (member: Behaviour) => member.part.groupText.split('\n').length;
    let kept = members.filter((member) => {
      if (members.length === 1 || replaced(member) > own(member)) return true;
      leaveInline(
        member,
        `extracting it would not pay: its group alone takes ${own(member)} lines in a simple scenario, its ${member.uses.length} uses would save ${replaced(member)}`,
      );
      return false;
    });
    /** The file `chosen` would share and the lines it saves in all (its uses' lines less its own). */
    const build = async (chosen: Behaviour[]): Promise<PooledFile> => {
      if (chosen.length === 1) {
        const text = variant(chosen[0]).text;
        return { text, net: replaced(chosen[0]) - countEditorLines(text), members: [variant(chosen[0])], stuck: [] };
      }
      const representative = inputs[chosen[0].part.occurrences[0].input];
      const unit = indentUnit(representative.text, representative.document.root?.children[0]?.start);
      const eol = representative.text.includes('\r\n') ? '\r\n' : '\n';
      for (;;) {
        const planned = chosen.map(variant);
        const pooled = await simpleScenarioText({
          ...planned[0].part,
          others: planned.slice(1).map((member) => member.part),
          file: path.join(simpleFolder, 'behaviours.xosc'),
          inputs,
          unit,
          eol,
          rebase,
        });
        const text = withCatalogsOf(pooled, planned, unit, eol);
        const conflicts = parameterConflicts(
          text,
          planned.map((member) => member.part),
          inputs,
        );
        const net = chosen.reduce((sum, member) => sum + replaced(member), 0) - countEditorLines(text);
        if (conflicts.size === 0) return { text, net, members: planned, stuck: [] };
        const stuck: Behaviour[] = [];
        for (const [position, names] of conflicts) {
          const member = chosen[position];
          const copied = new Set(planned[position].part.copies?.values());
          if ([...names].every((name) => copied.has(name))) {
            stuck.push(member);
            continue;
          }
          const copying = await planBehaviour(
            member.shapeKey,
            member.slots,
            member.part.occurrences,
            inputs,
            member.file,
            rebase,
            new Set(),
            member.groupName,
            new Set([...copied, ...names]),
          );
          if (copying.behaviour) variants.set(member, copying.behaviour);
          else stuck.push(member);
        }
        if (stuck.length > 0) return { text, net: -Infinity, members: planned, stuck };
      }
    };
    let current = kept.length > 0 ? await build(kept) : undefined;
    // Members whose parameters the file cannot copy share a file of their own, as separate sources did before.
    while (current && current.stuck.length > 0) {
      const stuck = current.stuck;
      const moved = stuck.some((member) => member !== kept[0]) ? stuck.filter((member) => member !== kept[0]) : kept.slice(1);
      kept = kept.filter((member) => !moved.includes(member));
      pools.push({ settings, members: moved });
      current = await build(kept);
    }
    // A member whose leaving makes the file save more goes back inline (what it brings costs more than it saves).
    while (current && kept.length > 1) {
      let best: { member: Behaviour; built: PooledFile } | undefined;
      for (const member of kept) {
        const built = await build(kept.filter((other) => other !== member));
        if (built.net > (best?.built.net ?? current.net)) best = { member, built };
      }
      if (!best) break;
      leaveInline(
        best.member,
        `extracting it would not pay: sharing a simple scenario with ${kept.length - 1} other behaviour${kept.length - 1 === 1 ? '' : 's'} it adds more lines than its ${best.member.uses.length} uses save`,
      );
      kept = kept.filter((member) => member !== best.member);
      current = best.built;
    }
    if (!current || kept.length === 0) continue;
    if (current.net <= 0) {
      for (const member of kept)
        leaveInline(
          member,
          `extracting it would not pay: its simple scenario (${countEditorLines(current.text)} lines) outweighs the ${replaced(member)} lines its ${member.uses.length} uses would save`,
        );
      continue;
    }
    const file = kept.length === 1 ? kept[0].file : path.join(simpleFolder, `${uniqueName('behaviours', taken)}.xosc`);
    const text = current.text;
    for (const member of current.members) result.push({ ...member, file, text });
  }
  return result;
}

interface Plan {
  behaviours: Behaviour[];
  mains: MainResult[];
  keptInline: ModularizeResult['keptInline'];
}

async function plan(
  inputs: ParsedInput[],
  rebase: RebasePaths,
  simpleFolder: string,
  excluded: Map<string, string>,
  pooling: boolean,
): Promise<Plan> {
  const candidates: Behaviour[] = [];
  const keptInline: ModularizeResult['keptInline'] = [];
  const taken = new Set<string>();
  const pending = [...recurringGroups(inputs, new Set(excluded.keys())).values()].map(({ shape, occurrences }) => ({
    shape,
    occurrences,
    key: shape.key,
    depth: 0,
  }));
  while (pending.length > 0) {
    const { shape, occurrences, key, depth } = pending.shift() as (typeof pending)[number];
    if (excluded.has(key)) continue;
    const stem = uniqueName(behaviourName(occurrences[0].elements), taken);
    const file = path.join(simpleFolder, `${stem}.xosc`);
    const planned = await planBehaviour(key, shape.slots, occurrences, inputs, file, rebase);
    if (planned.behaviour) {
      candidates.push(planned.behaviour);
      continue;
    }
    taken.delete(stem.toLowerCase());
    // Uses that agree on the attributes no key tells apart can still share one behaviour.
    const parts = new Map<string, GroupOccurrence[]>();
    if (planned.conflict && depth < 4) {
      const conflict = planned.conflict;
      for (const occurrence of occurrences) {
        const values = JSON.stringify(conflict.map((index) => occurrence.values[index]));
        parts.set(values, [...(parts.get(values) ?? []), occurrence]);
      }
    }
    for (const [values, part] of parts)
      if (part.length > 1 && part.length < occurrences.length)
        pending.push({ shape, occurrences: part, key: `${key}\n${values}`, depth: depth + 1 });
    const alone = planned.conflict && depth < 4 ? [...parts.values()].filter((part) => part.length === 1).flat() : occurrences;
    for (const occurrence of alone)
      keptInline.push({
        input: inputs[occurrence.input].path,
        group: occurrence.group.name,
        reason: planned.reason ?? 'cannot be imported exactly',
      });
  }
  const behaviours = await paying(candidates, inputs, rebase, simpleFolder, taken, pooling, keptInline);
  const mains: MainResult[] = [];
  for (const [index, input] of inputs.entries()) {
    const uses = behaviours.flatMap((behaviour) =>
      behaviour.uses.filter((use) => use.occurrence.input === index).map((use) => ({ behaviour, use })),
    );
    const text = mainText(input, uses);
    mains.push({
      input: input.path,
      output: input.output,
      text,
      linesBefore: countEditorLines(input.text),
      linesAfter: countEditorLines(text),
      imports: uses.map(({ behaviour }) => behaviour.file),
    });
  }
  return { behaviours, mains, keptInline };
}

/**
 * Flattens every main that imports something, with the simple scenarios read from memory, and compares
 * it with its input rebased onto the main's folder (SPEC 8): the first difference of each that differs, or
 * the parameter-conflict its flattening would warn of.
 */
async function verify(inputs: ParsedInput[], planned: Plan, limits: Partial<Limits>): Promise<ModularizeResult['failures']> {
  const files = new Map<string, string>();
  for (const behaviour of planned.behaviours) files.set(path.resolve(behaviour.file), behaviour.text);
  for (const main of planned.mains) if (main.imports.length > 0) files.set(path.resolve(main.output), main.text);
  const store = new ScenarioStore({ host: memoryHost(files), scenarioPath: [], limits });
  const flattener = new Flattener(store);
  const failures: ModularizeResult['failures'] = [];
  for (const [index, main] of planned.mains.entries()) {
    if (main.imports.length === 0) continue;
    const ref = diskRef(path.resolve(main.output));
    let result = await flattener.flatten(ref, { outputPath: main.output });
    // A main and its simple scenarios keep the input's catalog locations and references: their errors (a catalog
    // directory absent here) are the input's own, no reason to keep its groups inline; any other error is.
    const errors = result.problems.filter((problem) => problem.severity === 'error');
    const inputsOwn = (problem: Problem) =>
      CATALOG_CODES.has(problem.code) || (problem.code === 'source-errors' && CATALOG_CODES.has(problem.cause?.code ?? 'source-errors'));
    if (result.text === undefined && errors.length > 0 && errors.every(inputsOwn))
      result = await flattener.flatten(ref, { outputPath: main.output, force: true });
    if (result.text === undefined) {
      const error = result.problems.find((problem) => problem.severity === 'error');
      failures.push({ input: main.input, difference: `the main does not flatten: ${error?.message ?? 'no output'}` });
      continue;
    }
    const input = inputs[index];
    const expected = applyEdits(input.text, input.pathEdits);
    const difference = firstDifference(result.text, expected);
    if (difference) failures.push({ input: main.input, difference });
    // Equivalent, but warned that a declaration of the main differs from its simple scenario's: not what the input said either.
    const conflict = result.problems.find((problem) => problem.code === 'parameter-conflict');
    if (!difference && conflict) failures.push({ input: main.input, difference: `its main would be warned: ${conflict.message}` });
  }
  return failures;
}

/**
 * Extracts the ManeuverGroups that recur across `inputs` (same elements and attribute names in the
 * same order) into simple scenarios and writes a main per input that imports them; nothing is
 * written here. A behaviour whose mains do not flatten back to their inputs is kept inline and the
 * rest tried again, so `failures` names only inputs that still differ with every behaviour inline.
 */
export async function modularize(
  inputs: ModularizeInput[],
  options: ModularizeOptions,
  limits: Partial<Limits> = {},
): Promise<ModularizeResult> {
  const rebase = options.rebase ?? pathRebaser();
  const parsed: ParsedInput[] = [];
  // The catalogs are read as check reads them, each input's own text in place of the disk's.
  const catalogStore = new ScenarioStore({
    host: memoryHost(new Map(inputs.map((input) => [path.resolve(input.path), input.text]))),
    scenarioPath: [],
    limits,
  });
  for (const input of inputs) {
    const document = input.document ?? parseXml(input.text);
    const catalogParameters =
      input.catalogParameters ??
      (await catalogParametersOf(
        catalogStore,
        diskRef(path.resolve(input.path)),
        document,
        buildModel(document).groups.map((group) => group.element),
      ));
    parsed.push({
      ...input,
      document,
      catalogParameters,
      pathEdits: await rebase(document, path.dirname(input.path), path.dirname(input.output)),
    });
  }
  const excluded = new Map<string, string>();
  let pooling = true;
  let planned = await plan(parsed, rebase, options.simpleFolder, excluded, pooling);
  let failures = await verify(parsed, planned, limits);
  if (failures.length > 0) {
    // A shared file may be what fails (two behaviours' declarations at odds): each in its own file, then.
    pooling = false;
    planned = await plan(parsed, rebase, options.simpleFolder, excluded, pooling);
    failures = await verify(parsed, planned, limits);
  }
  const keptInline: ModularizeResult['keptInline'] = [];
  for (let round = 0; failures.length > 0 && round < 8; round++) {
    const failing = new Set(failures.map((failure) => failure.input));
    let dropped = 0;
    for (const behaviour of planned.behaviours) {
      const failure = failures.find((candidate) => behaviour.uses.some((use) => parsed[use.occurrence.input].path === candidate.input));
      if (!failure || !behaviour.uses.some((use) => failing.has(parsed[use.occurrence.input].path))) continue;
      excluded.set(behaviour.shapeKey, failure.difference);
      dropped++;
      for (const use of behaviour.uses)
        keptInline.push({
          input: parsed[use.occurrence.input].path,
          group: use.occurrence.group.name,
          reason: `its main would not flatten back exactly (${failure.difference})`,
        });
    }
    if (dropped === 0) break;
    planned = await plan(parsed, rebase, options.simpleFolder, excluded, pooling);
    failures = await verify(parsed, planned, limits);
  }
  const linesBefore = planned.mains.reduce((sum, main) => sum + main.linesBefore, 0);
  const linesAfter =
    planned.mains.reduce((sum, main) => sum + main.linesAfter, 0) +
    [...new Map(planned.behaviours.map((behaviour) => [behaviour.file, behaviour.text])).values()].reduce(
      (sum, text) => sum + countEditorLines(text),
      0,
    );
  return {
    mains: planned.mains,
    behaviours: planned.behaviours,
    failures,
    keptInline: [...planned.keptInline, ...keptInline],
    totals: { linesBefore, linesAfter, reduction: linesBefore === 0 ? 0 : Math.round((1 - linesAfter / linesBefore) * 1000) / 10 },
  };
}
