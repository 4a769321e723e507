import { attribute, XmlElement } from '../xml';
import { referencedName } from './parameterUses';
import { ScopeCollector } from './scopes';
import { Scope, SemanticModel } from './types';

const VARIABLE_REF_ELEMENTS = new Set(['VariableCondition', 'VariableAction']);

/** Collects the variables (1.2+ `VariableDeclarations`) and the `variableRef`s that name them. */
export class VariableCollector {
  constructor(
    private readonly model: SemanticModel,
    private readonly scopes: ScopeCollector,
  ) {}

  visit(element: XmlElement, scope: Scope): void {
    if (element.name === 'VariableDeclarations') {
      for (const declaration of element.children)
        if (declaration.name === 'VariableDeclaration') this.scopes.declare(scope, declaration, 'variable');
    }
    if (VARIABLE_REF_ELEMENTS.has(element.name)) {
      const ref = attribute(element, 'variableRef');
      if (ref) this.model.variableReferences.push({ element, attribute: ref, declaration: undefined });
    }
  }

  /** Variables are global (declared at the root), so references are resolved once all are known. */
  finish(): void {
    for (const reference of this.model.variableReferences)
      reference.declaration = this.model.variables.get(referencedName(reference.attribute).name);
  }
}
