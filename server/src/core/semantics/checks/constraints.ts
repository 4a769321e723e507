import { attribute, XmlElement } from '../../xml';
import { assignmentsOf } from '../catalogs';
import type { Finding, SemanticCheck, SemanticContext } from './types';
import { convertValue, formatValue, Mismatch, ParameterType, ParameterValue } from '../values';
import { Declaration, Evaluator, referencedName } from '../model';
import { at, relatedAt } from './support';
import { brokenConstraintNote, ConstraintFacts, valueConstraintWording } from '../../diagnostics/valueConstraint';

/*
 * A ParameterDeclaration's `ConstraintGroup`s (1.1 and later, `ValueConstraintGroup`): the value is valid
 * when at least one group holds, and a group holds when all its `ValueConstraint`s do. Each constraint
 * compares the value (left) with the constraint's value (right), converted to the parameter's type;
 * booleans and strings know only equalTo and notEqualTo. The value is the standard's in every reading: esmini 3.6
 * reads no ConstraintGroup (none of its sources names one), so its reading of a value (an unsignedInt kept as
 * text, 'wrongDouble' read as 0) has no constraint to break.
 */

const RULES = ['equalTo', 'notEqualTo', 'lessThan', 'lessOrEqual', 'greaterThan', 'greaterOrEqual'] as const;
type ConstraintRule = (typeof RULES)[number];

const EQUALITY_ONLY: ReadonlySet<ParameterType> = new Set<ParameterType>(['boolean', 'string']);

interface Constraint {
  element: XmlElement;
  rule: ConstraintRule;
  /** The constraint's value in the parameter's type; why not when it has none. */
  value: ParameterValue | Mismatch;
}

function isRule(text: string): text is ConstraintRule {
  return (RULES as readonly string[]).includes(text);
}

/** dateTime values compare as instants; an unzoned one is read as UTC (both sides the same way). */
function comparable(value: ParameterValue, type: ParameterType): number | string | boolean {
  if (type === 'dateTime' && typeof value === 'string') {
    const time = Date.parse(/[zZ]|[+-]\d\d:\d\d$/.test(value) ? value : `${value}Z`);
    return Number.isNaN(time) ? value : time;
  }
  return value;
}

function holds(rule: ConstraintRule, left: number | string | boolean, right: number | string | boolean): boolean {
  switch (rule) {
    case 'equalTo':
      return left === right;
    case 'notEqualTo':
      return left !== right;
    case 'lessThan':
      return left < right;
    case 'lessOrEqual':
      return left <= right;
    case 'greaterThan':
      return left > right;
    case 'greaterOrEqual':
      return left >= right;
  }
}

/** The constraint groups of a declaration, each constraint read (a rule or value that cannot be read is reported). */
function groupsOf(context: SemanticContext, declaration: Declaration, type: ParameterType, findings: Finding[]): Constraint[][] {
  const groups: Constraint[][] = [];
  for (const group of declaration.element.children) {
    if (group.name !== 'ConstraintGroup') continue;
    const constraints: Constraint[] = [];
    for (const element of group.children) {
      if (element.name !== 'ValueConstraint') continue;
      const ruleAttribute = attribute(element, 'rule');
      const valueAttribute = attribute(element, 'value');
      const ruleText = context.evaluator.textOf(element, ruleAttribute);
      const valueText = context.evaluator.textOf(element, valueAttribute);
      // A missing or misspelt rule is a schema problem, reported there.
      if (ruleText === undefined || valueText === undefined || !isRule(ruleText)) continue;
      if (EQUALITY_ONLY.has(type) && ruleText !== 'equalTo' && ruleText !== 'notEqualTo') {
        findings.push({
          ...at(element, ruleAttribute),
          ...valueConstraintWording({ kind: 'rule', rule: ruleText, type, parameter: declaration.name }),
        });
        continue;
      }
      const converted = convertValue({ value: valueText, type: 'string' }, type);
      if ('mismatch' in converted) {
        findings.push({
          ...at(element, valueAttribute),
          ...valueConstraintWording({ kind: 'value', value: valueText, type, parameter: declaration.name, reason: converted.mismatch }),
        });
      }
      constraints.push({ element, rule: ruleText, value: 'mismatch' in converted ? converted : converted.value });
    }
    if (constraints.length > 0) groups.push(constraints);
  }
  return groups;
}

/** The constraints the value breaks, for the message; undefined when one group holds (or no group can be read). */
function brokenConstraints(groups: Constraint[][], value: ParameterValue, type: ParameterType): Constraint[][] | undefined {
  const readable = groups.filter((group) => group.every((constraint) => typeof constraint.value !== 'object'));
  if (readable.length === 0) return undefined;
  const left = comparable(value, type);
  const broken = readable.map((group) =>
    group.filter((constraint) => !holds(constraint.rule, left, comparable(constraint.value as ParameterValue, type))),
  );
  return broken.some((group) => group.length === 0) ? undefined : broken;
}

/** A readable constraint as its diagnostic's wording takes it. */
function factsOf(constraint: Constraint): ConstraintFacts {
  return { rule: constraint.rule, value: formatValue(constraint.value as ParameterValue) };
}

function brokenFacts(broken: Constraint[][]): ConstraintFacts[][] {
  return broken.map((group) => group.map(factsOf));
}

/**
 * Every parameter value against its declaration's ConstraintGroups: the declared value at the
 * declaration, and a value a CatalogReference assigns to an entry's parameter at the assignment.
 */
export const valueConstraints: SemanticCheck = (context) => {
  const findings: Finding[] = [];
  const groupsByDeclaration = new Map<Declaration, Constraint[][]>();
  const groupsOfDeclaration = (declaration: Declaration, type: ParameterType, report: boolean): Constraint[][] => {
    let groups = groupsByDeclaration.get(declaration);
    if (!groups) {
      groups = groupsOf(context, declaration, type, report ? findings : []);
      groupsByDeclaration.set(declaration, groups);
    }
    return groups;
  };
  for (const declaration of context.model.declarations) {
    if (declaration.kind !== 'parameter' || declaration.type === undefined) continue;
    if (!declaration.element.children.some((child) => child.name === 'ConstraintGroup')) continue;
    const groups = groupsOfDeclaration(declaration, declaration.type, true);
    const result = context.evaluator.standardDeclarationValue(declaration);
    if (!result.ok) continue;
    const broken = brokenConstraints(groups, result.value, declaration.type);
    if (!broken) continue;
    findings.push({
      ...at(declaration.element, declaration.valueAttribute),
      ...valueConstraintWording({
        kind: 'broken',
        value: formatValue(result.value),
        parameter: declaration.name,
        broken: brokenFacts(broken),
      }),
      related: broken
        .flat()
        .map((constraint) =>
          relatedAt(context, constraint.element.start, constraint.element.nameEnd, brokenConstraintNote(factsOf(constraint))),
        ),
    });
  }
  for (const resolution of context.catalogs.references) {
    const entry = resolution.entry;
    if (!entry) continue;
    const entryModel = entry.file.model;
    const scope = entryModel.scopeOf(entry.element);
    if (!scope || scope.element !== entry.element) continue;
    const constrained = scope.declarations.filter(
      (declaration) => declaration.type !== undefined && declaration.element.children.some((child) => child.name === 'ConstraintGroup'),
    );
    if (constrained.length === 0) continue;
    const entryEvaluator = new Evaluator(entryModel, assignmentsOf(resolution.reference, context.evaluator), context.evaluator.reading);
    for (const assignment of resolution.reference.assignments) {
      const name = assignment.parameterRef ? referencedName(assignment.parameterRef).name : undefined;
      const declaration = constrained.find((candidate) => candidate.name === name);
      if (!declaration || !declaration.type || !assignment.valueAttribute) continue;
      const result = entryEvaluator.standardDeclarationValue(declaration);
      if (!result.ok) continue;
      // The entry's own file reports what cannot be read in its constraints.
      const broken = brokenConstraints(groupsOf(context, declaration, declaration.type, []), result.value, declaration.type);
      if (!broken) continue;
      findings.push({
        ...at(assignment.element, assignment.valueAttribute),
        ...valueConstraintWording({
          kind: 'broken',
          value: formatValue(result.value),
          parameter: declaration.name,
          entry: entry.name,
          broken: brokenFacts(broken),
        }),
      });
    }
  }
  return findings;
};
