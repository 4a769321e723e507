import * as path from 'node:path';
import { attribute, descendants, escapeAttributeValue, parseXml, XmlAttribute, XmlDocument } from '../xml';
import { applyEdits, TextEdit } from '../flatten/edits';
import { rebasePaths, ResolvedPath, written } from '../flatten/rebase';
import { catalogFoundThroughSearchPathMessage } from '../diagnostics/filePath';
import type { FileKind } from '../sources/host';
import { LineIndex } from '../text';
import { ParameterValue, VariationProblem } from './distribution';
import { valueForm } from '../semantics/expressionParser';
import { evaluateTree, LookupResult } from '../semantics/expressionEvaluation';
import { normalizeParameterType, readStringAsValue } from '../semantics/values';

export type ConstraintRule = 'equalTo' | 'greaterThan' | 'lessThan' | 'greaterOrEqual' | 'lessOrEqual' | 'notEqualTo';

export interface ValueConstraint {
  rule: ConstraintRule;
  value: string;
}

/** A root ParameterDeclaration of the scenario, with where its value is written. */
export interface DeclaredParameter {
  name: string;
  type: string;
  value: string;
  valueAttribute: XmlAttribute;
  offset: number;
  /** The value must meet every constraint of at least one group (none: any value). */
  constraintGroups: ValueConstraint[][];
}

export interface ScenarioParameters {
  text: string;
  lines: LineIndex;
  /** In document order; esmini assigns to the first declaration of a name. */
  declarations: DeclaredParameter[];
}

const RULES = new Set<string>(['equalTo', 'greaterThan', 'lessThan', 'greaterOrEqual', 'lessOrEqual', 'notEqualTo']);
const NUMERIC_TYPES = new Set(['double', 'int', 'integer', 'unsignedInt', 'unsignedShort']);

/** The scenario's root parameter declarations (`OpenSCENARIO/ParameterDeclarations`, where esmini assigns). */
export function readScenarioParameters(
  text: string,
  file: string,
): { scenario: ScenarioParameters | undefined; problems: VariationProblem[] } {
  const problems: VariationProblem[] = [];
  const document = parseXml(text);
  for (const xmlProblem of document.problems)
    if (xmlProblem.severity === 'error') problems.push({ file, offset: xmlProblem.start, message: xmlProblem.message, severity: 'error' });
  const root = document.root;
  if (!root || problems.length > 0) {
    if (!root && problems.length === 0) problems.push({ file, offset: 0, message: 'no root element', severity: 'error' });
    return { scenario: undefined, problems };
  }
  if (root.children.some((c) => c.name === 'ParameterValueDistribution'))
    problems.push({
      file,
      offset: root.start,
      message: 'the ScenarioFile is itself a distribution file, not a scenario',
      severity: 'error',
    });
  const declarations: DeclaredParameter[] = [];
  const list = root.name === 'OpenSCENARIO' ? root.children.find((c) => c.name === 'ParameterDeclarations') : undefined;
  for (const declaration of list?.children.filter((c) => c.name === 'ParameterDeclaration') ?? []) {
    const name = attribute(declaration, 'name');
    const valueAttribute = attribute(declaration, 'value');
    if (!name || !valueAttribute) continue;
    const constraintGroups: ValueConstraint[][] = [];
    for (const group of declaration.children.filter((c) => c.name === 'ConstraintGroup')) {
      const constraints: ValueConstraint[] = [];
      for (const constraint of group.children.filter((c) => c.name === 'ValueConstraint')) {
        const rule = attribute(constraint, 'rule');
        const value = attribute(constraint, 'value');
        if (!rule || !value || !RULES.has(rule.value)) {
          problems.push({
            file,
            offset: constraint.start,
            message: `a ValueConstraint needs rule (${[...RULES].join(', ')}) and value`,
            severity: 'error',
          });
          continue;
        }
        constraints.push({ rule: rule.value as ConstraintRule, value: value.value });
      }
      constraintGroups.push(constraints);
    }
    declarations.push({
      name: name.value,
      type: attribute(declaration, 'parameterType')?.value ?? 'string',
      value: valueAttribute.value,
      valueAttribute,
      offset: declaration.start,
      constraintGroups,
    });
  }
  return { scenario: { text, lines: document.lines, declarations }, problems };
}

/** Assignments naming a parameter the scenario does not declare at its root (esmini stops on them). */
export function undeclaredParameters(scenario: ScenarioParameters, assignments: ParameterValue[]): ParameterValue[] {
  const names = new Set(scenario.declarations.map((d) => d.name));
  return assignments.filter((assignment) => !names.has(assignment.parameter));
}

/** The final value of each declared parameter after the assignments (a later assignment of a name wins). */
export function valuesAfter(scenario: ScenarioParameters, assignments: ParameterValue[]): Map<string, string> {
  const values = new Map<string, string>();
  for (const declaration of scenario.declarations) if (!values.has(declaration.name)) values.set(declaration.name, declaration.value);
  for (const assignment of assignments) if (values.has(assignment.parameter)) values.set(assignment.parameter, assignment.value);
  return values;
}

/** The concrete scenario's text: the assigned declarations' value attributes replaced, every other byte kept. */
export function concreteScenarioText(scenario: ScenarioParameters, assignments: ParameterValue[]): string {
  const finalValues = valuesAfter(scenario, assignments);
  const assigned = new Set(assignments.map((a) => a.parameter));
  const seen = new Set<string>();
  const edits: { start: number; end: number; text: string }[] = [];
  for (const declaration of scenario.declarations) {
    if (seen.has(declaration.name)) continue;
    seen.add(declaration.name);
    if (!assigned.has(declaration.name)) continue;
    const value = finalValues.get(declaration.name) as string;
    const { valueStart, valueEnd, quote } = declaration.valueAttribute;
    edits.push({ start: valueStart, end: valueEnd, text: escapeAttributeValue(value, quote) });
  }
  edits.sort((a, b) => a.start - b.start);
  let result = '';
  let at = 0;
  for (const edit of edits) {
    result += scenario.text.slice(at, edit.start) + edit.text;
    at = edit.end;
  }
  return result + scenario.text.slice(at);
}

/** The folders a catalog `Directory path` that does not resolve from the ScenarioFile's folder was found in through the scenario path. */
export type SearchPathCatalogFolders = (written: string) => Promise<string[]>;

/**
 * A concrete scenario as written to `toDirectory` (SPEC 11.6): each file path it names (roads, catalogs),
 * which resolves from `fromDirectory` (the ScenarioFile's folder), rewritten to name the same file from
 * there; absolute when `toDirectory` is undefined (standard output, a run's private folder). Unchanged
 * when written beside the ScenarioFile. `warnings`: paths naming a parameter, which stay as written, and,
 * with `foundThroughSearchPath`, catalog folders found only through the scenario path, which stay as written too.
 */
export async function rebasedConcreteText(
  text: string,
  fromDirectory: string,
  toDirectory: string | undefined,
  kindOf: (diskPath: string) => Promise<FileKind>,
  foundThroughSearchPath?: SearchPathCatalogFolders,
): Promise<{ text: string; warnings: string[] }> {
  const document = parseXml(text);
  const rebase = await rebasePaths({ document, baseOf: () => fromDirectory, outputDirectory: toDirectory, kindOf });
  const handed = handedParameterPaths(document, rebase.resolved, fromDirectory, toDirectory);
  const warnings = rebase.findings.filter((finding) => !handed.sites.has(finding.site.attribute)).map((finding) => finding.message);
  for (const site of foundThroughSearchPath ? rebase.unresolved : []) {
    const written = site.attribute.value;
    if (site.kind !== 'directory' || written.includes('$')) continue;
    const folders = await (foundThroughSearchPath as SearchPathCatalogFolders)(written);
    if (folders.length > 0) warnings.push(catalogFoundThroughSearchPathMessage(written, fromDirectory, folders));
  }
  const edits = [...rebase.edits, ...handed.edits];
  return { text: edits.length === 0 ? text : applyEdits(text, edits), warnings };
}

/**
 * The root declarations of the parameters that serve only as whole file paths (`filepath="$Road"`, every use of `$Road` such
 * a path), their relative value rewritten to name the same file from `toDirectory` (absolute when undefined): a concrete
 * scenario is written elsewhere, and the value, not the `$Road` where it is used, is what names the file (SPEC 11.6 leaves
 * the use as written). A parameter used otherwise too (in a string, an expression, an assignment) keeps its value.
 */
function handedParameterPaths(
  document: XmlDocument,
  resolved: readonly ResolvedPath[],
  fromDirectory: string,
  toDirectory: string | undefined,
): { edits: TextEdit[]; sites: Set<XmlAttribute> } {
  const none = { edits: [], sites: new Set<XmlAttribute>() };
  const root = document.root;
  const output = toDirectory === undefined ? undefined : path.resolve(toDirectory);
  if (!root || output === path.resolve(fromDirectory)) return none;
  const byName = new Map<string, ResolvedPath[]>();
  for (const each of resolved) {
    const name = /^\$([A-Za-z_][\w]*)$/.exec(each.site.attribute.value.trim())?.[1];
    if (each.viaParameter && name !== undefined && !path.isAbsolute(each.written)) byName.set(name, [...(byName.get(name) ?? []), each]);
  }
  if (byName.size === 0) return none;
  const elements = [root, ...descendants(root)];
  const edits: TextEdit[] = [];
  const sites = new Set<XmlAttribute>();
  for (const [name, paths] of byName) {
    const declarations = elements.filter(
      (element) => element.name === 'ParameterDeclaration' && attribute(element, 'name')?.value === name,
    );
    const declaration = declarations[0];
    const value = declaration && attribute(declaration, 'value');
    if (declarations.length !== 1 || declaration.parent?.parent !== root || !value || value.value.includes('$')) continue;
    const use = new RegExp(`\\$\\{?${name}(?![\\w.])`);
    const uses = elements.flatMap((element) => element.attributes.filter((each) => use.test(each.value)));
    const disk = path.resolve(fromDirectory, value.value.trim());
    if (uses.length !== paths.length || paths.some((each) => each.disk !== disk)) continue;
    const text = output === undefined ? written(disk, value.value) : written(path.relative(output, disk), value.value);
    edits.push({ start: value.valueStart, end: value.valueEnd, text: escapeAttributeValue(text, value.quote) });
    for (const each of paths) sites.add(each.site.attribute);
  }
  return { edits, sites };
}

/** Whether the scenario declares any ValueConstraintGroup at its root. */
export function hasConstraints(scenario: ScenarioParameters): boolean {
  return scenario.declarations.some((d) => d.constraintGroups.length > 0);
}

/** The first declared parameter whose final value breaks its constraint groups, or undefined when all hold. */
export function brokenConstraint(
  scenario: ScenarioParameters,
  assignments: ParameterValue[],
): { parameter: string; value: string } | undefined {
  const values = valuesAfter(scenario, assignments);
  const resolve = resolverOf(scenario, values);
  const seen = new Set<string>();
  for (const declaration of scenario.declarations) {
    if (seen.has(declaration.name)) continue;
    seen.add(declaration.name);
    if (declaration.constraintGroups.length === 0) continue;
    const value = resolve(declaration.name) ?? (values.get(declaration.name) as string);
    const numeric = NUMERIC_TYPES.has(declaration.type);
    const holds = declaration.constraintGroups.some((group) =>
      group.every((constraint) => {
        const bound = resolve.text(constraint.value);
        return bound !== undefined && meets(value, bound, constraint.rule, numeric);
      }),
    );
    if (!holds) return { parameter: declaration.name, value: values.get(declaration.name) as string };
  }
  return undefined;
}

type Resolver = ((name: string) => string | undefined) & { text(written: string): string | undefined };

/**
 * The text of a value as the concrete scenario gives it: a literal as written, `$name` and `${...}` (as in
 * ALKS's `value="${-$Ego_InitSpeed_Ve0_kph}"`) evaluated over the combination's parameter values. Undefined
 * when it cannot be evaluated (an undeclared name, a circle, an expression error).
 */
function resolverOf(scenario: ScenarioParameters, values: Map<string, string>): Resolver {
  const types = new Map<string, string>();
  for (const declaration of scenario.declarations) if (!types.has(declaration.name)) types.set(declaration.name, declaration.type);
  const resolved = new Map<string, string | undefined>();
  const resolving = new Set<string>();
  const text = (written: string): string | undefined => {
    const form = valueForm(written.trim());
    if (form.kind === 'literal') return written;
    if (form.kind === 'parameter') return byName(form.name);
    const tree = form.expression.tree;
    if (!tree || form.expression.errors.length > 0) return undefined;
    const result = evaluateTree(tree, (name): LookupResult | undefined => {
      const found = byName(name);
      if (found === undefined) return undefined;
      const type = normalizeParameterType(types.get(name)) ?? 'string';
      if (type === 'string' || type === 'dateTime') return { value: found, type };
      return readStringAsValue(found) ?? { value: found, type: 'string' };
    });
    return result.ok ? String(result.value) : undefined;
  };
  const byName = (name: string): string | undefined => {
    if (resolved.has(name)) return resolved.get(name);
    const written = values.get(name);
    if (written === undefined || resolving.has(name)) return undefined;
    resolving.add(name);
    const value = text(written);
    resolving.delete(name);
    resolved.set(name, value);
    return value;
  };
  return Object.assign(byName, { text });
}

/**
 * Why a distribution's value does not fit its parameter's type, or undefined when it does. A `$name` or `${...}` value is
 * checked by what it evaluates to over the scenario's values (esmini writes the text into the declaration, which evaluates it:
 * ScenarioReader.cpp, "Parameter permutation"); one that cannot be evaluated is checked as written.
 */
export function assignedValueMismatch(scenario: ScenarioParameters, assignment: ParameterValue, type: string): string | undefined {
  const evaluated =
    valueForm(assignment.value.trim()).kind === 'literal'
      ? undefined
      : resolverOf(scenario, valuesAfter(scenario, [assignment])).text(assignment.value);
  return typeMismatch(evaluated ?? assignment.value, type);
}

/** Numbers compare as numbers for numeric parameter types; everything else compares as text (dateTime in ISO form orders correctly). */
function meets(value: string, bound: string, rule: ConstraintRule, numeric: boolean): boolean {
  let order: number;
  if (numeric) {
    const left = Number(value.trim());
    const right = Number(bound.trim());
    if (!Number.isFinite(left) || !Number.isFinite(right)) return false;
    order = left === right ? 0 : left < right ? -1 : 1;
  } else order = value === bound ? 0 : value < bound ? -1 : 1;
  switch (rule) {
    case 'equalTo':
      return order === 0;
    case 'notEqualTo':
      return order !== 0;
    case 'greaterThan':
      return order > 0;
    case 'lessThan':
      return order < 0;
    case 'greaterOrEqual':
      return order >= 0;
    case 'lessOrEqual':
      return order <= 0;
  }
}

const INTEGER_TYPES = new Set(['int', 'integer', 'unsignedInt', 'unsignedShort']);

/** Why a value does not fit a parameter type, or undefined when it does (strings and dateTime take any text here). */
export function typeMismatch(value: string, type: string): string | undefined {
  const trimmed = value.trim();
  const number = trimmed === '' ? NaN : Number(trimmed);
  if (type === 'boolean') return /^(true|false)$/.test(trimmed) ? undefined : 'is not true or false';
  if (!NUMERIC_TYPES.has(type)) return undefined;
  if (!Number.isFinite(number)) return 'is not a number';
  if (INTEGER_TYPES.has(type) && !Number.isInteger(number)) return 'is not a whole number';
  if ((type === 'unsignedInt' || type === 'unsignedShort') && number < 0) return 'is negative';
  if (type === 'unsignedShort' && number > 65535) return 'is above 65535';
  return undefined;
}
