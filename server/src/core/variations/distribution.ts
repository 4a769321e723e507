import { attribute, parseXml, XmlElement } from '../xml';
import { LineIndex } from '../text';

/** A problem in a distribution or scenario file, at an offset of its text. */
export interface VariationProblem {
  file: string;
  offset: number;
  message: string;
  severity: 'error' | 'warning';
  /** Set when the problem is a parameterName the ScenarioFile does not declare at its root: that name. */
  undeclaredParameter?: string;
}

/** A place in a file's text, kept so that later checks (unknown parameter, impossible range) can point at it. */
export interface Located {
  offset: number;
}

export interface ParameterValue extends Located {
  parameter: string;
  value: string;
  /** Where the value is written, when the file writes it (a DistributionSet's Element, a ParameterAssignment); `offset` is where the parameter is named. */
  valueOffset?: number;
}

export interface NumericRange extends Located {
  lower: number;
  upper: number;
}

/** One factor of the deterministic product: each alternative assigns one or more parameters. */
export type DeterministicDistribution =
  | { kind: 'set'; parameter: string; offset: number; values: ParameterValue[] }
  | { kind: 'range'; parameter: string; offset: number; step: number; range: NumericRange }
  | { kind: 'userDefined'; parameter: string; offset: number; type: string; values: ParameterValue[] }
  | { kind: 'multi'; offset: number; sets: ParameterValue[][] };

export type StochasticSampler =
  | { kind: 'normal'; mean: number; variance: number }
  | { kind: 'logNormal'; mean: number; variance: number }
  | { kind: 'uniform' }
  | { kind: 'poisson'; mean: number }
  | { kind: 'histogram'; bins: { weight: number; range: NumericRange }[] }
  | { kind: 'probabilitySet'; elements: { value: string; weight: number }[] }
  | { kind: 'userDefined'; type: string; values: string[] };

export interface StochasticDistribution extends Located {
  parameter: string;
  sampler: StochasticSampler;
  /** Values outside are drawn again (required for `uniform`). */
  range: NumericRange | undefined;
}

export interface DistributionFile {
  file: string;
  text: string;
  lines: LineIndex;
  /** `ScenarioFile/@filepath` as written, and its offset. */
  scenarioFile: { path: string; offset: number };
  deterministic: DeterministicDistribution[] | undefined;
  stochastic: { runs: number; seed: number; distributions: StochasticDistribution[]; offset: number } | undefined;
}

/** `UserDefinedDistribution` content this tool understands: `type="list"`, values separated by white space. */
export const USER_DEFINED_LIST_TYPE = 'list';

const DECIMAL = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;

/** Parses a ParameterValueDistribution file; problems name offsets of `text`. Never throws on bad input. */
export function parseDistribution(
  text: string,
  file: string,
): { distribution: DistributionFile | undefined; problems: VariationProblem[] } {
  const problems: VariationProblem[] = [];
  const problem = (offset: number, message: string, severity: 'error' | 'warning' = 'error'): void => {
    problems.push({ file, offset, message, severity });
  };
  const document = parseXml(text);
  for (const xmlProblem of document.problems) if (xmlProblem.severity === 'error') problem(xmlProblem.start, xmlProblem.message);
  const root = document.root;
  if (!root) {
    if (problems.length === 0) problem(0, 'no root element');
    return { distribution: undefined, problems };
  }
  if (root.name !== 'OpenSCENARIO') problem(root.start, `the root element is <${root.name}>, not <OpenSCENARIO>`);
  const element = child(root, 'ParameterValueDistribution');
  if (!element) {
    problem(root.start, 'no <ParameterValueDistribution>: this is not a distribution file');
    return { distribution: undefined, problems };
  }

  const required = (owner: XmlElement, name: string): { value: string; offset: number } | undefined => {
    const found = attribute(owner, name);
    if (!found) {
      problem(owner.start, `<${owner.name}> needs the attribute ${name}`);
      return undefined;
    }
    return { value: found.value, offset: found.valueStart };
  };
  // esmini finds a root parameter by its name with or without a leading `$` (Parameters.cpp getParameterEntry), and a
  // widely used generator writes parameterName="$speed": the name without it, with a warning (SPEC 12).
  const parameterName = (owner: XmlElement, name: string): { value: string; offset: number } | undefined => {
    const found = required(owner, name);
    if (!found || !found.value.trimStart().startsWith('$')) return found;
    const bare = found.value.trim().slice(1);
    problem(
      found.offset,
      `the standard names a parameter without '$' ('${bare}'); esmini reads ${name}="${found.value}" as '${bare}', and so does this tool`,
      'warning',
    );
    return { value: bare, offset: found.offset };
  };
  const number = (owner: XmlElement, name: string): number | undefined => {
    const found = required(owner, name);
    if (!found) return undefined;
    const trimmed = found.value.trim();
    if (trimmed.startsWith('$')) {
      problem(found.offset, `${name}="${found.value}": parameter references are not resolved in distribution files; write the number`);
      return undefined;
    }
    if (!DECIMAL.test(trimmed) || !Number.isFinite(Number(trimmed))) {
      problem(found.offset, `${name}="${found.value}" is not a number`);
      return undefined;
    }
    return Number(trimmed);
  };
  const range = (owner: XmlElement, needed: boolean): NumericRange | undefined => {
    const rangeElement = child(owner, 'Range');
    if (!rangeElement) {
      if (needed) problem(owner.start, `<${owner.name}> needs a <Range lowerLimit=".." upperLimit="..">`);
      return undefined;
    }
    const lower = number(rangeElement, 'lowerLimit');
    const upper = number(rangeElement, 'upperLimit');
    if (lower === undefined || upper === undefined) return undefined;
    if (upper < lower) {
      problem(rangeElement.start, `the range is empty: upperLimit ${upper} is below lowerLimit ${lower}`);
      return undefined;
    }
    return { lower, upper, offset: rangeElement.start };
  };
  const userDefinedValues = (owner: XmlElement): { type: string; values: string[] } | undefined => {
    const type = required(owner, 'type');
    if (!type) return undefined;
    if (type.value.trim().toLowerCase() !== USER_DEFINED_LIST_TYPE) {
      problem(
        type.offset,
        `UserDefinedDistribution type="${type.value}" is not understood; type="${USER_DEFINED_LIST_TYPE}" takes values separated by white space`,
      );
      return undefined;
    }
    const content = decodeText(text.slice(owner.startTagEnd, Math.max(owner.startTagEnd, owner.end - `</${owner.name}>`.length)));
    const values = owner.selfClosing ? [] : content.split(/\s+/).filter((value) => value.length > 0);
    if (values.length === 0) {
      problem(owner.start, 'the UserDefinedDistribution lists no values');
      return undefined;
    }
    return { type: type.value, values };
  };

  const scenarioElement = child(element, 'ScenarioFile');
  let scenarioFile = { path: '', offset: element.start };
  if (!scenarioElement) problem(element.start, '<ParameterValueDistribution> needs a <ScenarioFile filepath="...">');
  else {
    const filepath = required(scenarioElement, 'filepath');
    if (filepath && filepath.value.trim() === '') problem(filepath.offset, 'ScenarioFile filepath is empty');
    else if (filepath) scenarioFile = { path: filepath.value, offset: filepath.offset };
  }

  let deterministic: DeterministicDistribution[] | undefined;
  let stochastic: DistributionFile['stochastic'];
  const deterministicElement = child(element, 'Deterministic');
  const stochasticElement = child(element, 'Stochastic');
  if (deterministicElement && stochasticElement)
    problem(stochasticElement.start, 'a distribution is either <Deterministic> or <Stochastic>, not both');
  if (!deterministicElement && !stochasticElement) problem(element.start, 'no <Deterministic> or <Stochastic> distribution');

  if (deterministicElement) {
    deterministic = [];
    for (const item of deterministicElement.children) {
      if (item.name === 'DeterministicMultiParameterDistribution') {
        const valueSets = child(item, 'ValueSetDistribution');
        if (!valueSets) {
          problem(item.start, '<DeterministicMultiParameterDistribution> needs a <ValueSetDistribution>');
          continue;
        }
        const sets: ParameterValue[][] = [];
        for (const set of valueSets.children.filter((c) => c.name === 'ParameterValueSet')) {
          const assignments: ParameterValue[] = [];
          for (const assignment of set.children.filter((c) => c.name === 'ParameterAssignment')) {
            const parameter = parameterName(assignment, 'parameterRef');
            const value = required(assignment, 'value');
            if (parameter && value)
              assignments.push({ parameter: parameter.value, value: value.value, offset: parameter.offset, valueOffset: value.offset });
          }
          if (assignments.length === 0) problem(set.start, 'this ParameterValueSet assigns no parameter');
          sets.push(assignments);
        }
        if (sets.length === 0) problem(valueSets.start, 'the ValueSetDistribution has no ParameterValueSet');
        deterministic.push({ kind: 'multi', offset: item.start, sets });
      } else if (item.name === 'DeterministicSingleParameterDistribution') {
        const parameter = parameterName(item, 'parameterName');
        const definition = item.children[0];
        if (!parameter) continue;
        if (!definition) {
          problem(item.start, 'the distribution is missing: <DistributionSet>, <DistributionRange> or <UserDefinedDistribution>');
          continue;
        }
        if (definition.name === 'DistributionSet') {
          const values: ParameterValue[] = [];
          for (const element of definition.children.filter((c) => c.name === 'Element')) {
            const value = required(element, 'value');
            if (value) values.push({ parameter: parameter.value, value: value.value, offset: parameter.offset, valueOffset: value.offset });
          }
          if (values.length === 0) problem(definition.start, 'the DistributionSet has no Element');
          deterministic.push({ kind: 'set', parameter: parameter.value, offset: parameter.offset, values });
        } else if (definition.name === 'DistributionRange') {
          const step = number(definition, 'stepWidth');
          const stepOffset = attribute(definition, 'stepWidth')?.valueStart ?? definition.start;
          const limits = range(definition, true);
          if (step !== undefined && !(step > 0)) problem(stepOffset, `stepWidth ${step} must be greater than 0`);
          else if (step !== undefined && limits)
            deterministic.push({ kind: 'range', parameter: parameter.value, offset: parameter.offset, step, range: limits });
        } else if (definition.name === 'UserDefinedDistribution') {
          const listed = userDefinedValues(definition);
          if (listed) {
            const values = listed.values.map((value) => ({ parameter: parameter.value, value, offset: parameter.offset }));
            deterministic.push({ kind: 'userDefined', parameter: parameter.value, offset: parameter.offset, type: listed.type, values });
          }
        } else problem(definition.start, `unexpected <${definition.name}> in a DeterministicSingleParameterDistribution`);
      } else problem(item.start, `unexpected <${item.name}> in <Deterministic>`);
    }
  }

  if (stochasticElement) {
    const runs = number(stochasticElement, 'numberOfTestRuns');
    const runsOffset = attribute(stochasticElement, 'numberOfTestRuns')?.valueStart ?? stochasticElement.start;
    if (runs !== undefined && !(Number.isSafeInteger(runs) && runs >= 0))
      problem(runsOffset, `numberOfTestRuns ${runs} is not a whole number of runs`);
    const seed = attribute(stochasticElement, 'randomSeed') ? number(stochasticElement, 'randomSeed') : 0;
    const distributions: StochasticDistribution[] = [];
    for (const item of stochasticElement.children) {
      if (item.name !== 'StochasticDistribution') {
        problem(item.start, `unexpected <${item.name}> in <Stochastic>`);
        continue;
      }
      const parameter = parameterName(item, 'parameterName');
      const definition = item.children[0];
      if (!parameter) continue;
      if (!definition) {
        problem(item.start, 'the StochasticDistribution has no distribution');
        continue;
      }
      const before = problems.length;
      let sampler: StochasticSampler | undefined;
      let limits: NumericRange | undefined;
      switch (definition.name) {
        case 'NormalDistribution':
        case 'LogNormalDistribution': {
          const mean = number(definition, 'expectedValue');
          const variance = number(definition, 'variance');
          limits = range(definition, false);
          if (variance !== undefined && variance < 0)
            problem(attribute(definition, 'variance')?.valueStart ?? definition.start, `variance ${variance} is negative`);
          if (definition.name === 'LogNormalDistribution' && mean !== undefined && !(mean > 0))
            problem(
              attribute(definition, 'expectedValue')?.valueStart ?? definition.start,
              `a log-normal distribution's expectedValue must be greater than 0, not ${mean}`,
            );
          if (mean !== undefined && variance !== undefined)
            sampler = { kind: definition.name === 'NormalDistribution' ? 'normal' : 'logNormal', mean, variance };
          break;
        }
        case 'UniformDistribution':
          limits = range(definition, true);
          sampler = { kind: 'uniform' };
          break;
        case 'PoissonDistribution': {
          const mean = number(definition, 'expectedValue');
          limits = range(definition, false);
          if (mean !== undefined && !(mean >= 0))
            problem(
              attribute(definition, 'expectedValue')?.valueStart ?? definition.start,
              `a Poisson distribution's expectedValue must not be negative, not ${mean}`,
            );
          if (mean !== undefined) sampler = { kind: 'poisson', mean };
          break;
        }
        case 'Histogram': {
          const bins: { weight: number; range: NumericRange }[] = [];
          for (const bin of definition.children.filter((c) => c.name === 'Bin')) {
            const weight = number(bin, 'weight');
            const binRange = range(bin, true);
            if (weight !== undefined && weight < 0)
              problem(attribute(bin, 'weight')?.valueStart ?? bin.start, `weight ${weight} is negative`);
            if (weight !== undefined && binRange) bins.push({ weight, range: binRange });
          }
          if (bins.length > 0 && bins.every((bin) => bin.weight === 0)) problem(definition.start, 'every Bin has weight 0');
          if (definition.children.every((c) => c.name !== 'Bin')) problem(definition.start, 'the Histogram has no Bin');
          sampler = { kind: 'histogram', bins };
          break;
        }
        case 'ProbabilityDistributionSet': {
          const elements: { value: string; weight: number }[] = [];
          for (const element of definition.children.filter((c) => c.name === 'Element')) {
            const value = required(element, 'value');
            const weight = number(element, 'weight');
            if (weight !== undefined && weight < 0)
              problem(attribute(element, 'weight')?.valueStart ?? element.start, `weight ${weight} is negative`);
            if (value && weight !== undefined) elements.push({ value: value.value, weight });
          }
          if (elements.length === 0) problem(definition.start, 'the ProbabilityDistributionSet has no Element');
          else if (elements.every((element) => element.weight === 0)) problem(definition.start, 'every Element has weight 0');
          sampler = { kind: 'probabilitySet', elements };
          break;
        }
        case 'UserDefinedDistribution': {
          const listed = userDefinedValues(definition);
          if (listed) sampler = { kind: 'userDefined', type: listed.type, values: listed.values };
          break;
        }
        default:
          problem(definition.start, `unexpected <${definition.name}> in a StochasticDistribution`);
      }
      if (sampler && problems.length === before)
        distributions.push({ parameter: parameter.value, offset: parameter.offset, sampler, range: limits });
    }
    if (runs !== undefined && seed !== undefined) stochastic = { runs, seed, distributions, offset: stochasticElement.start };
  }

  const distribution: DistributionFile = { file, text, lines: document.lines, scenarioFile, deterministic, stochastic };
  return { distribution, problems };
}

function child(element: XmlElement, name: string): XmlElement | undefined {
  return element.children.find((candidate) => candidate.name === name);
}

/** Character content with the predefined entities and character references decoded (comments and CDATA are not expected here). */
function decodeText(raw: string): string {
  const named: Record<string, string> = { lt: '<', gt: '>', amp: '&', quot: '"', apos: "'" };
  return raw.replace(/&(#x[0-9a-fA-F]+|#\d+|lt|gt|amp|quot|apos);/g, (_whole, reference: string) => {
    if (reference.startsWith('#x')) return String.fromCodePoint(parseInt(reference.slice(2), 16));
    if (reference.startsWith('#')) return String.fromCodePoint(parseInt(reference.slice(1), 10));
    return named[reference];
  });
}

/** `file:line:col: severity: message`, 1-based, as compilers print. */
export function formatVariationProblem(problem: VariationProblem, lines: LineIndex | undefined, displayFile = problem.file): string {
  const position = lines ? lines.positionAt(problem.offset) : { line: 0, character: 0 };
  return `${displayFile}:${position.line + 1}:${position.character + 1}: ${problem.severity}: ${problem.message}`;
}
