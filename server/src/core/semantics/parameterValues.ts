import { expressionWording } from '../diagnostics/expressionWords';
import { differenceMatters } from '../diagnostics/simulatorValue';
import { parameterDeclaredNote, parameterSiteWording, ValueMismatch } from '../diagnostics/typeMismatch';
import { Problem } from '../problems';
import { SchemaIndex, schemaIndex } from '../schema/index';
import { SimpleType } from '../schema/model';
import { typeOfElement } from '../schema/query';
import { builtinOf, checkValue, describeType } from '../schema/values';
import { chooseVersion, SchemaVersionSetting } from '../schema/version';
import { XmlElement } from '../xml';
import type { DocumentSemantics } from './index';
import { resolveName, ValueSite } from './model';
import { convertValue, formatValue, ParameterType } from './values';

/*
 * A parameter's value against the type of every attribute that uses it (`s="$HostVehicle"` with a string
 * parameter `car_white` in a double attribute): the schema only sees `$HostVehicle`, which every
 * parameterisable type admits. SPEC 12: a value that cannot be converted is an error at the use; a numeric
 * string in a number attribute converts; a number with a fraction of zero for an integer is a warning.
 */

/** The type of an attribute as the schema declares it; undefined where the schema does not place the element. */
export function attributeType(
  index: SchemaIndex,
  element: XmlElement,
  attributeName: string,
): { name: string; type: SimpleType } | undefined {
  const typeName = typeOfElement(index, element);
  const declaration = typeName ? index.attribute(typeName, attributeName) : undefined;
  const type = declaration ? index.simpleType(declaration.type) : undefined;
  return declaration && type ? { name: declaration.type, type } : undefined;
}

/** The builtin type a parameter's value must convert to for an attribute; undefined for text, enumerations and patterns. */
function targetOf(type: SimpleType): ParameterType | undefined {
  const builtin = builtinOf(type);
  return builtin === 'string' ? undefined : builtin;
}

const INTEGER_TYPES: ReadonlySet<ParameterType> = new Set<ParameterType>(['int', 'unsignedInt', 'unsignedShort']);

/** `-5.0` for an integer: one clear meaning (esmini reads -5), which the standard's integer does not admit. */
function wholeNumberText(text: string): number | undefined {
  const trimmed = text.trim();
  if (!/^[+-]?\d+\.0*$/.test(trimmed)) return undefined;
  return Number(trimmed);
}

/** Whether a parameter's value fits the attribute's type; what is wrong when it does not. */
function mismatchOf(
  value: { value: string | number | boolean; type: ParameterType },
  attributeTypeName: string,
  type: SimpleType,
): ValueMismatch | undefined {
  const target = targetOf(type);
  if (target) {
    // Checked first: the lenient reading converts `5.0` to an integer, which is still a warning here.
    const whole = typeof value.value === 'string' && INTEGER_TYPES.has(target) ? wholeNumberText(value.value) : undefined;
    if (whole !== undefined && !('mismatch' in convertValue({ value: String(whole), type: 'string' }, target))) {
      return { kind: 'fraction', target, whole };
    }
    if (!('mismatch' in convertValue(value, target))) return undefined;
    return { kind: 'conversion', target };
  }
  // Text, an enumeration or a pattern: the value's text must be one the type admits itself.
  const literalOnly: SimpleType = { ...type, parameter: false, expression: false };
  if (checkValue(literalOnly, formatValue(value.value)).valid) return undefined;
  return { kind: 'text', type: attributeTypeName, expected: describeType(literalOnly) };
}

/** Whether a parameter's value converts to an attribute's type without a word (completion offers such parameters first). */
export function valueFits(
  value: { value: string | number | boolean; type: ParameterType },
  attribute: { name: string; type: SimpleType },
): boolean {
  return mismatchOf(value, attribute.name, attribute.type) === undefined;
}

/**
 * The problem of a `$name` site whose value does not fit an attribute's type, at the site, naming the
 * declaration; `attributeName` is how the message names the attribute (`LanePosition.s`); `setBy` the
 * ParameterReference that sets the attribute to the parameter, where an override does.
 */
export function siteTypeProblem(
  semantics: DocumentSemantics,
  site: ValueSite,
  target: { name: string; type: SimpleType },
  attributeName: string,
  setBy?: string,
): Problem | undefined {
  if (site.form.kind !== 'parameter') return undefined;
  const declaration = resolveName(site.scope, site.form.name, site.declaration);
  if (!declaration) return undefined;
  // A value that cannot be evaluated is reported at its declaration already.
  const result = semantics.evaluator.evaluateSite(site);
  if (!result.ok) return undefined;
  const mismatch = mismatchOf({ value: result.value, type: result.type }, target.name, target.type);
  if (!mismatch) return undefined;
  const document = semantics.model.document;
  const place = declaration.valueAttribute ?? declaration.nameAttribute;
  return {
    source: semantics.ref,
    range: document.lines.range(site.attribute.valueStart, site.attribute.valueEnd),
    ...parameterSiteWording({
      value: formatValue(result.value),
      parameter: declaration.name,
      writtenType: declaration.writtenType,
      mismatch,
      attribute: attributeName,
      setBy,
    }),
    related: [
      {
        source: semantics.ref,
        range: place
          ? document.lines.range(place.valueStart, place.valueEnd)
          : document.lines.range(declaration.element.start, declaration.element.nameEnd),
        message: parameterDeclaredNote(declaration.name, declaration.value),
      },
    ],
  };
}

/**
 * esmini's six-decimal rounding of a double that an integer attribute reads (laneId="${$Third * 3}": the standard's 1,
 * esmini's 0.999999, which its atoi() makes 0), at the attribute: the evaluator, which knows no attribute's schema type, judged
 * the difference as a quantity's and let it pass (simulatorValue.ts differenceMatters).
 */
function integerReadProblem(semantics: DocumentSemantics, site: ValueSite, target: { type: SimpleType }): Problem | undefined {
  const builtin = targetOf(target.type);
  if (!builtin || !INTEGER_TYPES.has(builtin)) return undefined;
  const result = semantics.evaluator.evaluateSite(site);
  if (!result.ok || !result.differs) return undefined;
  const standard = Number(result.differs.standard);
  const esmini = Number(result.differs.esmini);
  if (!Number.isInteger(standard) || Math.trunc(esmini) === standard || differenceMatters(standard, esmini, false)) return undefined;
  return {
    source: semantics.ref,
    range: semantics.model.document.lines.range(site.attribute.valueStart, site.attribute.valueEnd),
    ...expressionWording({ kind: 'simulator', fact: 'differs', difference: result.differs }),
  };
}

/**
 * Every `$name` that is an attribute's whole value, checked against that attribute's type in the schema
 * of the file's version: an error (or, for `5.0` in an integer, a warning) at the use, naming the declaration.
 */
export function parameterValueProblems(semantics: DocumentSemantics, setting: SchemaVersionSetting): Problem[] {
  const document = semantics.model.document;
  if (!document.root) return [];
  const index = schemaIndex(chooseVersion(document, setting).version);
  const problems: Problem[] = [];
  for (const site of semantics.model.sites) {
    // A declaration's own value is text to the schema; its type is checked against its parameterType.
    if (site.declaration || site.element.name === 'ParameterDeclaration') continue;
    const target = attributeType(index, site.element, site.attribute.name);
    if (!target) continue;
    const rounded = integerReadProblem(semantics, site, target);
    if (rounded) problems.push(rounded);
    if (site.form.kind !== 'parameter') continue;
    const problem = siteTypeProblem(semantics, site, target, `${site.element.name}.${site.attribute.name}`);
    if (problem) problems.push(problem);
  }
  return problems;
}
