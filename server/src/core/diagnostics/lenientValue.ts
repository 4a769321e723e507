import { ProblemDataByCode } from '../problems';
import { defineDiagnostic, isRelatedReplacement, isSuggestion, ProblemWording } from './definition';
import { LenientFact } from './expressionFacts';
import { unknownNameWords } from './expressionSyntax';
import { esminiRule } from './simulatorValue';
import { expressionTypeMessage } from './typeMismatch';

/** The message of a form esmini accepts with one clear meaning, found in an expression or a declared value. */
export function lenientValueMessage(fact: LenientFact): string {
  switch (fact.fact) {
    case 'string-parameter':
      return `'${fact.name}' is a string parameter: the standard allows no string in an expression; esmini and the ASAM OpenSCENARIO API read its text ${JSON.stringify(fact.value)} as the ${fact.type} ${fact.read}`;
    case 'bare-parameter':
      return `'${fact.name}' is the parameter $${fact.name} written without '$': the standard names parameters in expressions only as $${fact.name}; esmini reads the bare word as text`;
    case 'integral-fraction':
      return `'${fact.text}' is not an ${fact.type} by the standard (no fraction is allowed, not even .0); esmini reads it as ${fact.standard}`;
    case 'glued-text': {
      const cause = fact.cause.kind === 'syntax' ? unknownNameWords(fact.cause.name) : expressionTypeMessage(fact.cause);
      return `the standard has no text in expressions (${cause}); ${esminiRule('textGluing')}, which gives '${fact.text}'`;
    }
  }
}

/** A parameter declared as `name="$X"` (core/semantics/esminiValues.ts reads it as esmini does). */
export function dollarDeclarationWording(name: string): ProblemWording<'lenient-value'> {
  return {
    severity: 'warning',
    code: 'lenient-value',
    message: `the standard declares a parameter by its name without '$' ('${name}'); ${esminiRule('declarationName')}, so this declares '${name}'`,
    hint: `write name="${name}"`,
  };
}

/** The hint of a lenient form whose standard form is written where it stands. */
export function writeStandardHint(text: string): string {
  return `write '${text}'`;
}

/** The hint of a string parameter read as a number or boolean, and the note at its parameterType, where the standard form is written. */
export function retypeWords(type: string): { hint: string; note: string } {
  return { hint: `declare it parameterType="${type}"`, note: `write '${type}' here` };
}

/**
 * A form esmini accepts that the standard does not (SPEC 12): its fix writes the standard's form where the
 * diagnostic is (`$` before a bare parameter, `-5` for `-5.0`, a name without `$`, glued text as a literal),
 * or at its related place in the same document (the parameterType of a string parameter read as a number).
 */
export const LENIENT_VALUE = defineDiagnostic({
  code: 'lenient-value',
  rule: { description: "A value is written in the standard's form, not only in a form esmini also accepts (SPEC 12)." },
  severity: 'warning',
  isData: (value): value is ProblemDataByCode['lenient-value'] => isSuggestion(value) || isRelatedReplacement(value),
  fixes: ({ data, range, related }) => {
    if (data && 'suggestion' in data)
      return [
        {
          title: `Write the standard form '${data.suggestion}'`,
          edits: [{ place: 'document', range, newText: data.suggestion }],
          preferred: true,
        },
      ];
    if (!data || !('relatedReplacement' in data) || !related?.sameDocument) return [];
    return [
      {
        title: `Declare the parameter parameterType="${data.relatedReplacement}"`,
        edits: [{ place: 'document', range: related.range, newText: data.relatedReplacement }],
        preferred: true,
      },
    ];
  },
});
