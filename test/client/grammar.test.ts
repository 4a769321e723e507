import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';

interface Rule {
  match?: string;
  begin?: string;
  end?: string;
  name?: string;
  include?: string;
  patterns?: Rule[];
}

const grammar = JSON.parse(fs.readFileSync(path.resolve(__dirname, '..', '..', 'syntaxes', 'xosc.tmLanguage.json'), 'utf8')) as {
  repository: Record<string, Rule>;
};

/**
 * The scopes a list of match rules gives a text, as TextMate scans: at each position the first rule
 * that matches there wins (the grammar's regular expressions here are also valid JavaScript ones).
 */
function scan(text: string, rules: Rule[]): string[] {
  const tokens: string[] = [];
  for (let at = 0; at < text.length;) {
    const hit = rules
      .map((rule) => ({ rule, found: new RegExp(rule.match as string, 'y') }))
      .find(({ found }) => {
        found.lastIndex = at;
        return found.test(text);
      });
    if (!hit) {
      at++;
      continue;
    }
    tokens.push(`${text.slice(at, hit.found.lastIndex)} ${hit.rule.name}`);
    at = hit.found.lastIndex;
  }
  return tokens;
}

describe('TextMate grammar: $name and ${...} inside attribute values', () => {
  const [expression, parameter] = grammar.repository['parameter-value'].patterns as Rule[];

  it('is included in every quoted attribute value', () => {
    for (const quoted of grammar.repository['generic-string'].patterns as Rule[])
      assert.equal(quoted.patterns?.[0].include, '#parameter-value');
  });

  it('scopes a ${...} from its opening to its closing brace, or to the closing quote when unfinished', () => {
    assert.ok(new RegExp(expression.begin as string).test('${'));
    assert.deepEqual(new RegExp(expression.end as string).exec('}')?.[1], '}');
    assert.equal(new RegExp(expression.end as string).exec('2 + "')?.index, 4);
  });

  it('tells parameters, functions, operators and numbers apart inside an expression', () => {
    assert.deepEqual(scan('2*$a/round($b) - 1.5e3 and not $c', expression.patterns as Rule[]), [
      '2 constant.numeric.xosc',
      '* keyword.operator.arithmetic.xosc',
      '$a variable.other.parameter.xosc',
      '/ keyword.operator.arithmetic.xosc',
      'round support.function.math.xosc',
      '( punctuation.section.expression.xosc',
      '$b variable.other.parameter.xosc',
      ') punctuation.section.expression.xosc',
      '- keyword.operator.arithmetic.xosc',
      '1.5e3 constant.numeric.xosc',
      'and keyword.operator.logical.xosc',
      'not keyword.operator.logical.xosc',
      '$c variable.other.parameter.xosc',
    ]);
  });

  it('scopes a whole-value $name, and leaves a digit inside a name alone', () => {
    assert.deepEqual(scan('$Ego_2', [parameter]), ['$Ego_2 variable.other.parameter.xosc']);
    assert.deepEqual(scan('$P1 + 2', expression.patterns as Rule[]), [
      '$P1 variable.other.parameter.xosc',
      '+ keyword.operator.arithmetic.xosc',
      '2 constant.numeric.xosc',
    ]);
  });
});

function scopeNames(node: unknown): string[] {
  if (Array.isArray(node)) return node.flatMap(scopeNames);
  if (typeof node !== 'object' || node === null) return [];
  return Object.entries(node).flatMap(([key, value]) => (key === 'name' && typeof value === 'string' ? [value] : scopeNames(value)));
}

describe('client: the xosc grammar', () => {
  it('underlines nothing: themes draw markup.underline through the text, hiding the underscores of file names', () => {
    const names = scopeNames(grammar);
    assert.ok(
      names.some((name) => name.includes('reference.file.modular2simple')),
      'the reference value scope is gone',
    );
    assert.deepEqual(
      names.filter((name) => /\bmarkup\.underline\b/.test(name)),
      [],
    );
  });
});
