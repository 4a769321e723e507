import { ExpressionError } from '../expressionParser';
import { Evaluator } from '../evaluator';
import { ModelCarry, takeModelCarry } from '../incremental';
import { SemanticModel } from '../types';
import { coreMemo } from '../../memos';

/**
 * The expression errors of one model in one reading, before they are placed: per site and per
 * declaration (by index), the errors a finding is made of. Kept so that the next model, carried over
 * an in-value edit, evaluates only what the edit can change.
 */
export interface ExpressionErrorResults {
  sites: readonly ExpressionError[][];
  declarations: readonly ExpressionError[][];
}

const results = coreMemo<SemanticModel, Map<Evaluator['reading'], ExpressionErrorResults>>('expressionErrors');

/** The results of the previous model, moved to this one: undefined where the edit may change them. */
export interface CarriedResults {
  site(index: number): ExpressionError[] | undefined;
  declaration(index: number): ExpressionError[] | undefined;
}

/** Above this many changed names, every value may depend on one: everything is evaluated again. */
const MAX_CHANGED_NAMES = 64;

const WORD = /[A-Za-z0-9_]/;

/** A `$` that no name character follows: esmini reads it as the parameter named '' (a declaration may have that name). */
const BARE_DOLLAR = /\$(?![A-Za-z0-9_])/;

/** Whether `text` names one of `names` (not followed by a name character, as both readings end a name). */
function mentions(text: string, names: ReadonlySet<string>): boolean {
  if (!text.includes('$')) return false;
  for (const name of names) {
    if (name === '') {
      if (BARE_DOLLAR.test(text)) return true;
      continue;
    }
    for (let at = text.indexOf(name); at >= 0; at = text.indexOf(name, at + 1)) {
      if (at + name.length >= text.length || !WORD.test(text[at + name.length])) return true;
    }
  }
  return false;
}

function shifted(errors: ExpressionError[], carry: ModelCarry): ExpressionError[] {
  const move = (offset: number) => (offset >= carry.removedEnd ? offset + carry.delta : offset);
  return errors.map((error) => {
    const moved: ExpressionError = { ...error, start: move(error.start), end: move(error.end) };
    if (error.fix) moved.fix = { ...error.fix, start: move(error.fix.start), end: move(error.fix.end) };
    return moved;
  });
}

/**
 * The results that carry over to `model` from the model it was carried from. An edit inside one value
 * changes that value's own sites and the value of its declaration; what depends on a changed value
 * names it (the standard's and esmini's lookups both go by name), so a value naming none of the
 * changed names, transitively, keeps its errors.
 */
export function carriedExpressionErrors(model: SemanticModel, evaluator: Evaluator): CarriedResults | undefined {
  const carry = takeModelCarry(model);
  const previous = carry && results.get(carry.previous)?.get(evaluator.reading);
  if (!carry || !previous) return undefined;
  const changed = new Set<string>();
  for (const declaration of carry.editedDeclarations) changed.add(declaration.name);
  const dependent = (text: string | undefined) => text !== undefined && changed.size > 0 && mentions(text, changed);
  const changedDeclarations = new Set(carry.editedDeclarations);
  for (let grown = changed.size > 0; grown;) {
    grown = false;
    for (const declaration of model.declarations) {
      if (changedDeclarations.has(declaration) || !dependent(declaration.valueAttribute?.value)) continue;
      changedDeclarations.add(declaration);
      if (!changed.has(declaration.name)) {
        changed.add(declaration.name);
        grown = true;
      }
    }
    if (changed.size > MAX_CHANGED_NAMES) return undefined;
  }
  return {
    site(index) {
      const origin = carry.siteOrigins[index];
      if (origin === undefined || dependent(model.sites[index].attribute.value)) return undefined;
      const errors = previous.sites[origin];
      return errors && (errors.length === 0 ? errors : shifted(errors, carry));
    },
    declaration(index) {
      if (changedDeclarations.has(model.declarations[index])) return undefined;
      const errors = previous.declarations[index];
      return errors && (errors.length === 0 ? errors : shifted(errors, carry));
    },
  };
}

/** Remembers a model's results for the model the next in-value edit carries from it. */
export function rememberExpressionErrors(model: SemanticModel, evaluator: Evaluator, found: ExpressionErrorResults): void {
  let byReading = results.get(model);
  if (!byReading) results.set(model, (byReading = new Map()));
  byReading.set(evaluator.reading, found);
}
