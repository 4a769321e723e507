import { attribute, XmlElement } from '../xml';
import { normalizeParameterType } from './values';
import { Declaration, DeclarationKind, Scope, SemanticModel } from './types';

/**
 * Collects the scopes of a model and their parameter declarations (and the root's variables, which
 * share the declaration records): a scope is opened, and its parameters declared, before anything
 * below its element is read.
 */
export class ScopeCollector {
  /** The declaration made by each `ParameterDeclaration` element. */
  readonly declarationByElement = new Map<XmlElement, Declaration>();
  private readonly scopeByElement = new Map<XmlElement, Scope>();

  constructor(
    private readonly model: SemanticModel,
    private readonly rootElement: XmlElement,
  ) {}

  /** The scope each element belongs to (its own for a scope holder). */
  scopeOf(element: XmlElement): Scope | undefined {
    for (let current: XmlElement | undefined = element; current; current = current.parent) {
      const scope = this.scopeByElement.get(current);
      if (scope) return scope;
    }
    return undefined;
  }

  declare(scope: Scope, element: XmlElement, kind: DeclarationKind): Declaration {
    const nameAttribute = attribute(element, 'name');
    const typeAttribute = attribute(element, kind === 'parameter' ? 'parameterType' : 'variableType');
    const declaration: Declaration = {
      kind,
      // esmini and the ASAM OpenSCENARIO API take name="$X" as X (the 0.9 style); dollarDeclarations warns.
      name: (nameAttribute?.value.trim() ?? '').replace(/^\$/, ''),
      type: normalizeParameterType(typeAttribute?.value),
      writtenType: typeAttribute?.value,
      value: attribute(element, 'value')?.value ?? '',
      element,
      nameAttribute,
      valueAttribute: attribute(element, 'value'),
      typeAttribute,
      scope,
      index: scope.declarations.length,
    };
    if (kind === 'parameter') {
      scope.declarations.push(declaration);
      if (!scope.byName.has(declaration.name)) scope.byName.set(declaration.name, declaration);
      scope.lastByName.set(declaration.name, declaration);
    } else if (!this.model.variables.has(declaration.name)) {
      this.model.variables.set(declaration.name, declaration);
    }
    this.model.declarations.push(declaration);
    this.model.usesOf.set(declaration, []);
    return declaration;
  }

  /** Opens the scope an element holds, declaring its parameters before anything below it is read. */
  enter(element: XmlElement, current: Scope | undefined): Scope | undefined {
    let holdsDeclarations = false;
    // Index loops on this per-element path: for...of makes an iterator and a result object per step until optimized.
    const children = element.children;
    for (let i = 0; i < children.length; i++) {
      if (children[i].name === 'ParameterDeclarations') {
        holdsDeclarations = true;
        break;
      }
    }
    const isCatalogEntry = element.parent !== undefined && element.parent.name === 'Catalog';
    if (!holdsDeclarations && element !== this.rootElement && !isCatalogEntry) return current;
    const scope: Scope = {
      element,
      parent: current,
      children: [],
      declarations: [],
      byName: new Map(),
      lastByName: new Map(),
      catalogEntry: isCatalogEntry,
    };
    current?.children.push(scope);
    this.model.scopes.push(scope);
    this.scopeByElement.set(element, scope);
    for (const child of element.children) {
      if (child.name !== 'ParameterDeclarations') continue;
      for (const declaration of child.children) {
        if (declaration.name === 'ParameterDeclaration')
          this.declarationByElement.set(declaration, this.declare(scope, declaration, 'parameter'));
      }
    }
    return scope;
  }
}

/**
 * The declaration `name` resolves to from `scope`: the innermost scope that declares it wins. For the
 * value of a declaration, only the declarations before it in its own scope are visible (a value may
 * use earlier parameters, so no value can depend on itself). Of two declarations of the name in one scope the
 * first is found, or with `lastWins` the last, as esmini reads them (core/profiles/esmini.ts valueRules.redeclaration).
 */
export function resolveName(
  scope: Scope | undefined,
  name: string,
  within: Declaration | undefined,
  lastWins = false,
): Declaration | undefined {
  for (let current = scope; current; current = current.parent) {
    if (within && current === within.scope) {
      // A declaration of the name is found only when it comes before the value being read.
      const first = current.byName.get(name);
      if (!first || first.index >= within.index) continue;
      if (!lastWins) return first;
      const last = current.lastByName.get(name) as Declaration;
      if (last.index < within.index) return last;
      // esmini reads the declarations in order: the last of the name before the value being read.
      for (let index = within.index - 1; index > first.index; index--)
        if (current.declarations[index].name === name) return current.declarations[index];
      return first;
    }
    const found = lastWins ? current.lastByName.get(name) : current.byName.get(name);
    if (found) return found;
  }
  return undefined;
}

/** Every declaration visible from a scope (innermost first, shadowed ones left out). */
export function visibleDeclarations(scope: Scope | undefined, within?: Declaration): Declaration[] {
  const seen = new Set<string>();
  const result: Declaration[] = [];
  for (let current = scope; current; current = current.parent) {
    for (const candidate of current.declarations) {
      if (within && current === within.scope && candidate.index >= within.index) break;
      if (seen.has(candidate.name)) continue;
      seen.add(candidate.name);
      result.push(candidate);
    }
  }
  return result;
}
