import * as path from 'node:path';
import { LineIndex } from '../text';
import {
  assignedValueMismatch,
  brokenConstraint,
  concreteScenarioText,
  hasConstraints,
  readScenarioParameters,
  ScenarioParameters,
  undeclaredParameters,
} from './concrete';
import { assignmentAt, DeterministicExpansion, expandDeterministic } from './deterministic';
import { DistributionFile, formatVariationProblem, ParameterValue, parseDistribution, VariationProblem } from './distribution';
import { SamplingError, stochasticAssignment } from './stochastic';

export { formatVariationProblem } from './distribution';
export type { VariationProblem } from './distribution';

/**
 * Turns the ScenarioFile's absolute path into the plain scenario text the values are spliced into. The hook
 * for modular mains and `.mosc` files: the flattener plugs in here; by default the file is read as it is.
 */
export type ScenarioTextLoader = (scenarioPath: string) => Promise<string>;

export type ConcreteScenario =
  | { index: bigint; assignments: ParameterValue[]; text: string }
  | { index: bigint; assignments: ParameterValue[]; broken: { parameter: string; value: string } };

export interface Variations {
  distribution: DistributionFile;
  scenarioPath: string;
  scenario: ScenarioParameters;
  kind: 'deterministic' | 'stochastic';
  /** Combinations before ValueConstraintGroups are applied: esmini's number of permutations (or numberOfTestRuns). */
  count: bigint;
  constrained: boolean;
  /** The assignments of index I (esmini's --param_permutation I). Throws SamplingError when a Range cannot be met. */
  assignmentAt(index: bigint): ParameterValue[];
  /** The concrete scenario I, or why ValueConstraintGroups discard it. */
  concreteAt(index: bigint): ConcreteScenario;
  /** The parameter whose value in combination I breaks its ValueConstraintGroups, without writing the text. */
  brokenAt(index: bigint): { parameter: string; value: string } | undefined;
}

export interface LoadResult {
  variations: Variations | undefined;
  problems: VariationProblem[];
  /** Line tables of the files the problems name, to print file:line:col. */
  lines: Map<string, LineIndex>;
}

/** Reads a distribution and its scenario and checks every parameter it names; problems rather than throws for bad input. */
export async function loadVariations(
  distributionText: string,
  distributionPath: string,
  loadScenarioText: ScenarioTextLoader,
): Promise<LoadResult> {
  const lines = new Map<string, LineIndex>();
  const { distribution, problems } = parseDistribution(distributionText, distributionPath);
  lines.set(distributionPath, distribution?.lines ?? new LineIndex(distributionText));
  if (!distribution || problems.some((p) => p.severity === 'error') || !distribution.scenarioFile.path)
    return { variations: undefined, problems, lines };

  const scenarioPath = path.resolve(path.dirname(distributionPath), distribution.scenarioFile.path);
  let scenarioText: string;
  try {
    scenarioText = await loadScenarioText(scenarioPath);
  } catch (error) {
    const reason = (error as NodeJS.ErrnoException).code === 'ENOENT' ? 'no such file' : (error as Error).message;
    problems.push({
      file: distributionPath,
      offset: distribution.scenarioFile.offset,
      severity: 'error',
      message: `ScenarioFile ${distribution.scenarioFile.path} (${scenarioPath}): ${reason}`,
    });
    return { variations: undefined, problems, lines };
  }
  const read = readScenarioParameters(scenarioText, scenarioPath);
  problems.push(...read.problems);
  lines.set(scenarioPath, read.scenario?.lines ?? new LineIndex(scenarioText));
  const scenario = read.scenario;
  if (!scenario || problems.some((p) => p.severity === 'error')) return { variations: undefined, problems, lines };

  let expansion: DeterministicExpansion | undefined;
  let named: ParameterValue[];
  if (distribution.deterministic) {
    const expanded = expandDeterministic(distribution.deterministic, distributionPath);
    problems.push(...expanded.problems);
    expansion = expanded.expansion;
    named = expansion.factors.flat(2);
    if (expansion.factors.length === 0)
      problems.push({
        file: distributionPath,
        offset: distribution.scenarioFile.offset,
        severity: 'error',
        message: 'the <Deterministic> element has no distribution: there is nothing to vary',
      });
  } else {
    const stochastic = distribution.stochastic;
    named = stochastic ? stochastic.distributions.map((d) => ({ parameter: d.parameter, value: '', offset: d.offset })) : [];
    if (stochastic && stochastic.distributions.length === 0)
      problems.push({
        file: distributionPath,
        offset: stochastic.offset,
        severity: 'error',
        message: 'the <Stochastic> element has no StochasticDistribution',
      });
  }
  const reported = new Set<string>();
  for (const missing of undeclaredParameters(scenario, named)) {
    if (reported.has(`${missing.parameter}@${missing.offset}`)) continue;
    reported.add(`${missing.parameter}@${missing.offset}`);
    problems.push({
      file: distributionPath,
      offset: missing.offset,
      severity: 'error',
      message: `parameter '${missing.parameter}' is not declared in the root ParameterDeclarations of ${distribution.scenarioFile.path}`,
      undeclaredParameter: missing.parameter,
    });
  }
  if (problems.some((p) => p.severity === 'error')) return { variations: undefined, problems, lines };
  problems.push(...typeWarnings(scenario, expansion ? named : [], distribution, distributionPath));

  const stochastic = distribution.stochastic;
  const assignments = expansion
    ? (index: bigint): ParameterValue[] => assignmentAt(expansion, index)
    : (index: bigint): ParameterValue[] => {
        if (!stochastic || index < 0n || index >= BigInt(stochastic.runs))
          throw new RangeError(`index ${index} is outside 0..${(stochastic ? BigInt(stochastic.runs) : 0n) - 1n}`);
        return stochasticAssignment(stochastic.distributions, stochastic.seed, Number(index));
      };
  const variations: Variations = {
    distribution,
    scenarioPath,
    scenario,
    kind: expansion ? 'deterministic' : 'stochastic',
    count: expansion ? expansion.count : BigInt(stochastic?.runs ?? 0),
    constrained: hasConstraints(scenario),
    assignmentAt: assignments,
    concreteAt(index: bigint): ConcreteScenario {
      const assigned = assignments(index);
      const broken = brokenConstraint(scenario, assigned);
      if (broken) return { index, assignments: assigned, broken };
      return { index, assignments: assigned, text: concreteScenarioText(scenario, assigned) };
    },
    brokenAt(index: bigint): { parameter: string; value: string } | undefined {
      return brokenConstraint(scenario, assignments(index));
    },
  };
  return { variations, problems, lines };
}

const CONTINUOUS_SAMPLERS = new Set(['normal', 'logNormal', 'uniform', 'histogram']);

/** Values that do not fit the type of the parameter they go to: warned, since esmini takes them as they are. */
function typeWarnings(
  scenario: ScenarioParameters,
  deterministicValues: ParameterValue[],
  distribution: DistributionFile,
  file: string,
): VariationProblem[] {
  const types = new Map<string, string>();
  for (const declaration of scenario.declarations) if (!types.has(declaration.name)) types.set(declaration.name, declaration.type);
  const warnings: VariationProblem[] = [];
  const reported = new Set<string>();
  for (const assignment of deterministicValues) {
    const type = types.get(assignment.parameter) ?? 'string';
    const mismatch = assignedValueMismatch(scenario, assignment, type);
    if (!mismatch || reported.has(assignment.parameter)) continue;
    reported.add(assignment.parameter);
    warnings.push({
      file,
      offset: assignment.valueOffset ?? assignment.offset,
      severity: 'warning',
      message: `the value '${assignment.value}' for ${type} parameter '${assignment.parameter}' ${mismatch}`,
    });
  }
  for (const stochastic of distribution.stochastic?.distributions ?? []) {
    const type = types.get(stochastic.parameter) ?? 'string';
    const kind = stochastic.sampler.kind;
    if (
      (type === 'boolean' && kind !== 'probabilitySet' && kind !== 'userDefined') ||
      (['int', 'integer', 'unsignedInt', 'unsignedShort'].includes(type) && CONTINUOUS_SAMPLERS.has(kind))
    ) {
      warnings.push({
        file,
        offset: stochastic.offset,
        severity: 'warning',
        message: `${type} parameter '${stochastic.parameter}' gets values drawn from a ${kind} distribution, which are not ${type === 'boolean' ? 'true or false' : 'whole numbers'}`,
      });
    }
  }
  return warnings;
}

/** A sampling failure as a problem at the distribution's Range. */
export function samplingProblem(error: SamplingError, distributionPath: string): VariationProblem {
  return { file: distributionPath, offset: error.offset, severity: 'error', message: error.message };
}

/** Prints problems as file:line:col, with file names relative to `base` when given. */
export function formatVariationProblems(problems: VariationProblem[], lines: Map<string, LineIndex>, base?: string): string[] {
  return problems.map((problem) =>
    formatVariationProblem(problem, lines.get(problem.file), base ? path.relative(base, problem.file) || problem.file : problem.file),
  );
}

export { SamplingError } from './stochastic';
export { rebasedConcreteText } from './concrete';
