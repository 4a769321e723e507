import * as assert from 'node:assert/strict';
import { closingTagFor } from '../../client/src/tagClosing';

describe('client: closing tags as the user types', () => {
  it('closes an opening tag, with or without attributes', () => {
    assert.equal(closingTagFor('    <ScenarioReference scenarioFileName="a.xosc">', ''), '</ScenarioReference>');
    assert.equal(closingTagFor('<Actors>', '  '), '</Actors>');
    assert.equal(closingTagFor('<ns:Tag a="1" b=\'2\'>', ''), '</ns:Tag>');
  });

  it('leaves empty elements, closing tags, comments and declarations alone', () => {
    for (const before of ['<EntityRef entityRef="ego"/>', '</Actors>', '<!-- note -->', '<?xml version="1.0"?>', 'text >', '<!DOCTYPE x>']) {
      assert.equal(closingTagFor(before, ''), undefined, before);
    }
  });

  it('does not close when the > is inside an attribute value or the tag is already closed', () => {
    assert.equal(closingTagFor('<Rule expression="a >', ''), undefined);
    assert.equal(closingTagFor('<Actors>', '</Actors>'), undefined);
  });
});
