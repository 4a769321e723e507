import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { closingTagFor } from '../../client/src/tagClosing';
import { repoRoot } from '../support/paths';

interface AutoClosingPair {
  open: string;
  close: string;
}

const languageConfiguration = JSON.parse(fs.readFileSync(path.join(repoRoot, 'language-configuration.json'), 'utf8')) as {
  autoClosingPairs: AutoClosingPair[];
};

/**
 * Types `keys` one by one into an empty line as VS Code does with this extension: an auto-closing
 * pair's close is inserted when its open is completed, a typed single character steps over the same
 * auto-inserted one, and a typed `>` gets the closing tag closingTagFor names.
 */
function type(keys: string): string {
  let before = '';
  let after = '';
  for (const key of keys) {
    if (after.startsWith(key) && languageConfiguration.autoClosingPairs.some((pair) => pair.close === key)) {
      before += key;
      after = after.slice(1);
      continue;
    }
    before += key;
    const pair = languageConfiguration.autoClosingPairs.find((candidate) => before.endsWith(candidate.open));
    if (pair) after = pair.close + after;
    if (key === '>') after = (closingTagFor(before, after) ?? '') + after;
  }
  return before + after;
}

describe('client: closing tags as the user types', () => {
  it('closes an opening tag, with or without attributes', () => {
    assert.equal(closingTagFor('    <ScenarioReference scenarioFileName="a.xosc">', ''), '</ScenarioReference>');
    assert.equal(closingTagFor('<Actors>', '  '), '</Actors>');
    assert.equal(closingTagFor('<ns:Tag a="1" b=\'2\'>', ''), '</ns:Tag>');
  });

  it('leaves empty elements, closing tags, comments and declarations alone', () => {
    for (const before of [
      '<EntityRef entityRef="ego"/>',
      '</Actors>',
      '<!-- note -->',
      '<?xml version="1.0"?>',
      'text >',
      '<!DOCTYPE x>',
    ]) {
      assert.equal(closingTagFor(before, ''), undefined, before);
    }
  });

  it('typing a whole comment gives that comment, with no second -->', () => {
    assert.equal(type('<!-- x -->'), '<!-- x -->');
    assert.equal(type('<Actors>'), '<Actors></Actors>');
    assert.equal(type('<Rule expression="a">'), '<Rule expression="a"></Rule>');
  });

  it('does not close a tag typed inside a comment, on its line or lines below', () => {
    assert.equal(closingTagFor('<!-- <Actors>', ''), undefined);
    assert.equal(closingTagFor('<!--\n  <Actors>', ''), undefined);
    assert.equal(closingTagFor('<!-- note -->\n  <Actors>', ''), '</Actors>');
    assert.equal(closingTagFor('<Rule\n    expression="a">', ''), '</Rule>');
  });

  it('does not close when the > is inside an attribute value or the tag is already closed', () => {
    assert.equal(closingTagFor('<Rule expression="a >', ''), undefined);
    assert.equal(closingTagFor('<Actors>', '</Actors>'), undefined);
  });
});
