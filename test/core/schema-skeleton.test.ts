import * as assert from 'node:assert/strict';
import { schemaIndex } from '../../server/src/core/schema/index';
import { ElementParticle, SCHEMA_VERSIONS } from '../../server/src/core/schema/model';
import { elementSkeleton, placeholderValue, SkeletonElement, SKELETON_DEPTH, skeletonText } from '../../server/src/core/schema/skeleton';
import { schemaFindingWords } from '../../server/src/core/diagnostics/schemaFindings';
import { checkSchema } from '../../server/src/core/schema/validate';
import { parseXml } from '../../server/src/core/xml';

function depthOf(element: SkeletonElement): number {
  return 1 + Math.max(0, ...element.children.map(depthOf));
}

describe('core: minimal valid skeletons of schema elements (what the quick fix inserts)', () => {
  it('the root element of each version, as a skeleton, validates without any finding', () => {
    for (const version of SCHEMA_VERSIONS) {
      const index = schemaIndex(version);
      const root: ElementParticle = { kind: 'element', name: index.schema.rootElement, type: index.schema.rootType, min: 1, max: 1 };
      const text = skeletonText(elementSkeleton(index, root), { indent: '', unit: '  ', eol: '\n' }, (declaration) =>
        placeholderValue(index, declaration.type),
      );
      // The placeholder header states 0.0; the file must state its own version to be read against it.
      const stated = text.replace('revMajor="0" revMinor="0"', `revMajor="1" revMinor="${version.split('.')[1]}"`);
      assert.notEqual(stated, text, version);
      const findings = checkSchema(parseXml(stated), { modular: true }).findings;
      assert.deepEqual(
        findings.map((finding) => `${finding.code} ${schemaFindingWords(finding).message}`),
        [],
        `${version}:\n${stated}`,
      );
      assert.match(stated, /<Storyboard>\n {4}<Init>\n {6}<Actions\/>\n {4}<\/Init>/, version);
    }
  });

  it('every element of every version gets a skeleton whose children its content model accepts, within the depth bound', () => {
    let checked = 0;
    let cut = 0;
    for (const version of SCHEMA_VERSIONS) {
      const index = schemaIndex(version);
      const verify = (element: SkeletonElement, level: number, open: Set<string>) => {
        const type = index.complexType(element.type);
        const required = (type?.attributes ?? []).filter((declaration) => declaration.required).map((declaration) => declaration.name);
        assert.deepEqual(
          element.attributes.map((declaration) => declaration.name),
          required,
          `${version} <${element.name}>`,
        );
        if (!type?.content || type.content.kind === 'all') return;
        if (level >= SKELETON_DEPTH || open.has(element.type)) {
          assert.deepEqual(element.children, [], `${version} <${element.name}> is cut at depth ${level}`);
          cut++;
          return;
        }
        const automaton = index.automaton(element.type);
        let states = automaton.start;
        for (const child of element.children) {
          const next = automaton.step(states, child.name);
          assert.ok(next, `${version} <${element.name}> does not accept <${child.name}> here`);
          states = next.states;
        }
        assert.ok(
          automaton.accepts(states),
          `${version} <${element.name}> is incomplete with ${element.children.map((child) => child.name).join(', ')}`,
        );
        checked++;
        const inside = new Set(open).add(element.type);
        for (const child of element.children) verify(child, level + 1, inside);
      };
      for (const typeName of Object.keys(index.schema.complexTypes)) {
        for (const particle of index.childParticles(typeName)) {
          const skeleton = elementSkeleton(index, particle);
          assert.ok(depthOf(skeleton) <= SKELETON_DEPTH, `${version} <${particle.name}>`);
          verify(skeleton, 1, new Set());
        }
      }
    }
    assert.ok(checked > 500, `only ${checked} elements checked`);
    // Deep content (Story, Vehicle, conditions) reaches the bound somewhere: the cut is exercised, not assumed.
    assert.ok(cut > 0, 'no skeleton reached the depth bound');
  });

  it('a depth bound of 1 writes the element alone; on one line when no line break is given', () => {
    const index = schemaIndex('1.0');
    const story = index.childParticle('Storyboard', 'Story', false) as ElementParticle;
    assert.deepEqual(elementSkeleton(index, story, 1).children, []);
    const oneLine = skeletonText(elementSkeleton(index, story), { indent: '    ', unit: '  ', eol: '' }, (declaration) =>
      placeholderValue(index, declaration.type),
    );
    assert.equal(
      oneLine,
      '<Story name=""><Act name=""><ManeuverGroup maximumExecutionCount="0" name=""><Actors selectTriggeringEntities="false"/></ManeuverGroup><StartTrigger/></Act></Story>',
    );
  });
});
