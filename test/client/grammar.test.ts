import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';

const GRAMMAR = path.resolve(__dirname, '..', '..', 'syntaxes', 'xosc.tmLanguage.json');

function scopeNames(node: unknown): string[] {
  if (Array.isArray(node)) return node.flatMap(scopeNames);
  if (typeof node !== 'object' || node === null) return [];
  return Object.entries(node).flatMap(([key, value]) => (key === 'name' && typeof value === 'string' ? [value] : scopeNames(value)));
}

describe('client: the xosc grammar', () => {
  it('underlines nothing: themes draw markup.underline through the text, hiding the underscores of file names', () => {
    const names = scopeNames(JSON.parse(fs.readFileSync(GRAMMAR, 'utf8')));
    assert.ok(names.some((name) => name.includes('reference.file.modular2simple')), 'the reference value scope is gone');
    assert.deepEqual(names.filter((name) => /\bmarkup\.underline\b/.test(name)), []);
  });
});
