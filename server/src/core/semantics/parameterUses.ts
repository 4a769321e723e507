import { attribute, XmlAttribute, XmlElement } from '../xml';
import { valueForm } from './expressionParser';
import { resolveName } from './scopes';
import { Declaration, ParameterUse, Scope, SemanticModel, ValueSite } from './types';

/** Elements whose `parameterRef` names a parameter of the enclosing scopes (1.0-1.1 parameter actions and conditions). */
export const PARAMETER_REF_ELEMENTS = new Set(['ParameterCondition', 'ParameterAction', 'ParameterSetAction', 'ParameterModifyAction']);
/**
 * Attributes that name a parameter or variable rather than use its value; esmini accepts them with a leading `$`.
 * A distribution's `parameterName` names a root parameter of its ScenarioFile, not one of its own file.
 */
const NAME_REFERENCE_ATTRIBUTES = new Set(['parameterRef', 'variableRef', 'parameterName']);

/**
 * CARLA scenario_runner reads a StopTrigger condition named `criteria_NAME` as its evaluation
 * criterion NAME, whose ParameterCondition `parameterRef` is an argument name, not a parameter
 * (scenario_runner srunner/tools/openscenario_parser.py, `convert_condition_to_atomic`).
 */
function isCarlaCriterion(element: XmlElement): boolean {
  for (let current = element.parent; current; current = current.parent) {
    if (current.name === 'Condition') return attribute(current, 'name')?.value.startsWith('criteria_') ?? false;
  }
  return false;
}

/** The name a `parameterRef`/`variableRef` gives, without the `$` some files write, and its offsets. */
export function referencedName(attr: XmlAttribute): { name: string; start: number; end: number } {
  const leading = attr.value.length - attr.value.trimStart().length;
  const dollar = attr.value.trimStart().startsWith('$') ? 1 : 0;
  const name = attr.value.trim().slice(dollar);
  const start = attr.valueStart + leading + dollar;
  return { name, start, end: start + name.length };
}

/** Collects the `$name` and `${...}` values of every attribute and the `parameterRef`s that name a parameter. */
export class ParameterUseCollector {
  /** `model`: where sites and uses go (a whole model, or the few lists an incremental update fills). */
  constructor(private readonly model: Pick<SemanticModel, 'sites' | 'siteOf' | 'uses' | 'usesOf'>) {}

  /** `ownDeclaration`: the declaration `element` makes, whose value sees only the earlier ones of its scope. */
  visit(element: XmlElement, scope: Scope, ownDeclaration: Declaration | undefined): void {
    const attributes = element.attributes;
    for (let i = 0; i < attributes.length; i++) this.visitValue(element, attributes[i], scope, ownDeclaration);
    if (PARAMETER_REF_ELEMENTS.has(element.name) && !isCarlaCriterion(element)) {
      const ref = attribute(element, 'parameterRef');
      if (ref && ref.value.trim()) {
        const { name, start, end } = referencedName(ref);
        this.addUse({ name, start, end, element, attribute: ref, declaration: resolveName(scope, name, undefined), via: 'parameterRef' });
      }
    }
  }

  /** The site and uses of one attribute's value, when it is a `$name` or a `${...}`. */
  visitValue(element: XmlElement, attr: XmlAttribute, scope: Scope, ownDeclaration: Declaration | undefined): void {
    if (attr.value.charCodeAt(0) !== 36 || NAME_REFERENCE_ATTRIBUTES.has(attr.name)) return;
    // The offsets of a decoded value are exact only when it was written without references.
    const form = valueForm(attr.value, attr.valueStart);
    if (form.kind === 'literal') return;
    const declaration = ownDeclaration && attr.name === 'value' ? ownDeclaration : undefined;
    const site: ValueSite = { element, attribute: attr, form, scope, declaration };
    this.model.sites.push(site);
    this.model.siteOf.set(attr, site);
    const names = form.kind === 'parameter' ? [{ name: form.name, start: form.start, end: form.end }] : form.expression.parameters;
    const via = form.kind === 'parameter' ? 'value' : 'expression';
    const found = names.map((name) => ({ ...name, declaration: resolveName(scope, name.name, declaration) }));
    // A bare word naming a declared parameter is a use (written without `$`, a warning); any other word is text.
    if (form.kind === 'expression') {
      for (const name of form.expression.names) {
        const resolved = resolveName(scope, name.name, declaration);
        if (resolved) found.push({ ...name, declaration: resolved });
      }
      found.sort((a, b) => a.start - b.start);
    }
    for (const name of found)
      this.addUse({ name: name.name, start: name.start, end: name.end, element, attribute: attr, declaration: name.declaration, via });
  }

  private addUse(use: ParameterUse): void {
    this.model.uses.push(use);
    if (use.declaration) this.model.usesOf.get(use.declaration)?.push(use);
  }
}
