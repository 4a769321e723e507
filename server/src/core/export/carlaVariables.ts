/**
 * OpenSCENARIO 1.2 variables in their 1.0 form, and the parameters ScenarioRunner compares while it runs.
 *
 * 1.0 has no variables, but its parameters change at run time the same way: ScenarioRunner keeps every declared
 * parameter in a global table (SR_CONFIGURATION:234), a ParameterAction changes it (SR_PARSER:1259-1270,
 * SR_ATOMICS:194-226 ChangeParameter) and a ParameterCondition compares it at every tick (SR_PARSER:1099-1123,
 * SR_TRIGGER_CONDITIONS:1459-1477 CheckParameter). So a VariableDeclaration is written as a ParameterDeclaration,
 * a VariableAction as a ParameterAction and a VariableCondition as a ParameterCondition.
 *
 * The table holds a declared value as its text, which CheckParameter compares with a number (ParameterRef,
 * SR_PARSER:143-147, 189-214): lessThan and greaterThan raise TypeError, equalTo never holds. Only a value a
 * ParameterAction wrote compares as a number. So the Init sets every parameter a condition compares to its
 * declared value (SR_SCENARIO:201-222, ticked before the stories: SR_SCENARIO:516-518), a boolean as 1 or 0
 * (float('true') raises), and a value that is no number is not kept.
 */
import { dropUnit } from './carlaLosses';
import type { LossSink } from './carlaLosses';
import { SR_ATOMICS, SR_CONFIGURATION, SR_PARSER, SR_SCENARIO, SR_TRIGGER_CONDITIONS } from './carlaFacts';
import { ancestor, appendChild, attr, child, childrenNamed, makeNode, named, Node, removeNode, replaceNode, setAttr } from './tree';

const AS_PARAMETERS = `ScenarioRunner keeps parameters in a global table (${SR_CONFIGURATION}:234) that a ParameterAction changes (${SR_PARSER}:1259-1270, ${SR_ATOMICS}:194-226 ChangeParameter) and a ParameterCondition compares at every tick (${SR_PARSER}:1099-1123, ${SR_TRIGGER_CONDITIONS}:1459-1477 CheckParameter); 1.0 has no variables`;

const COMPARED_AS_NUMBERS = `ScenarioRunner compares a parameter as a number, and a value that is no number raises ValueError there (${SR_PARSER}:143-147, 189-214 ParameterRef)`;

const SET_IN_INIT = `the Init sets it (${SR_SCENARIO}:201-222), since a value still as declared is text to ScenarioRunner, which raises TypeError or never holds when compared (${SR_PARSER}:143-147, 189-214 ParameterRef)`;

/** The value ScenarioRunner compares for a value of this type: a boolean as 1 or 0, a number as written; undefined for anything else. */
type AsNumber = (value: string | undefined) => string | undefined;

function asNumber(type: string | undefined): AsNumber {
  if (type === 'boolean') return (value) => (value === 'true' ? '1' : value === 'false' ? '0' : undefined);
  if (type === 'string' || type === 'dateTime') return () => undefined;
  return (value) => (value !== undefined && value.trim() !== '' && Number.isFinite(Number(value)) ? value.trim() : undefined);
}

/** A variable's parameter: its name in the export and how its values are written. */
interface VariableParameter {
  name: string;
  boolean: boolean;
  asNumber: AsNumber;
}

/** The node renamed, with these attributes and its children (a node's name is fixed, so it is replaced). */
function renamed(node: Node, name: string, attributes: [string, string][]): Node {
  const replacement = makeNode(name, attributes, [...node.children], node.place);
  replaceNode(node, replacement);
  return replacement;
}

export function variables(tree: Node, context: { sink: LossSink }): void {
  const mapped = variablesAsParameters(tree, context);
  const fromVariables = new Set([...mapped.values()].map((parameter) => parameter.name));
  for (const action of named(tree, 'VariableAction')) {
    const parameter = mapped.get(attr(action, 'variableRef') ?? '');
    const set = child(action, 'SetAction');
    const rule = child(child(action, 'ModifyAction') ?? action, 'Rule');
    const change = set ?? (rule && (child(rule, 'AddValue') ?? child(rule, 'MultiplyByValue')));
    const value = parameter && change && parameter.asNumber(attr(change, 'value'));
    // A boolean is set, never added to or multiplied.
    if (!parameter || !change || value === undefined || (parameter.boolean && !set)) {
      dropUnit(action, context, 'VariableAction', COMPARED_AS_NUMBERS);
      continue;
    }
    setAttr(change, 'value', value);
    renamed(action, 'ParameterAction', [['parameterRef', parameter.name]]);
  }
  for (const condition of named(tree, 'VariableCondition')) {
    const parameter = mapped.get(attr(condition, 'variableRef') ?? '');
    const value = parameter?.asNumber(attr(condition, 'value'));
    if (!parameter || value === undefined) {
      dropUnit(condition, context, 'VariableCondition', COMPARED_AS_NUMBERS);
      continue;
    }
    const rule = attr(condition, 'rule') ?? 'equalTo';
    // Of two values, "not this one" is "the other one", which 1.0 can say (it has no notEqualTo).
    const other = parameter.boolean && rule === 'notEqualTo';
    renamed(condition, 'ParameterCondition', [
      ['parameterRef', parameter.name],
      ['value', other ? (value === '1' ? '0' : '1') : value],
      ['rule', other ? 'equalTo' : rule],
    ]);
  }
  comparedParametersSetInInit(tree, context, fromVariables);
}

/** Each VariableDeclaration as a ParameterDeclaration (renamed if a parameter has its name), by the variable's name; the VariableDeclarations go. */
function variablesAsParameters(tree: Node, context: { sink: LossSink }): Map<string, VariableParameter> {
  const declarations = child(tree, 'ParameterDeclarations');
  const taken = new Set(declarations ? childrenNamed(declarations, 'ParameterDeclaration').map((each) => attr(each, 'name')) : []);
  const mapped = new Map<string, VariableParameter>();
  const added: Node[] = [];
  for (const block of named(tree, 'VariableDeclarations')) {
    for (const variable of childrenNamed(block, 'VariableDeclaration')) {
      const name = attr(variable, 'name') ?? '';
      const type = attr(variable, 'variableType');
      const number = asNumber(type);
      const initial = number(attr(variable, 'value'));
      if (initial === undefined) {
        context.sink.dropped(
          variable,
          'VariableDeclaration',
          `the ${type ?? ''} variable '${name}' ('${attr(variable, 'value') ?? ''}') is dropped, with its actions and conditions`,
          COMPARED_AS_NUMBERS,
        );
        continue;
      }
      let parameter = name;
      for (let count = 1; taken.has(parameter); count++) parameter = `${name}_variable${count > 1 ? count : ''}`;
      taken.add(parameter);
      const boolean = type === 'boolean';
      mapped.set(name, { name: parameter, boolean, asNumber: number });
      const parameterType = boolean || type === 'int' ? 'integer' : (type ?? 'double');
      added.push(
        makeNode(
          'ParameterDeclaration',
          [
            ['name', parameter],
            ['parameterType', parameterType],
            ['value', initial],
          ],
          [],
          variable.place,
        ),
      );
      context.sink.approximated(
        variable,
        'VariableDeclaration',
        `the variable '${name}' is written as the parameter '${parameter}'${boolean ? ' (1 for true, 0 for false)' : ''}, set in the Init; its VariableActions as ParameterActions, its VariableConditions as ParameterConditions`,
        AS_PARAMETERS,
      );
    }
    removeNode(block);
  }
  if (added.length > 0) {
    const parameters = declarations ?? appendChild(tree, makeNode('ParameterDeclarations'), child(tree, 'CatalogLocations'));
    for (const each of added) appendChild(parameters, each);
  }
  return mapped;
}

/** Every parameter a ParameterCondition compares is set in the Init to its declared value, as a number; a boolean one is 1 or 0 throughout. */
function comparedParametersSetInInit(tree: Node, context: { sink: LossSink }, fromVariables: ReadonlySet<string>): void {
  const declarations = child(tree, 'ParameterDeclarations');
  const actions = child(child(child(tree, 'Storyboard') ?? tree, 'Init') ?? tree, 'Actions');
  if (!declarations || !actions) return;
  const declared = new Map(childrenNamed(declarations, 'ParameterDeclaration').map((each) => [attr(each, 'name') ?? '', each]));
  const setAlready = new Set(
    named(actions, 'ParameterAction')
      .filter((action) => ancestor(action, 'GlobalAction')?.parent === actions)
      .map((action) => attr(action, 'parameterRef')),
  );
  const firstOther = actions.children.find((each) => each.name !== 'GlobalAction');
  const booleans = new Set<string>();
  for (const condition of named(tree, 'ParameterCondition')) {
    // A criteria_ condition names one of ScenarioRunner's test criteria, not a parameter (SR_PARSER:1104-1121).
    if ((attr(ancestor(condition, 'Condition') ?? condition, 'name') ?? '').startsWith('criteria_')) continue;
    const name = (attr(condition, 'parameterRef') ?? '').replace(/^\$/, '');
    const declaration = declared.get(name);
    if (!declaration) continue;
    const type = attr(declaration, 'parameterType');
    const number = asNumber(type);
    const initial = number(attr(declaration, 'value'));
    const value = number(attr(condition, 'value'));
    if (initial === undefined || value === undefined) {
      dropUnit(condition, context, 'ParameterCondition', COMPARED_AS_NUMBERS);
      continue;
    }
    setAttr(condition, 'value', value);
    if (type === 'boolean') booleans.add(name);
    if (setAlready.has(name)) continue;
    setAlready.add(name);
    const set = makeNode('SetAction', [['value', initial]]);
    appendChild(actions, makeNode('GlobalAction', [], [makeNode('ParameterAction', [['parameterRef', name]], [set])]), firstOther);
    // A variable's declaration said so already.
    if (!fromVariables.has(name))
      context.sink.approximated(declaration, 'ParameterDeclaration', `'${name}' is set to ${initial} in the Init`, SET_IN_INIT);
  }
  for (const name of booleans) {
    const declaration = declared.get(name) as Node;
    setAttr(declaration, 'parameterType', 'integer');
    setAttr(declaration, 'value', asNumber('boolean')(attr(declaration, 'value')) as string);
    for (const action of named(tree, 'ParameterAction')) {
      const set = attr(action, 'parameterRef') === name ? child(action, 'SetAction') : undefined;
      const value = set && asNumber('boolean')(attr(set, 'value'));
      if (set && value !== undefined) setAttr(set, 'value', value);
    }
  }
}
