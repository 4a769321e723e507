import * as path from 'node:path';
import { CodeLens, CompletionItem, CompletionItemKind, Hover, MarkupKind, TextEdit } from 'vscode-languageserver/node';
import { valueContextAt } from '../core/cursor';
import { childRef, diskRef, refId, SourceRef } from '../core/sources';
import { loadVariations, SamplingError, Variations } from '../core/variations';
import { DistributionRead, distributionProblems, isDistributionParse, isDistributionText } from '../core/variations/problems';
import { LineIndex } from '../core/text';
import { readScenarioParameters } from '../core/variations/concrete';
import { expandDeterministic } from '../core/variations/deterministic';
import { ParameterValue } from '../core/variations/distribution';
import { attribute, descendants, parseXml, XmlElement } from '../core/xml';
import { Place } from '../analysis';
import { Workspace } from '../workspace';
import { SERVER_MEMOS, serverMemo } from '../database';

/** The client command that runs `batch` for a distribution file (CodeLens and palette). */
export const RUN_VARIATIONS_COMMAND = 'modular2simple.runVariations';

/** Constrained distributions with more combinations than this are not counted one by one in the editor. */
export const MAX_COUNTED_COMBINATIONS = 200_000n;

/** Values a hover lists before it says how many there are. */
const HOVER_VALUES = 5;

const REFERENCE = /<ScenarioReference\b/;

/** The number of concrete scenarios, as `vary --count` gives it. */
export type DistributionCount = { concrete: bigint; discarded: bigint; total: bigint } | { total: bigint; uncounted: string };

/** A distribution file read with its scenario, once per workspace generation. */
export interface DistributionAnalysis extends DistributionRead {
  /** The ScenarioFile's absolute path, where the file names one. */
  scenarioPath: string | undefined;
  /** The file that declares the scenario's root parameters as written (a modular main inside a `.mosc`). */
  scenarioRef: SourceRef | undefined;
}

const analyses = serverMemo<Workspace, Map<string, { version: number; analysis: Promise<DistributionAnalysis | undefined> }>>(
  'distributionAnalyses',
);

export { distributionProblems, isDistributionText };

/** The file's distribution read with its scenario; undefined when it is not a distribution file on disk. */
export function distributionAnalysis(workspace: Workspace, ref: SourceRef): Promise<DistributionAnalysis | undefined> {
  let perWorkspace = analyses.get(workspace);
  if (!perWorkspace) analyses.set(workspace, (perWorkspace = new Map()));
  const id = refId(ref);
  const cached = perWorkspace.get(id);
  if (cached && cached.version === workspace.version) return cached.analysis;
  const analysis = analyze(workspace, ref, cached?.analysis);
  perWorkspace.set(id, { version: workspace.version, analysis });
  if (perWorkspace.size > SERVER_MEMOS.distributionAnalyses.bound.entries)
    for (const [key, entry] of perWorkspace) if (entry.version !== workspace.version) perWorkspace.delete(key);
  return analysis;
}

/** Whether the file's text is a distribution's: an open file's parse of this text (its analysis made it) answers once, and carries the answer over a value edit. */
function isDistribution(workspace: Workspace, ref: SourceRef, text: string): boolean {
  const parse = workspace.store.lastParse(ref, text);
  return parse ? isDistributionParse(parse) : isDistributionText(text);
}

async function analyze(
  workspace: Workspace,
  ref: SourceRef,
  previous: Promise<DistributionAnalysis | undefined> | undefined,
): Promise<DistributionAnalysis | undefined> {
  // A distribution inside a package has no folder of its own for the ScenarioFile to resolve from.
  if (ref.entries.length > 0) return undefined;
  const text = await workspace.text(ref);
  if (text === undefined || !isDistribution(workspace, ref, text)) return undefined;
  const file = ref.disk;
  let scenarioText: string | undefined;
  let scenarioRef: SourceRef | undefined;
  let scenarioPath: string | undefined;
  const loaded = await loadVariations(text, file, async (absolute) => {
    scenarioPath = absolute;
    const read = await scenarioTextOf(workspace, absolute);
    scenarioText = read.text;
    scenarioRef = read.declaredIn;
    return read.text;
  });
  // A value being typed (its quote not yet closed) leaves the file unreadable: its scenario is the one it named a moment ago.
  if (scenarioText === undefined && parseXml(text).problems.length > 0) {
    const before = await previous?.catch(() => undefined);
    if (before?.scenarioRef)
      return { ref, file, text, loaded, scenarioPath: before.scenarioPath, scenarioRef: before.scenarioRef, parameters: before.parameters };
  }
  const parameters =
    scenarioText === undefined ? [] : (readScenarioParameters(scenarioText, scenarioPath ?? '').scenario?.declarations ?? []);
  return { ref, file, text, loaded, scenarioPath, scenarioRef, parameters };
}

/** The ScenarioFile as plain OpenSCENARIO, as the editor has it: a plain file as it is, a modular main, folder or `.mosc` flattened. */
async function scenarioTextOf(workspace: Workspace, absolute: string): Promise<{ text: string; declaredIn: SourceRef }> {
  const kind = await workspace.store.kindOf(absolute);
  if (kind === undefined) throw Object.assign(new Error('no such file'), { code: 'ENOENT' });
  let main: SourceRef;
  if (kind === 'directory') main = diskRef(path.join(absolute, 'main.xosc'));
  else if (absolute.toLowerCase().endsWith('.mosc')) main = childRef(diskRef(absolute), 'main.xosc');
  else {
    main = diskRef(absolute);
    const text = await workspace.store.readText(main);
    if (!REFERENCE.test(text)) return { text, declaredIn: main };
  }
  const result = await workspace.flattener().flatten(main);
  if (result.text !== undefined) return { text: result.text, declaredIn: main };
  const errors = result.problems.filter((problem) => problem.severity === 'error');
  const first = errors[0];
  throw new Error(`cannot be flattened (${errors.length} error${errors.length === 1 ? '' : 's'})` + (first ? `: ${first.message}` : ''));
}

const counts = serverMemo<Variations, DistributionCount>('distributionCounts');

/** How many concrete scenarios the distribution gives, discarding those its scenario's ValueConstraintGroups refuse; once per analysis. */
export function countConcrete(variations: Variations): DistributionCount {
  const known = counts.get(variations);
  if (known) return known;
  const count = countEach(variations);
  counts.set(variations, count);
  return count;
}

function countEach(variations: Variations): DistributionCount {
  if (!variations.constrained) return { concrete: variations.count, discarded: 0n, total: variations.count };
  if (variations.count > MAX_COUNTED_COMBINATIONS)
    return {
      total: variations.count,
      uncounted: `more than ${MAX_COUNTED_COMBINATIONS} combinations are not checked against the ValueConstraintGroups one by one`,
    };
  let discarded = 0n;
  try {
    for (let index = 0n; index < variations.count; index++) if (variations.brokenAt(index)) discarded++;
  } catch (error) {
    if (!(error instanceof SamplingError)) throw error;
    return { total: variations.count, uncounted: error.message };
  }
  return { concrete: variations.count - discarded, discarded, total: variations.count };
}

function plural(count: bigint, word: string): string {
  return `${count} ${word}${count === 1n ? '' : 's'}`;
}

/** The count above the distribution, and Run Variations. */
export async function distributionLenses(workspace: Workspace, uri: string, ref: SourceRef): Promise<CodeLens[]> {
  const analysis = await distributionAnalysis(workspace, ref);
  if (!analysis) return [];
  const document = parseXml(analysis.text);
  const element = document.root?.children.find((candidate) => candidate.name === 'ParameterValueDistribution');
  if (!element) return [];
  const lines = new LineIndex(analysis.text);
  const range = lines.range(element.start, element.start + 1 + element.name.length);
  const variations = analysis.loaded.variations;
  if (!variations) return [{ range, command: { title: 'no concrete scenarios: the distribution has errors', command: '' } }];
  const count = countConcrete(variations);
  const title =
    'uncounted' in count
      ? `${plural(count.total, 'combination')} (${count.uncounted})`
      : `${plural(count.concrete, 'concrete scenario')}` +
        (count.discarded > 0n ? ` (${count.discarded} of ${count.total} discarded by ValueConstraintGroups)` : '');
  return [
    { range, command: { title, command: '' } },
    { range, command: { title: 'Run Variations', command: RUN_VARIATIONS_COMMAND, arguments: [uri] } },
  ];
}

const DISTRIBUTION_ELEMENTS = new Set([
  'DeterministicSingleParameterDistribution',
  'DeterministicMultiParameterDistribution',
  'StochasticDistribution',
]);

function elementsAt(root: XmlElement | undefined, offset: number): XmlElement[] {
  const found: XmlElement[] = [];
  let current = root;
  while (current) {
    found.push(current);
    current = current.children.find((child) => child.start <= offset && offset < child.end);
  }
  return found;
}

function assignmentText(alternative: ParameterValue[]): string {
  return alternative.map((assignment) => `${assignment.parameter} = ${assignment.value}`).join(', ');
}

/** On a distribution element's start tag: the values it gives (the first few and how many). */
export async function distributionHover(workspace: Workspace, ref: SourceRef, offset: number): Promise<Hover | null> {
  const analysis = await distributionAnalysis(workspace, ref);
  const variations = analysis?.loaded.variations;
  if (!analysis || !variations) return null;
  const element = elementsAt(parseXml(analysis.text).root, offset).find((candidate) => DISTRIBUTION_ELEMENTS.has(candidate.name));
  if (!element || offset > element.startTagEnd) return null;
  const inElement = (at: number) => element.start <= at && at < element.end;
  const lines = new LineIndex(analysis.text);
  const range = lines.range(element.start, element.startTagEnd);
  const deterministic = variations.distribution.deterministic;
  if (deterministic) {
    const factor = deterministic.findIndex((candidate) => inElement(candidate.offset));
    if (factor < 0) return null;
    const alternatives = expandDeterministic([deterministic[factor]], analysis.file).expansion.factors[0] ?? [];
    const listed = alternatives.slice(0, HOVER_VALUES).map((alternative) => `- ${assignmentText(alternative)}`);
    const more = alternatives.length > HOVER_VALUES ? [`- … (${alternatives.length - HOVER_VALUES} more)`] : [];
    const value = [`**${plural(BigInt(alternatives.length), 'value')}**`, '', ...listed, ...more].join('\n');
    return { contents: { kind: MarkupKind.Markdown, value }, range };
  }
  const stochastic = variations.distribution.stochastic;
  const drawn = stochastic?.distributions.find((candidate) => inElement(candidate.offset));
  if (!stochastic || !drawn) return null;
  const draws: string[] = [];
  try {
    for (let index = 0; index < Math.min(HOVER_VALUES, stochastic.runs); index++) {
      const value = variations.assignmentAt(BigInt(index)).find((assignment) => assignment.parameter === drawn.parameter);
      if (value) draws.push(`- run ${index}: ${value.value}`);
    }
  } catch (error) {
    if (!(error instanceof SamplingError)) throw error;
    draws.push(`- ${error.message}`);
  }
  const more = stochastic.runs > HOVER_VALUES ? [`- … (${stochastic.runs - HOVER_VALUES} more)`] : [];
  const value = [
    `**${plural(BigInt(stochastic.runs), 'draw')}** from a ${drawn.sampler.kind} distribution (seed ${stochastic.seed})`,
    '',
    ...draws,
    ...more,
  ].join('\n');
  return { contents: { kind: MarkupKind.Markdown, value }, range };
}

/**
 * The `parameterName` or `parameterRef` value the offset stands in, as the file's tolerant tree has it
 * (core/cursor, which every feature asks what is at an offset; a value still being typed ends at the cursor's line).
 */
function parameterNameAt(text: string, offset: number): { start: number; end: number; name: string } | undefined {
  const value = valueContextAt(parseXml(text), offset);
  if (!value || (value.attribute !== 'parameterName' && value.attribute !== 'parameterRef')) return undefined;
  return { start: value.valueStart, end: value.valueEnd, name: text.slice(value.valueStart, value.valueEnd) };
}

/** In a `parameterName` or `parameterRef`: the scenario's root parameters, with type and default. */
export async function distributionCompletion(
  workspace: Workspace,
  ref: SourceRef,
  text: string,
  offset: number,
): Promise<CompletionItem[] | undefined> {
  if (!isDistribution(workspace, ref, text)) return undefined;
  const at = parameterNameAt(text, offset);
  if (!at) return undefined;
  const analysis = await distributionAnalysis(workspace, ref);
  if (!analysis) return undefined;
  const lines = new LineIndex(text);
  const range = lines.range(at.start, at.end);
  const seen = new Set<string>();
  return analysis.parameters
    .filter((declaration) => !seen.has(declaration.name) && seen.add(declaration.name))
    .map((declaration, index) => ({
      label: declaration.name,
      kind: CompletionItemKind.Variable,
      detail: `${declaration.type} = ${declaration.value}`,
      sortText: String(index).padStart(5, '0'),
      textEdit: { range, newText: declaration.name },
    }));
}

/** From a `parameterName` or `parameterRef` to its declaration in the scenario file. */
export async function distributionDefinition(workspace: Workspace, ref: SourceRef, offset: number): Promise<Place[] | undefined> {
  const analysis = await distributionAnalysis(workspace, ref);
  if (!analysis) return undefined;
  const at = parameterNameAt(analysis.text, offset);
  if (!at || !analysis.scenarioRef) return undefined;
  const declaredText = await workspace.text(analysis.scenarioRef);
  if (declaredText === undefined) return [];
  const declaration = readScenarioParameters(declaredText, '').scenario?.declarations.find((candidate) => candidate.name === at.name);
  if (!declaration) return [];
  const nameValue = new RegExp(`\\bname\\s*=\\s*["']`).exec(declaredText.slice(declaration.offset));
  const start = nameValue ? declaration.offset + nameValue.index + nameValue[0].length : declaration.offset;
  const lines = new LineIndex(declaredText);
  return [{ ref: analysis.scenarioRef, range: lines.range(start, start + (nameValue ? declaration.name.length : 0)) }];
}

/** The attributes of a distribution file that name a root parameter of its ScenarioFile, by element. */
const PARAMETER_NAMING: Readonly<Record<string, string>> = {
  DeterministicSingleParameterDistribution: 'parameterName',
  StochasticDistribution: 'parameterName',
  ParameterAssignment: 'parameterRef',
};

/**
 * A root parameter renamed in `scenario`: the same name changed in every distribution file of the workspace that
 * varies it (its `parameterName`s and `parameterRef`s; a `$` written before the name is kept), by file URI.
 */
export async function distributionRenameEdits(
  workspace: Workspace,
  scenario: SourceRef,
  oldName: string,
  newName: string,
): Promise<Record<string, TextEdit[]>> {
  const changes: Record<string, TextEdit[]> = {};
  for (const file of await workspace.distributionsOf(scenario)) {
    const ref = diskRef(file);
    const text = await workspace.text(ref);
    if (text === undefined) continue;
    const document = parseXml(text);
    const edits: TextEdit[] = [];
    for (const element of document.root ? descendants(document.root) : []) {
      const naming = PARAMETER_NAMING[element.name];
      const value = naming ? attribute(element, naming) : undefined;
      if (!value || (value.value !== oldName && value.value !== `$${oldName}`)) continue;
      edits.push(TextEdit.replace(document.lines.range(value.valueEnd - oldName.length, value.valueEnd), newName));
    }
    if (edits.length > 0) changes[workspace.uriOf(ref)] = edits;
  }
  return changes;
}
