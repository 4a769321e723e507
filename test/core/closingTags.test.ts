import { strict as assert } from 'node:assert';
import { nodeFromXml } from '../../server/src/core/export/tree';
import { findGroup, parseScenario } from '../../server/src/core/model';
import { readOccurrence } from '../../server/src/core/modularize/shape';
import { parseXml } from '../../server/src/core/xml';

// An element's own text ends at its own end tag, also when its parent's end tag follows with no space between.
describe('closing tags: an element followed at once by its parent’s end tag', () => {
  it('nodeFromXml gives an empty element no text, and a text element only its own text', () => {
    const document = parseXml('<P><X></X></P>');
    const empty = nodeFromXml(
      document,
      document.root!,
      () => undefined,
      (element, index) => element.attributes[index].value,
    );
    assert.equal(empty.children[0].text, undefined);
    const withText = parseXml('<P><X>abc</X></P>');
    const node = nodeFromXml(
      withText,
      withText.root!,
      () => undefined,
      (element, index) => element.attributes[index].value,
    );
    assert.equal(node.children[0].text, 'abc');
  });

  it('modularize reads one shape from a group written compactly and the same group written with line breaks', () => {
    const group = (compact: boolean): string => {
      const parts = [
        '<ManeuverGroup name="G" maximumExecutionCount="1">',
        '<Actors selectTriggeringEntities="false"><EntityRef entityRef="car"/></Actors>',
        '<Maneuver name="M"></Maneuver>',
        '</ManeuverGroup>',
      ];
      return parts.join(compact ? '' : '\n');
    };
    const shapeOf = (compact: boolean): string => {
      const text = `<OpenSCENARIO><Storyboard><Story name="S"><Act name="A">${group(compact)}</Act></Story></Storyboard></OpenSCENARIO>`;
      const model = parseScenario(text);
      const found = findGroup(model, 'G');
      assert.ok(found, 'the group is found');
      const read = readOccurrence(0, model.document, found);
      assert.ok(read, 'the group can be imported');
      return read.shape.key;
    };
    assert.equal(shapeOf(true), shapeOf(false));
    assert.doesNotMatch(shapeOf(true), /<\//);
  });
});
