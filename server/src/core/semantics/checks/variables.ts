import { attribute, XmlElement } from '../../xml';
import type { Finding, SemanticCheck } from './types';
import { convertValue } from '../values';
import { Declaration, referencedName, resolveName, SemanticModel } from '../model';
import { at } from './support';
import { modifyNonNumberWording, variableValueWording } from '../../diagnostics/typeMismatch';
import {
  catalogEntryVariableWording,
  undeclaredEntryVariableWording,
  undeclaredVariableWording,
} from '../../diagnostics/undeclaredVariable';

/** The catalog entry (a child of the file's `Catalog`) that holds an element. */
function entryOf(model: SemanticModel, element: XmlElement): XmlElement | undefined {
  for (let current: XmlElement | undefined = element; current; current = current.parent) {
    if (current.parent && current.parent === model.catalog) return current;
  }
  return undefined;
}

/**
 * Every `variableRef` names a declared variable (1.2 and later). A name a parameter in scope has is
 * accepted: ASAM's Quality Checker (`resolvable_variable_reference`) resolves a variableRef against
 * parameter declarations too. A catalog declares no variables: a variable used in a catalog entry
 * resolves against each scenario that references the entry, where it is checked (catalogVariables);
 * in the catalog it is only a note.
 */
export const undeclaredVariables: SemanticCheck = ({ model }) => {
  const findings: Finding[] = [];
  for (const reference of model.variableReferences) {
    if (reference.declaration) continue;
    const name = referencedName(reference.attribute).name;
    if (resolveName(model.scopeOf(reference.element), name, undefined)) continue;
    const entry = model.catalog ? entryOf(model, reference.element) : undefined;
    const entryName = entry ? attribute(entry, 'name')?.value : undefined;
    findings.push({
      ...at(reference.element, reference.attribute),
      ...(entry ? catalogEntryVariableWording(name, entryName) : undeclaredVariableWording(reference.attribute.value)),
      data: entryName !== undefined ? { variable: name, entry: entryName } : { variable: name },
    });
  }
  return findings;
};

/** A variable's declaration for a reference: this file's variables, else a parameter in scope (undefined: reported elsewhere). */
function variableOf(model: SemanticModel, element: XmlElement, name: string): Declaration | undefined {
  return model.variables.get(name) ?? resolveName(model.scopeOf(element), name, undefined);
}

const NUMERIC = new Set(['double', 'int', 'unsignedInt', 'unsignedShort']);

/** Where a value is given to a variable or parameter: its action or condition and what it names. */
interface ValueTarget {
  element: XmlElement;
  declaration: Declaration;
  name: string;
}

function valueTargets(model: SemanticModel): ValueTarget[] {
  const targets: ValueTarget[] = [];
  for (const reference of model.variableReferences) {
    const name = referencedName(reference.attribute).name;
    const declaration = reference.declaration ?? variableOf(model, reference.element, name);
    if (declaration) targets.push({ element: reference.element, declaration, name });
  }
  for (const use of model.uses) {
    if (
      use.via !== 'parameterRef' ||
      !use.declaration ||
      (use.element.name !== 'ParameterAction' && use.element.name !== 'ParameterCondition')
    )
      continue;
    targets.push({ element: use.element, declaration: use.declaration, name: use.name });
  }
  return targets;
}

/**
 * The values given to a variable (or, in the deprecated ParameterAction, a parameter) fit its type: a
 * `SetAction` value converts to it (`wrongBoolean` is no boolean), a `ModifyAction` (add, multiply)
 * only changes a number, a condition compares with a value of the type.
 */
export const variableValues: SemanticCheck = ({ model, evaluator }) => {
  const findings: Finding[] = [];
  for (const { element: target, declaration, name } of valueTargets(model)) {
    const type = declaration.type;
    if (!type) continue;
    const named = { kind: declaration.kind, name, writtenType: declaration.writtenType };
    const condition = target.name === 'VariableCondition' || target.name === 'ParameterCondition';
    const valued: XmlElement[] = condition ? [target] : target.children.filter((child) => child.name === 'SetAction');
    for (const element of valued) {
      const valueAttribute = attribute(element, 'value');
      const text = evaluator.textOf(element, valueAttribute);
      if (text === undefined) continue;
      const converted = convertValue({ value: text, type: 'string' }, type);
      if (!('mismatch' in converted)) continue;
      findings.push({
        ...at(element, valueAttribute),
        ...variableValueWording(text, named, converted.mismatch),
      });
    }
    const modify = target.children.find((child) => child.name === 'ModifyAction');
    if (modify && !NUMERIC.has(type)) {
      findings.push({
        ...at(modify, undefined),
        ...modifyNonNumberWording(named),
      });
    }
  }
  return findings;
};

/**
 * A variable a catalog entry uses that the entry's catalog cannot declare: every scenario that
 * references the entry declares it, or gets an error at its CatalogReference.
 */
export const catalogVariables: SemanticCheck = (context) => {
  const findings: Finding[] = [];
  if (context.model.catalog) return findings;
  for (const resolution of context.catalogs.references) {
    const entry = resolution.entry;
    if (!entry) continue;
    const entryModel = entry.file.model;
    const missing = new Set<string>();
    for (const reference of entryModel.variableReferences) {
      if (reference.declaration || entryOf(entryModel, reference.element) !== entry.element) continue;
      const name = referencedName(reference.attribute).name;
      if (resolveName(entryModel.scopeOf(reference.element), name, undefined)) continue;
      if (!variableOf(context.model, resolution.reference.element, name)) missing.add(name);
    }
    for (const name of missing) {
      findings.push({
        ...at(resolution.reference.element, resolution.reference.entryNameAttribute),
        ...undeclaredEntryVariableWording(entry.name, name),
      });
    }
  }
  return findings;
};
