import { expressionWording } from '../diagnostics/expressionWords';
import { nonstandardToken } from '../diagnostics/expressionSyntax';
import { entryFindings, SimulatorFinding, simulatorFindings } from '../profiles/checks';
import { baseName, displayRef } from '../sources';
import { closestMatch } from '../text';
import { coreMemo } from '../memos';
import { attribute, descendants, XmlAttribute, XmlElement } from '../xml';
import { ExpressionError } from './expressionParser';
import { valueConstraints } from './checks/constraints';
import { duplicateNames } from './checks/names';
import { carlaReleaseOf, carlaScenario } from './checks/carla';
import { esminiScenario } from './checks/esmini';
import { at, onCatalogReferences, relatedAt } from './checks/support';
import type { Finding, SemanticCheck, SemanticContext } from './checks/types';
import type { CatalogFile, CatalogReferenceResolution, LocationResolution } from './catalogs';
import { carriedExpressionErrors, rememberExpressionErrors } from './checks/carriedResults';
import { catalogVariables, undeclaredVariables, variableValues } from './checks/variables';
import {
  lightTransitionTimes,
  phaseDurations,
  privateActionActors,
  trafficSignalControllerRefs,
  roadFileFound,
  trafficSignalIds,
  valueRanges,
} from './networkChecks';
import { CATALOG_FOLDER_ALSO_NOTE, catalogDirectoryWording, catalogFolderWording } from '../diagnostics/catalogDirectory';
import { ambiguousReferenceWording } from '../diagnostics/ambiguousReference';
import { DUPLICATE_PARAMETER_FIRST_NOTE, duplicateParameterWording } from '../diagnostics/duplicateParameter';
import { dollarDeclarationWording, retypeWords, writeStandardHint } from '../diagnostics/lenientValue';
import { renamedReferenceWording } from '../diagnostics/renamedReference';
import { undeclaredCatalogParameterWording } from '../diagnostics/undeclaredCatalogParameter';
import { undeclaredEntityWording } from '../diagnostics/undeclaredEntity';
import { undeclaredParameterWording } from '../diagnostics/undeclaredParameter';
import { unknownAssignedParameterWording } from '../diagnostics/unknownAssignedParameter';
import { catalogFileNameWording, catalogFoundByFileNameWording, unknownCatalogWording } from '../diagnostics/unknownCatalog';
import { SHADOWED_ENTRY_NOTE, unknownCatalogEntryWording } from '../diagnostics/unknownCatalogEntry';
import { unknownStoryboardElementWording } from '../diagnostics/unknownStoryboardElement';
import { unusedParameterWording } from '../diagnostics/unusedParameter';
import { simulatorWording } from '../diagnostics/simulator';
import {
  Declaration,
  Evaluator,
  referencedName,
  resolveName,
  SemanticModel,
  STORYBOARD_ELEMENT_NAMES,
  STORYBOARD_ELEMENT_TYPES,
} from './model';

/**
 * The semantic checks: each is one small function over a document's model, registered in
 * SEMANTIC_CHECKS. A check reports Findings at offsets of the document; the caller turns them into
 * Problems (for a flattened output, at the source position each element came from).
 */

export type { Finding, SemanticCheck, SemanticContext } from './checks/types';

/** The entry of a catalog file that holds an element (the child of its `Catalog`). */
export function catalogEntryOf(model: SemanticModel, element: XmlElement): XmlElement | undefined {
  for (let current: XmlElement | undefined = element; current; current = current.parent) {
    if (current.parent && current.parent === model.catalog) return current;
  }
  return undefined;
}

/** The parameters a resolved catalog entry uses and does not declare: esmini takes them from the referencing scenario. */
export function entryFreeParameters(resolution: CatalogReferenceResolution): Set<string> {
  const entry = resolution.entry;
  if (!entry) return new Set();
  const entryModel = entry.file.model;
  return new Set(
    entryModel.uses.filter((use) => !use.declaration && catalogEntryOf(entryModel, use.element) === entry.element).map((use) => use.name),
  );
}

/**
 * Every `$name` and `parameterRef` resolves to a declaration in scope. A catalog entry declares every
 * parameter it uses (ASAM QC `parameters.valid_parameter_declaration_in_catalogs`): an error, although
 * esmini takes the name from the scenario that references the entry (catalogReferences checks it there).
 */
export const undeclaredParameters: SemanticCheck = ({ model, simulator }) =>
  model.uses
    .filter((use) => !use.declaration)
    .map((use) => {
      const inEntry = model.catalog !== undefined && catalogEntryOf(model, use.element) !== undefined;
      return {
        element: use.element,
        attribute: use.attribute,
        start: use.start,
        end: use.end,
        // esmini takes the value from the referencing scenario, where catalogReferences checks it (SPEC 12: a warning with esmini).
        ...(inEntry ? undeclaredCatalogParameterWording(use.name, simulator === 'esmini') : undeclaredParameterWording(use.name)),
        data: { parameter: use.name },
      };
    });

/**
 * `name="$X"` (the 0.9 style esmini and the ASAM OpenSCENARIO API accept) declares X: a warning with
 * the name without `$` as its fix (SPEC 12).
 */
export const dollarDeclarations: SemanticCheck = ({ model }) =>
  model.declarations
    .filter(
      (declaration) => declaration.kind === 'parameter' && declaration.nameAttribute?.value.trim().startsWith('$') && declaration.name,
    )
    .map((declaration) => {
      const attr = declaration.nameAttribute as XmlAttribute;
      const exact = attr.value.length === attr.valueEnd - attr.valueStart;
      const leading = attr.value.length - attr.value.trimStart().length;
      const start = exact ? attr.valueStart + leading : attr.valueStart;
      const end = exact ? start + attr.value.trim().length : attr.valueEnd;
      return {
        element: declaration.element,
        attribute: attr,
        start,
        end,
        ...dollarDeclarationWording(declaration.name),
        data: { suggestion: declaration.name },
      };
    });

/** The declarations of a file that its referenced catalog entries use without declaring them (esmini takes them from the reference's scope). */
function usedByCatalogEntries({ model, catalogs }: SemanticContext): Set<Declaration> {
  const used = new Set<Declaration>();
  const freeByEntry = new Map<XmlElement, Set<string>>();
  for (const resolution of catalogs.references) {
    if (!resolution.entry) continue;
    let free = freeByEntry.get(resolution.entry.element);
    if (!free) freeByEntry.set(resolution.entry.element, (free = entryFreeParameters(resolution)));
    if (free.size === 0) continue;
    const scope = model.scopeOf(resolution.reference.element);
    for (const name of free) {
      const declaration = resolveName(scope, name, undefined);
      if (declaration) used.add(declaration);
    }
  }
  return used;
}

/** A declared parameter that nothing uses (a hint, shown faded): neither the file nor a catalog entry it references that takes it undeclared. */
export const unusedParameters: SemanticCheck = (context) => {
  const { model } = context;
  const unused = model.declarations
    .filter((declaration) => declaration.kind === 'parameter' && declaration.name && (model.usesOf.get(declaration)?.length ?? 0) === 0)
    .filter((declaration) => declaration.scope.byName.get(declaration.name) === declaration);
  if (unused.length === 0) return [];
  const usedByEntries = usedByCatalogEntries(context);
  return unused
    .filter((declaration) => !usedByEntries.has(declaration))
    .map((declaration) => ({
      ...at(declaration.element, declaration.nameAttribute),
      ...unusedParameterWording(declaration.name),
    }));
};

/** Two declarations of one name in one scope. */
export const duplicateDeclarations: SemanticCheck = (context) => {
  const findings: Finding[] = [];
  for (const scope of context.model.scopes) {
    for (const declaration of scope.declarations) {
      const first = scope.byName.get(declaration.name) as Declaration;
      if (first === declaration) continue;
      const last = scope.declarations.filter((each) => each.name === declaration.name).at(-1) as Declaration;
      const valueOf = (each: Declaration) => attribute(each.element, 'value')?.value ?? '';
      findings.push({
        ...at(declaration.element, declaration.nameAttribute),
        ...duplicateParameterWording(
          declaration.name,
          scope.element.name,
          context.simulator === 'esmini' ? { first: valueOf(first), last: valueOf(last) } : undefined,
        ),
        related: [relatedAt(context, first.element.start, first.element.nameEnd, DUPLICATE_PARAMETER_FIRST_NOTE)],
      });
    }
  }
  return findings;
};

/** A catalog entry's parameter declared with an empty value of a type that has no empty value: it has no default (ASAM QC valid_parameter_declaration_in_catalogs.py:66-78, 94-98). */
function isEmptyCatalogDefault(element: XmlElement, error: ExpressionError): boolean {
  if (error.kind !== 'type-mismatch' || error.fact !== 'declared-value' || error.mismatch.fact !== 'not-of-type') return false;
  if (error.mismatch.text.trim() !== '') return false;
  for (let parent = element.parent; parent; parent = parent.parent) if (parent.name === 'Catalog') return true;
  return false;
}

function expressionFinding(context: SemanticContext, element: XmlElement, attr: XmlAttribute, error: ExpressionError): Finding | undefined {
  // An unknown parameter is reported once by undeclaredParameters, or at the declaration that has no valid value.
  if (error.kind === 'unknown-parameter') return undefined;
  const exactOffsets = attr.value.length === attr.valueEnd - attr.valueStart;
  const start = exactOffsets ? error.start : attr.valueStart;
  const end = exactOffsets ? Math.max(error.end, error.start + 1) : attr.valueEnd;
  const finding: Finding = {
    element,
    attribute: attr,
    start,
    end,
    ...expressionWording(error),
  };
  const token = error.kind === 'syntax' ? nonstandardToken(error) : undefined;
  if (token !== undefined) finding.subject = { element: element.name, attribute: attr.name, token };
  else if (isEmptyCatalogDefault(element, error)) finding.subject = { element: element.name, attribute: attr.name, noCatalogDefault: true };
  const fix = error.fix;
  if (fix && fix.start === start && fix.end === end) {
    finding.data = { suggestion: fix.text };
    finding.hint = writeStandardHint(fix.text);
  } else if (fix) {
    // The standard's form is written elsewhere (a string parameter's parameterType).
    const { hint, note } = retypeWords(fix.text);
    finding.related = [relatedAt(context, fix.start, fix.end, note)];
    finding.data = { relatedReplacement: fix.text };
    finding.hint = hint;
  }
  return finding;
}

/** The errors of a site's value that findings are made of. */
function siteErrors(evaluator: Evaluator, site: SemanticModel['sites'][number]): ExpressionError[] {
  if (site.form.kind !== 'expression') return NO_ERRORS;
  const result = evaluator.evaluateSite(site);
  const errors = [...(result.ok ? [] : result.errors), ...(result.warnings ?? [])].filter((error) => error.kind !== 'unknown-parameter');
  return errors.length > 0 ? errors : NO_ERRORS;
}

/** The errors of a declaration's own value that findings are made of (its warnings, then a type mismatch of the value itself). */
function declarationErrors(evaluator: Evaluator, declaration: Declaration): ExpressionError[] {
  const attr = declaration.valueAttribute;
  if (!attr || declaration.type === undefined) return NO_ERRORS;
  const errors: ExpressionError[] = evaluator.declarationWarnings(declaration).filter((warning) => warning.kind !== 'unknown-parameter');
  const result = evaluator.declarationValue(declaration);
  if (!result.ok && result.provenance.kind === 'declaration') {
    // Errors inside the expression itself were reported at the site, with their column.
    errors.push(
      ...result.errors.filter((error) => error.start === attr.valueStart && error.end === attr.valueEnd && error.kind === 'type-mismatch'),
    );
  }
  return errors.length > 0 ? errors : NO_ERRORS;
}

const NO_ERRORS: ExpressionError[] = [];

/**
 * Syntax, type and division errors of every `${...}`, and values that do not fit their declared type.
 * After an edit inside one value, the errors of values the edit cannot change carry over (checks/carriedResults.ts).
 */
export const expressionErrors: SemanticCheck = (context) => {
  const { model, evaluator } = context;
  // A catalog entry's evaluator with assignments computes other values than the model's own.
  const remembered = evaluator.model === model && evaluator.assignments === undefined;
  const carried = remembered ? carriedExpressionErrors(model, evaluator) : undefined;
  const sites = model.sites.map((site, index) => carried?.site(index) ?? siteErrors(evaluator, site));
  const declarations = model.declarations.map(
    (declaration, index) => carried?.declaration(index) ?? declarationErrors(evaluator, declaration),
  );
  if (remembered) rememberExpressionErrors(model, evaluator, { sites, declarations });
  const findings: Finding[] = [];
  model.sites.forEach((site, index) => {
    for (const error of sites[index]) findings.push(expressionFinding(context, site.element, site.attribute, error) as Finding);
  });
  model.declarations.forEach((declaration, index) => {
    for (const error of declarations[index])
      findings.push(expressionFinding(context, declaration.element, declaration.valueAttribute as XmlAttribute, error) as Finding);
  });
  return findings;
};

/**
 * The catalog kinds (`CatalogLocations` children) a CatalogReference may be found in, by where it stands
 * (ASAM OpenSCENARIO 1.x: a ScenarioObject's entity is a Vehicle, Pedestrian or MiscObject; an
 * ObjectController's a Controller; and so on). Undefined where the place does not tell.
 */
const CATALOG_KINDS_BY_PARENT: Readonly<Record<string, readonly string[]>> = {
  ScenarioObject: ['VehicleCatalog', 'PedestrianCatalog', 'MiscObjectCatalog'],
  EntityObject: ['VehicleCatalog', 'PedestrianCatalog', 'MiscObjectCatalog'],
  CentralSwarmObject: ['VehicleCatalog', 'PedestrianCatalog', 'MiscObjectCatalog'],
  ObjectController: ['ControllerCatalog'],
  AssignControllerAction: ['ControllerCatalog'],
  ManeuverGroup: ['ManeuverCatalog'],
  EnvironmentAction: ['EnvironmentCatalog'],
  AssignRouteAction: ['RouteCatalog'],
  RoutingAction: ['RouteCatalog'],
  FollowTrajectoryAction: ['TrajectoryCatalog'],
  TrajectoryRef: ['TrajectoryCatalog'],
};

/** A reference resolved in the catalog file esmini reads (`fileNameMismatch.esminiReads`) instead of the standard's. */
function readByEsmini(resolution: CatalogReferenceResolution, file: CatalogFile): CatalogReferenceResolution {
  const entry = file.entries.find((candidate) => candidate.name === resolution.entryName);
  return { ...resolution, catalogs: [file], entry, shadowedEntry: undefined, foundByFileName: false };
}

/**
 * Unknown catalogs, entries and assigned parameters; directories that do not exist where a reference
 * needs them: a catalog kind with a reference that found no catalog. A directory no reference needs is
 * harmless (CARLA and esmini load such files; a generator writes every kind, some empty or unused).
 */
export const catalogReferences: SemanticCheck = (context) => {
  const findings: Finding[] = [];
  const neededKinds = new Set<string>();
  let anyKindNeeded = false;
  for (const resolution of context.catalogs.references) {
    if (resolution.catalogName === undefined || resolution.catalogs.length > 0) continue;
    const kinds = CATALOG_KINDS_BY_PARENT[resolution.reference.element.parent?.name ?? ''];
    if (kinds) for (const kind of kinds) neededKinds.add(kind);
    else anyKindNeeded = true;
  }
  // Kinds whose directory is missing beside the file: their references' unknown catalogs are that one problem.
  const missingKinds = new Set<string>();
  const missing: LocationResolution[] = [];
  for (const location of context.catalogs.locations) {
    if (!anyKindNeeded && !neededKinds.has(location.location.kind)) continue;
    // Found beside the file: the catalog is missing from it, which the references say. Otherwise the directory is
    // missing, though SCENARIO_PATH folders may stand for it (esmini searches them, and each folder itself).
    if (location.path === undefined || location.directories.some((directory) => directory.via === 'file')) continue;
    missingKinds.add(location.location.kind);
    missing.push(location);
  }
  // Directories missing because one folder of their paths is (a Catalogs/ folder left behind): one problem for the folder.
  const byFolder = new Map<string, LocationResolution[]>();
  for (const location of missing) {
    const key = location.missingFolder?.folder ?? `\0${byFolder.size}`;
    byFolder.set(key, [...(byFolder.get(key) ?? []), location]);
  }
  for (const group of byFolder.values()) {
    const [first, ...others] = group;
    const searched = [...new Set(group.flatMap((location) => location.directories.map((directory) => directory.directory)))];
    const kinds = [...new Set(group.map((location) => location.location.kind))];
    findings.push({
      ...at(first.location.directory, first.location.pathAttribute),
      ...(kinds.length > 1 && first.missingFolder
        ? catalogFolderWording(
            first.missingFolder.written,
            kinds,
            group.every((location) => location.missingFolder?.written === location.path?.trim().replace(/\\/g, '/')),
            searched,
          )
        : catalogDirectoryWording(first.location.kind, first.path as string, searched)),
      ...(others.length > 0
        ? {
            related: others.map((location) => {
              const place = at(location.location.directory, location.location.pathAttribute);
              return relatedAt(context, place.start, place.end, `${CATALOG_FOLDER_ALSO_NOTE}: the ${location.location.kind} directory`);
            }),
          }
        : {}),
    });
  }
  for (const resolution of context.catalogs.references) {
    const { reference } = resolution;
    if (!resolution.searched || resolution.catalogName === undefined) continue;
    if (resolution.catalogs.length === 0) {
      const kinds = CATALOG_KINDS_BY_PARENT[reference.element.parent?.name ?? ''];
      if (kinds ? kinds.some((kind) => missingKinds.has(kind)) : missingKinds.size > 0) continue;
      findings.push({
        ...at(reference.element, reference.catalogNameAttribute),
        ...unknownCatalogWording(
          resolution.catalogName,
          context.catalogs.locations.flatMap((location) => location.directories.map((directory) => directory.directory)),
        ),
      });
      continue;
    }
    const esminiReads = resolution.fileNameMismatch?.esminiReads;
    if (resolution.fileNameMismatch) {
      findings.push({
        ...at(reference.element, reference.catalogNameAttribute),
        ...catalogFileNameWording(
          resolution.catalogName,
          displayRef(resolution.catalogs[0].ref, undefined),
          esminiReads && { file: displayRef(esminiReads.ref, undefined), catalog: esminiReads.name },
          // esmini stops only where it finds no file of the name; one it reads instead may well hold the entry.
          context.simulator === 'esmini' && !esminiReads ? 'error' : 'warning',
        ),
      });
    }
    // For esmini, the entries are those of the file it reads.
    const checked = context.simulator === 'esmini' && esminiReads ? readByEsmini(resolution, esminiReads) : resolution;
    if (!checked.entry) {
      // The catalog is the file esmini loads (core/semantics/catalogs.ts loadedFirst): its entries alone are there to name.
      const loaded = checked.catalogs[0];
      const names = loaded.entries.map((entry) => entry.name);
      const suggestion = checked.entryName ? closestMatch(checked.entryName, names) : undefined;
      const shadowed = checked.shadowedEntry;
      findings.push({
        ...at(reference.element, reference.entryNameAttribute),
        ...unknownCatalogEntryWording(
          resolution.catalogName,
          displayRef(loaded.ref, undefined),
          checked.entryName ?? '',
          names,
          suggestion,
          shadowed && { holder: displayRef(shadowed.file.ref, undefined) },
        ),
        data: suggestion ? { suggestion } : undefined,
        ...(shadowed
          ? {
              related: [
                {
                  source: shadowed.file.ref,
                  range: shadowed.file.model.document.lines.range(shadowed.element.start, shadowed.element.nameEnd),
                  message: SHADOWED_ENTRY_NOTE,
                },
              ],
            }
          : {}),
      });
      continue;
    }
    if (checked.foundByFileName) {
      findings.push({
        ...at(reference.element, reference.catalogNameAttribute),
        ...catalogFoundByFileNameWording(resolution.catalogName, checked.catalogs[0].name),
      });
    }
    const entryModel = checked.entry.file.model;
    const referenceScope = context.model.scopeOf(reference.element);
    for (const name of entryFreeParameters(checked)) {
      if (resolveName(referenceScope, name, undefined)) continue;
      findings.push({
        ...at(reference.element, reference.entryNameAttribute),
        ...undeclaredParameterWording(name, checked.entry.name),
        data: { parameter: name },
      });
    }
    const entryScope = entryModel.scopeOf(checked.entry.element);
    const declared =
      entryScope && entryScope.element === checked.entry.element ? entryScope.declarations.map((declaration) => declaration.name) : [];
    for (const assignment of reference.assignments) {
      const name = assignment.parameterRef ? referencedName(assignment.parameterRef).name : undefined;
      if (name === undefined || declared.includes(name)) continue;
      const suggestion = closestMatch(name, declared);
      findings.push({
        ...at(assignment.element, assignment.parameterRef),
        ...unknownAssignedParameterWording(checked.entry.name, name, declared, suggestion),
        data: suggestion ? { suggestion } : undefined,
      });
    }
  }
  return findings;
};

const DOLLAR = 36;

/**
 * A model's entity references (a value edit leaving them alone keeps the list, incremental.ts) that are all
 * written without `$` and declared: the names they use, so the check skips the list while those stay declared.
 */
const declaredEntityReferences = coreMemo<readonly { element: XmlElement; attribute: XmlAttribute }[], readonly string[]>(
  'declaredEntityReferences',
);

/** Entity names, with `$parameters` evaluated; only in files that declare Entities (not in catalogs). */
export const undeclaredEntities: SemanticCheck = ({ model, evaluator }) => {
  if (!model.hasEntities || model.catalog || !model.document.root) return [];
  const names = new Set(model.entities.map((entity) => evaluator.textOf(entity.element, entity.nameAttribute) ?? entity.name));
  const known = declaredEntityReferences.get(model.entityReferences);
  if (known && known.every((name) => names.has(name))) return [];
  const findings: Finding[] = [];
  // The names written without `$`, each once, while every reference is one of them and declared.
  let literals: Set<string> | undefined = new Set();
  for (const { element, attribute: attr } of model.entityReferences) {
    if (attr.value.charCodeAt(0) === DOLLAR) literals = undefined;
    const value = evaluator.textOf(element, attr);
    if (value !== undefined) literals?.add(value);
    if (value === undefined || names.has(value)) continue;
    literals = undefined;
    const suggestion = names.size <= 2000 ? closestMatch(value, names) : undefined;
    findings.push({
      ...at(element, attr),
      ...undeclaredEntityWording(value, attr.value, suggestion),
      data: { entity: value },
    });
  }
  if (literals && model.entityReferences.length > 0) declaredEntityReferences.set(model.entityReferences, [...literals]);
  return findings;
};

/** The storyboard elements a reference may name (an optional `A::B::` prefix names ancestors). */
export function storyboardTargets(
  model: SemanticModel,
  extra: { name: string; element: XmlElement }[],
  written: string,
  type: string | undefined,
): XmlElement[] {
  const parts = written.split('::').map((part) => part.trim());
  const name = parts.pop() ?? '';
  const elementName = type ? STORYBOARD_ELEMENT_TYPES[type] : undefined;
  const candidates = [...(model.storyboardByName.get(name) ?? []), ...extra.filter((candidate) => candidate.name === name)].filter(
    (candidate) => !elementName || candidate.element.name === elementName,
  );
  if (parts.length === 0) return candidates.map((candidate) => candidate.element);
  return candidates
    .filter((candidate) => {
      let index = parts.length - 1;
      for (let current = candidate.element.parent; current && index >= 0; current = current.parent) {
        if (attribute(current, 'name')?.value === parts[index]) index--;
      }
      return index < 0;
    })
    .map((candidate) => candidate.element);
}

/** Names a reference may reach in maneuvers taken from catalogs. */
function catalogStoryboardNames(context: SemanticContext): { name: string; element: XmlElement }[] {
  const result: { name: string; element: XmlElement }[] = [];
  for (const resolution of context.catalogs.references) {
    const entry = resolution.entry?.element;
    if (!entry || entry.name !== 'Maneuver') continue;
    for (const element of [entry, ...descendants(entry)]) {
      if (STORYBOARD_ELEMENT_NAMES.has(element.name)) result.push({ name: attribute(element, 'name')?.value ?? '', element });
    }
  }
  return result;
}

/** Every StoryboardElementStateCondition names an element of its type that exists. */
export const storyboardReferences: SemanticCheck = (context) => {
  if (context.modular || context.model.catalog) return [];
  const unresolvedCatalogManeuvers = context.catalogs.references.some(
    (resolution) => !resolution.entry && resolution.reference.element.parent?.name === 'ManeuverGroup',
  );
  if (unresolvedCatalogManeuvers) return [];
  const extra = catalogStoryboardNames(context);
  const findings: Finding[] = [];
  for (const reference of context.model.storyboardReferences) {
    const written = context.evaluator.textOf(reference.element, reference.refAttribute);
    const type = context.evaluator.textOf(reference.element, attribute(reference.element, 'storyboardElementType'));
    if (written === undefined || storyboardTargets(context.model, extra, written, type).length > 0) continue;
    const elementName = type ? STORYBOARD_ELEMENT_TYPES[type] : undefined;
    const known = context.model.storyboardElements
      .filter((candidate) => !elementName || candidate.element.name === elementName)
      .map((candidate) => candidate.name);
    const suggestion = known.length <= 2000 ? closestMatch(written, known) : undefined;
    findings.push({
      ...at(reference.element, reference.refAttribute),
      // A warning in a file of its own: a simple scenario may name an element of the main it is composed into; the flattened output's check (below) makes it an error where it still names nothing.
      ...unknownStoryboardElementWording(written, elementName, suggestion, false),
      data: suggestion ? { suggestion } : undefined,
    });
  }
  return findings;
};

/**
 * In a flattened output every storyboard reference names exactly one element. A name that only
 * exists as `OUTER.NAME` names a group that flattening renamed: an error, since the output no longer
 * has what the reference was written for.
 */
export const flattenedStoryboardReferences: SemanticCheck = (context) => {
  const extra = catalogStoryboardNames(context);
  const findings: Finding[] = [];
  for (const reference of context.model.storyboardReferences) {
    const written = context.evaluator.textOf(reference.element, reference.refAttribute);
    const type = context.evaluator.textOf(reference.element, attribute(reference.element, 'storyboardElementType'));
    if (written === undefined) continue;
    const targets = storyboardTargets(context.model, extra, written, type);
    if (targets.length === 1) continue;
    const elementName = type ? STORYBOARD_ELEMENT_TYPES[type] : undefined;
    if (targets.length > 1) {
      findings.push({
        ...at(reference.element, reference.refAttribute),
        ...ambiguousReferenceWording(targets.length, written, elementName),
      });
      continue;
    }
    // An outer group OUTER became OUTER.INNER, and an imported group INNER became OUTER.INNER.
    const renamed = context.model.storyboardElements
      .filter(
        (candidate) =>
          (candidate.name.endsWith(`.${written}`) || candidate.name.startsWith(`${written}.`)) &&
          (!elementName || candidate.element.name === elementName),
      )
      .map((candidate) => candidate.name);
    if (renamed.length > 0) {
      findings.push({
        ...at(reference.element, reference.refAttribute),
        ...renamedReferenceWording(written, renamed),
        data: renamed.length === 1 ? { suggestion: renamed[0] } : undefined,
      });
      continue;
    }
    findings.push({
      ...at(reference.element, reference.refAttribute),
      ...unknownStoryboardElementWording(written, elementName, undefined, true),
    });
  }
  return findings;
};

/** A simulator profile's finding, with its one-edit suggestion and whether the export maps it. */
function profileFinding(finding: SimulatorFinding): Finding {
  return {
    ...at(finding.element, finding.attribute),
    ...simulatorWording(finding),
    ...(finding.suggestion !== undefined || finding.exportMaps
      ? { data: { suggestion: finding.suggestion, exportMaps: finding.exportMaps } }
      : {}),
  };
}

/**
 * What the chosen simulator does not run, from facts read in its own sources (core/profiles/). What a catalog
 * entry holds is reported on each CatalogReference that uses the entry, as the catalog problems are: the simulator
 * reads an entry only there.
 */
export const simulatorProfile: SemanticCheck = (context) => {
  const simulator = context.simulator ?? 'asam';
  const release = carlaReleaseOf(context);
  const own = simulatorFindings(simulator, context.model.document, baseName(context.ref), release).map(profileFinding);
  const inEntries = onCatalogReferences(context, (entry) =>
    entryFindings(simulator, entry.file.model.document, baseName(entry.file.ref), entry.element, release).map(profileFinding),
  );
  return [...own, ...inEntries];
};

/** The checks of a document, in the order their problems are listed. */
export const SEMANTIC_CHECKS: readonly { name: string; check: SemanticCheck }[] = [
  { name: 'undeclared parameter', check: undeclaredParameters },
  { name: 'unused parameter', check: unusedParameters },
  { name: 'parameter declared with $', check: dollarDeclarations },
  { name: 'parameter declared twice', check: duplicateDeclarations },
  { name: 'expression errors', check: expressionErrors },
  { name: 'catalog references', check: catalogReferences },
  { name: 'undeclared entity', check: undeclaredEntities },
  { name: 'storyboard references', check: storyboardReferences },
  { name: 'undeclared variable', check: undeclaredVariables },
  { name: 'variable values', check: variableValues },
  { name: 'variables of catalog entries', check: catalogVariables },
  { name: 'names unique on each level', check: duplicateNames },
  { name: 'value constraints', check: valueConstraints },
  { name: 'simulator profile', check: simulatorProfile },
  { name: 'CARLA ScenarioRunner', check: carlaScenario },
  { name: 'esmini', check: esminiScenario },
  // The road file, traffic signals, actors and value ranges (./networkChecks.ts).
  { name: 'road file', check: roadFileFound },
  { name: 'traffic signal id', check: trafficSignalIds },
  { name: 'traffic signal controller', check: trafficSignalControllerRefs },
  { name: 'private action actors', check: privateActionActors },
  { name: 'light transition time', check: lightTransitionTimes },
  { name: 'phase duration', check: phaseDurations },
  { name: 'value ranges', check: valueRanges },
];

/**
 * The checks of SEMANTIC_CHECKS whose findings for esmini carry the code `simulator` (its profile, its own rules, the actors
 * it refuses): run again in esmini's context over semantics read for another simulator, they give what an analysis for
 * esmini gives of that code (`core/flatten/esminiFindings.ts`).
 */
export const ESMINI_FINDING_CHECKS: readonly { name: string; check: SemanticCheck }[] = SEMANTIC_CHECKS.filter((entry) =>
  ['simulator profile', 'esmini', 'private action actors'].includes(entry.name),
);

/** The checks of a flattened output (SPEC 11.5); entities are checked by the flattener at the reference. */
export const OUTPUT_CHECKS: readonly { name: string; check: SemanticCheck }[] = [
  { name: 'undeclared parameter', check: undeclaredParameters },
  { name: 'expression errors', check: expressionErrors },
  { name: 'catalog references', check: catalogReferences },
  { name: 'storyboard references', check: flattenedStoryboardReferences },
  { name: 'undeclared variable', check: undeclaredVariables },
  // What the simulator gets is the output: a value set through a ParameterReference is checked here.
  { name: 'simulator profile', check: simulatorProfile },
  { name: 'CARLA ScenarioRunner', check: carlaScenario },
  { name: 'esmini', check: esminiScenario },
];

export { undeclaredVariables };

export function runChecks(context: SemanticContext, checks: readonly { check: SemanticCheck }[] = SEMANTIC_CHECKS): Finding[] {
  return checks.flatMap((entry) => entry.check(context));
}
