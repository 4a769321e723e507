/**
 * Scenario libraries: folders of simple scenarios (modules) that any main file names as `library:NAME`
 * (SPEC 3 as the project extends it, docs/library.md). A module opens with a doc block, an XML comment
 * that this module reads:
 *
 *     <!-- library module
 *     name: cut-in
 *     title: Cut-in
 *     group: Vehicles ahead
 *     maneuverGroup: CutIn
 *     actor: adversary: the cutting-in car, in a lane beside the ego's
 *     summary: A vehicle ... changes into the ego's lane.
 *     parameter RelativeDistanceCondition.value = gap [m] (2..100): the gap when the lane change starts
 *     -->
 *
 * Each `parameter` line names a key of the group (SPEC 5), a short name, a unit, a range and what it means;
 * its default is the attribute's own value in the file.
 */
import { decodeScenario } from './encoding';
import { keyMatches, overridableAttributes } from './keys';
import { findGroup, ManeuverGroupInfo, parseScenario } from './model';
import { attributeValue } from './xml';
import { pathsFor } from './paths';
import { FileSystemHost, LibraryFolder, LIBRARY_PREFIX } from './sources';
import { closestMatch, LineIndex } from './text';

export interface ModuleParameter {
  key: string;
  name: string;
  unit?: string;
  /** The range as written (`2..100`), and its bounds when they are numbers. */
  range?: string;
  min?: number;
  max?: number;
  about: string;
  /** The attribute's value in the module: what the key gives when a main file leaves it out. */
  defaultValue: string | undefined;
}

export interface LibraryModule {
  /** What `library:NAME` names: the file name without `.xosc`. */
  name: string;
  file: string;
  library: LibraryFolder;
  title: string;
  group: string;
  summary: string;
  maneuverGroup: string;
  actor: { name: string; about: string };
  /**
   * The entities the group's `Actors` names, in order (the first is the one a main's outer group sets, SPEC 4 step 2):
   * a group whose actions apply alike to several (traffic-jam-end's queue) names them all.
   */
  actors: string[];
  parameters: ModuleParameter[];
  /** `examples/NAME.xosc` of the library, a main file that uses the module, when it exists. */
  example?: string;
  /** `pictures/NAME.svg` of the library, when it exists. */
  picture?: string;
  /** The files of modules of the same name in later libraries, which this one hides. */
  hides: string[];
  /**
   * Its actor's place in the ego's lane, for *Insert into Main* (doc block `queue:`): `enters` it ahead of the ego (a cut-in),
   * or drives `slower` than the ego ahead in it (a braking lead): a slower one goes behind the ones that enter (docs/library.md).
   */
  queue?: ModuleQueue;
}

export type ModuleQueue = 'enters' | 'slower';
const QUEUES: readonly string[] = ['enters', 'slower'] satisfies ModuleQueue[];

/** A library folder or module file that cannot be used, and why; the rest of the library still is. */
export interface LibraryProblem {
  file: string;
  line?: number;
  message: string;
}

export interface LibraryListing {
  /** Every usable module, the first library's first: a name hidden by an earlier library is not listed again. */
  modules: LibraryModule[];
  problems: LibraryProblem[];
}

const DOC_BLOCK = /<!--\s*library module\b([\s\S]*?)-->/;
const PARAMETER_LINE = /^parameter\s+(\S+)\s*=\s*([^\s[(:]+)\s*(?:\[([^\]]*)\])?\s*(?:\(([^)]*)\))?\s*:\s*(.*)$/;

/** The entityRefs of a group's own `Actors`, in order. */
function groupActors(group: ManeuverGroupInfo | undefined): string[] {
  const actors = group?.element.children.find((child) => child.name === 'Actors');
  return (actors?.children ?? [])
    .filter((child) => child.name === 'EntityRef')
    .map((entityRef) => attributeValue(entityRef, 'entityRef') ?? '')
    .filter((name) => name !== '');
}

/** The module a file's text describes, or the problems that keep it out of the library. */
export function readModule(text: string, file: string, library: LibraryFolder): { module?: LibraryModule; problems: LibraryProblem[] } {
  const problems: LibraryProblem[] = [];
  const lines = new LineIndex(text);
  const lineAt = (offset: number) => lines.positionAt(offset).line + 1;
  const block = DOC_BLOCK.exec(text);
  if (!block) {
    return {
      problems: [{ file, line: 1, message: 'no doc block: a library module opens with <!-- library module ... --> (docs/library.md)' }],
    };
  }
  const fields = new Map<string, { value: string; line: number }>();
  const parameterLines: { text: string; line: number }[] = [];
  let offset = block.index + block[0].indexOf(block[1]);
  for (const raw of block[1].split('\n')) {
    const line = raw.trim();
    const lineNumber = lineAt(offset);
    offset += raw.length + 1;
    if (!line) continue;
    if (line.startsWith('parameter ')) {
      parameterLines.push({ text: line, line: lineNumber });
      continue;
    }
    const colon = line.indexOf(':');
    if (colon < 0) {
      problems.push({
        file,
        line: lineNumber,
        message: `'${line}' is neither 'field: value' nor 'parameter KEY = NAME [UNIT] (MIN..MAX): what it is'`,
      });
      continue;
    }
    fields.set(line.slice(0, colon).trim(), { value: line.slice(colon + 1).trim(), line: lineNumber });
  }
  const name = pathsFor(file)
    .basename(file)
    .replace(/\.xosc$/i, '');
  const blockLine = lineAt(block.index);
  const required = (field: string) => {
    const found = fields.get(field);
    if (!found || !found.value) problems.push({ file, line: blockLine, message: `the doc block has no '${field}:'` });
    return found?.value ?? '';
  };
  const declaredName = fields.get('name');
  if (declaredName && declaredName.value !== name)
    problems.push({
      file,
      line: declaredName.line,
      message: `the doc block names '${declaredName.value}', the file '${name}': ${LIBRARY_PREFIX}${name} is what a main writes`,
    });
  const title = required('title');
  const group = required('group');
  const summary = required('summary');
  const maneuverGroup = required('maneuverGroup');
  const actorField = required('actor');
  const actorColon = actorField.indexOf(':');
  const actor =
    actorColon < 0
      ? { name: actorField, about: '' }
      : { name: actorField.slice(0, actorColon).trim(), about: actorField.slice(actorColon + 1).trim() };

  const queueField = fields.get('queue');
  if (queueField && !QUEUES.includes(queueField.value))
    problems.push({
      file,
      line: queueField.line,
      message: `'queue: ${queueField.value}' is neither 'enters' (the actor enters the ego's lane ahead of it) nor 'slower' (it drives slower ahead in that lane)`,
    });
  const queue = queueField && QUEUES.includes(queueField.value) ? (queueField.value as ModuleQueue) : undefined;

  const model = parseScenario(text);
  const parseError = model.document.problems.find((problem) => problem.severity === 'error');
  if (parseError) problems.push({ file, line: lineAt(parseError.start), message: `not well-formed XML: ${parseError.message}` });
  const groupInfo = maneuverGroup ? findGroup(model, maneuverGroup) : undefined;
  if (maneuverGroup && !groupInfo && !parseError) {
    const suggestion = closestMatch(
      maneuverGroup,
      model.groups.map((candidate) => candidate.name),
    );
    problems.push({
      file,
      line: fields.get('maneuverGroup')?.line,
      message: `no ManeuverGroup '${maneuverGroup}' in the module${suggestion ? `: did you mean '${suggestion}'?` : ''}`,
    });
  }
  const targets = groupInfo ? overridableAttributes(model, groupInfo) : [];
  const parameters: ModuleParameter[] = [];
  for (const { text: parameterText, line } of parameterLines) {
    const match = PARAMETER_LINE.exec(parameterText);
    if (!match) {
      problems.push({ file, line, message: `'${parameterText}' is not 'parameter KEY = NAME [UNIT] (MIN..MAX): what it is'` });
      continue;
    }
    const [, key, parameterName, unit, range, about] = match;
    const reached = targets.filter((target) => keyMatches(key, target));
    if (groupInfo && reached.length === 0) {
      problems.push({
        file,
        line,
        message: `the key '${key}' reaches no attribute that group '${maneuverGroup}' lists in parameterAttributes`,
      });
      continue;
    }
    const bounds = range?.split('..').map((bound) => Number(bound.trim()));
    parameters.push({
      key,
      name: parameterName,
      ...(unit ? { unit: unit.trim() } : {}),
      ...(range ? { range: range.trim() } : {}),
      ...(bounds && bounds.length === 2 && bounds.every(Number.isFinite) ? { min: bounds[0], max: bounds[1] } : {}),
      about: about.trim(),
      defaultValue: reached[0]?.defaultValue,
    });
  }
  if (groupInfo) {
    const undocumented = targets.filter((target) => !parameters.some((parameter) => keyMatches(parameter.key, target)));
    for (const target of undocumented)
      problems.push({
        file,
        line: lineAt(target.declaration.start),
        message: `'${target.path.slice(1).concat(target.attributeName).join('.')}' is listed in parameterAttributes but no 'parameter' line of the doc block names it`,
      });
  }
  if (problems.length > 0) return { problems };
  return {
    module: {
      name,
      file,
      library,
      title,
      group,
      summary,
      maneuverGroup,
      actor,
      actors: groupActors(groupInfo),
      parameters,
      hides: [],
      ...(queue ? { queue } : {}),
    },
    problems,
  };
}

/**
 * The modules of the libraries, in order: a name found in an earlier library hides the same name in a later
 * one (the earlier module `hides` the later file). A folder that does not exist and a file that is not a
 * usable module are each reported; the others are listed.
 */
export async function listLibraries(host: FileSystemHost, libraries: readonly LibraryFolder[]): Promise<LibraryListing> {
  const modules: LibraryModule[] = [];
  const problems: LibraryProblem[] = [];
  for (const library of libraries) {
    const paths = pathsFor(library.folder);
    if ((await host.kind(library.folder)) !== 'directory') {
      problems.push({ file: library.folder, message: `the ${library.label} library folder does not exist (or is not a folder)` });
      continue;
    }
    const entries = ((await host.listDirectory?.(library.folder)) ?? []).filter((entry) => /\.xosc$/i.test(entry)).sort();
    const names = new Set(((await host.listDirectory?.(paths.join(library.folder, 'examples'))) ?? []).map((entry) => entry));
    const pictures = new Set((await host.listDirectory?.(paths.join(library.folder, 'pictures'))) ?? []);
    for (const entry of entries) {
      const file = paths.join(library.folder, entry);
      let text: string;
      try {
        const bytes = await host.readFile(file);
        if (!bytes) continue;
        text = decodeScenario(bytes);
      } catch (error) {
        problems.push({ file, message: (error as Error).message });
        continue;
      }
      const read = readModule(text, file, library);
      problems.push(...read.problems);
      if (!read.module) continue;
      const module = read.module;
      if (names.has(entry)) module.example = paths.join(library.folder, 'examples', entry);
      if (pictures.has(`${module.name}.svg`)) module.picture = paths.join(library.folder, 'pictures', `${module.name}.svg`);
      const earlier = modules.find((other) => other.name === module.name);
      if (earlier) earlier.hides.push(file);
      else modules.push(module);
    }
  }
  return { modules, problems };
}

/** The module of that name, or the closest name for a "did you mean". */
export function findModule(listing: LibraryListing, name: string): { module?: LibraryModule; suggestion?: string } {
  const wanted = name.startsWith(LIBRARY_PREFIX) ? name.slice(LIBRARY_PREFIX.length) : name;
  const module = listing.modules.find((candidate) => candidate.name === wanted.replace(/\.xosc$/i, ''));
  if (module) return { module };
  return {
    suggestion: closestMatch(
      wanted,
      listing.modules.map((candidate) => candidate.name),
    ),
  };
}
