import * as path from 'node:path';
import { distributionWording } from '../diagnostics/distribution';
import { unknownDistributionParameterWording } from '../diagnostics/unknownDistributionParameter';
import { Problem } from '../problems';
import { SourceRef } from '../sources';
import { closestMatch, LineIndex, Range } from '../text';
import { parseTextMatches, TextSearch, textMatches, XmlDocument } from '../xml';
import type { DeclaredParameter } from './concrete';
import type { VariationProblem } from './distribution';
import type { LoadResult } from './index';

/** A distribution file's root element, as a quick scan finds it. */
const DISTRIBUTION_ELEMENT = /<ParameterValueDistribution\b/;

/** The scan for it: a match and its `\b` look at 28 characters. */
const DISTRIBUTION_SEARCH: TextSearch = { pattern: DISTRIBUTION_ELEMENT, literal: '<ParameterValueDistribution', span: 28 };

/** Whether a text is a ParameterValueDistribution file (a quick scan, before any parse). */
export function isDistributionText(text: string): boolean {
  return textMatches(text, DISTRIBUTION_SEARCH);
}

/** `isDistributionText` of a parse's text, scanned once per parse and carried over an edit inside one value (a keystroke in a large scenario). */
export function isDistributionParse(document: XmlDocument): boolean {
  return parseTextMatches(document, DISTRIBUTION_SEARCH);
}

/** A distribution file read with its ScenarioFile, as the editor and `check` read it (the engine's `vary` reading). */
export interface DistributionRead {
  ref: SourceRef;
  /** The distribution file's absolute path, as the engine's problems name it. */
  file: string;
  text: string;
  loaded: LoadResult;
  /** The root parameters of the scenario as esmini sees it (flattened for a modular main): the names a misspelt parameterName is compared with. */
  parameters: DeclaredParameter[];
}

/** The extent of what a problem's offset points at: an attribute value, or an element's name. */
function extentAt(text: string, offset: number): { start: number; end: number } {
  const quote = text[offset - 1];
  if (quote === '"' || quote === "'") {
    const end = text.indexOf(quote, offset);
    return { start: offset, end: end < 0 ? offset : end };
  }
  if (text[offset] === '<') {
    const name = /^<[\w:.-]*/.exec(text.slice(offset, offset + 200));
    return { start: offset + 1, end: offset + (name ? name[0].length : 1) };
  }
  return { start: offset, end: Math.min(text.length, offset + 1) };
}

/** The engine's problems as the file's problems: those in the scenario are shown at the ScenarioFile. */
export function distributionProblems(analysis: DistributionRead): Problem[] {
  const lines = new LineIndex(analysis.text);
  const scenarioFileOffset = analysis.loaded.variations?.distribution.scenarioFile.offset ?? scenarioFileAttributeOffset(analysis.text);
  const names = analysis.parameters.map((declaration) => declaration.name);
  return [...analysis.loaded.problems, ...rangeWarnings(analysis)].map((problem): Problem => {
    const own = problem.file === analysis.file;
    const extent = extentAt(analysis.text, own ? problem.offset : scenarioFileOffset);
    const range: Range = lines.range(extent.start, extent.end);
    const severity = problem.severity;
    const undeclared = own ? problem.undeclaredParameter : undefined;
    if (undeclared !== undefined) {
      const suggestion = closestMatch(undeclared, names);
      return {
        source: analysis.ref,
        range,
        ...unknownDistributionParameterWording(severity, problem.message, suggestion),
        ...(suggestion ? { data: { suggestion } } : {}),
      };
    }
    const inScenario = own ? undefined : { file: path.basename(problem.file), line: scenarioLine(analysis, problem) };
    return { source: analysis.ref, range, ...distributionWording(severity, problem.message, inScenario) };
  });
}

function scenarioLine(analysis: DistributionRead, problem: VariationProblem): number {
  const lines = analysis.loaded.lines.get(problem.file);
  return lines ? lines.positionAt(problem.offset).line + 1 : 1;
}

function scenarioFileAttributeOffset(text: string): number {
  const found = /<ScenarioFile\b[^>]*?\bfilepath\s*=\s*["']/.exec(text);
  return found ? found.index + found[0].length : Math.max(0, text.search(DISTRIBUTION_ELEMENT));
}

/** A range whose step is wider than the range itself gives its lower limit alone: likely not what was meant. */
function rangeWarnings(analysis: DistributionRead): VariationProblem[] {
  const warnings: VariationProblem[] = [];
  for (const factor of analysis.loaded.variations?.distribution.deterministic ?? []) {
    if (factor.kind !== 'range') continue;
    const { lower, upper, offset } = factor.range;
    if (upper > lower && factor.step > upper - lower) {
      warnings.push({
        file: analysis.file,
        offset,
        severity: 'warning',
        message: `stepWidth ${factor.step} is wider than the range ${lower}..${upper}: only ${lower} is used`,
      });
    }
  }
  return warnings;
}
